"""Shared fixtures of the Python tests (run by CTest: tests/CMakeLists.txt sets PYTHONPATH to
build/python, INTERLIN_DATA_DIR and INTERLIN_CLI)."""
import os
import subprocess

import numpy as np
import pytest

DATA = os.environ.get("INTERLIN_DATA_DIR",
                      os.path.join(os.path.dirname(__file__), "..", "..", "data"))
ROTOR37 = os.path.join(DATA, "rotor37", "sections.csv")


@pytest.fixture
def data_dir():
    return DATA


def cli_error(*args):
    """The one error line `interlin ARGS` prints (without its "interlin: " prefix) and its exit
    status."""
    cli = os.environ["INTERLIN_CLI"]
    r = subprocess.run([cli, *args], capture_output=True, text=True)
    line = r.stderr.strip().splitlines()[-1]
    assert line.startswith("interlin: "), r.stderr
    return line[len("interlin: "):], r.returncode


def write_text(path, text):
    with open(path, "w") as f:
        f.write(text)
    return str(path)


def body_point(t, z):
    """A smooth twisted, tapering elliptic body (tests/support/test_sections.h): exact surface."""
    a = 2.0 + 0.3 * np.sin(z)
    b = 0.6 + 0.1 * z * z
    w = 0.4 * z
    x, y = a * np.cos(t), b * np.sin(t)
    return np.stack([x * np.cos(w) - y * np.sin(w), x * np.sin(w) + y * np.cos(w),
                     np.broadcast_to(z, np.shape(t))], axis=-1)


def body_sections(zs, n, rng):
    """Sections of body_point at heights zs, n points each: the first at angle 0 (the same
    feature on every section), the others at angles jittered by up to 0.3 of their spacing."""
    out = []
    for z in zs:
        jitter = rng.uniform(-0.3, 0.3, n)
        jitter[0] = 0
        out.append(body_point(2 * np.pi * (np.arange(n) + jitter) / n, z))
    return out

