"""Implicit bodies: R-function models and expressions, values and gradients on arrays, Python
callables as bodies, Monte Carlo volumes."""
import numpy as np
import pytest

import interlin
from interlin import rf


def test_model_value_matches_cli_digest(data_dir):
    F = interlin.load_model(data_dir + "/models/impeller.rf")
    v = F(np.array([[10.0, 0, 2], [0.5, 0, 2]]))
    # interlin eval prints 0.2023382447274798 and -0.39147877575995371 (digest 000 T18)
    assert v[0] == pytest.approx(0.2023382447274798, abs=1e-15)
    assert v[1] == pytest.approx(-0.39147877575995371, abs=1e-15)
    assert F.box.shape == (2, 3)


def test_model_gradient_against_differences(data_dir):
    F = interlin.load_model(data_dir + "/models/car.rf", parameters={"y2": 14.0}, output="fig5")
    rng = np.random.default_rng(0)
    lo, hi = F.box
    P = rng.uniform(lo, hi, (200, 3))
    v, G = F.gradient(P)
    assert np.array_equal(v, F.value(P))
    h = 1e-6
    for a in range(3):
        e = np.zeros(3)
        e[a] = h
        fd = (F(P + e) - F(P - e)) / (2 * h)
        ok = np.abs(G[:, a] - fd) < 1e-5 * (1 + np.abs(fd))  # kinks of R-functions aside
        assert ok.mean() > 0.97


def test_large_arrays_are_evaluated_in_blocks():
    ball = rf.compile(rf.sphere(rf.x, rf.y, rf.z, 2.0), [[-3, -3, -3], [3, 3, 3]])
    P = np.random.default_rng(1).normal(size=(10001, 3))  # more than two blocks of 4096
    r2 = np.sum(P ** 2, axis=1)
    assert np.max(np.abs(ball(P) - (4 - r2) / 4)) < 1e-14
    F, G = ball.gradient(P)
    assert np.max(np.abs(G + P / 2)) < 1e-14


def test_expression_language():
    e = rf.and0(rf.sphere(rf.x, rf.y, rf.z, 1.0), -rf.cylinder(rf.x, rf.y, rf.z, 0.5, 2.0))
    body = rf.compile(e, [[-1.5] * 3, [1.5] * 3])
    inside = body(np.array([[0.75, 0, 0], [0, 0, 0]]))
    assert inside[0] > 0 > inside[1]
    assert (2 * rf.x + 1).is_constant is False and rf.Expr(3).value == 3
    d = rf.derivative(rf.x ** 3, 0)
    F = rf.compile(d, [[-1] * 3, [1] * 3])
    assert F(np.array([[2.0, 0, 0]]))[0] == pytest.approx(12, rel=1e-14)


def test_model_errors_are_cli_lines(tmp_path):
    from conftest import cli_error, write_text
    bad = write_text(tmp_path / "bad.rf", "box(-1, -1, -1, 1, 1, 1);\nres = 1 - x*x +;\n")
    pts = write_text(tmp_path / "p.csv", "x,y,z\n0,0,0\n")
    message, status = cli_error("eval", bad, pts)
    assert status == 1
    with pytest.raises(interlin.InputError) as e:
        interlin.load_model(bad)
    assert str(e.value) == message


def test_python_callable_body_meshes_on_worker_threads():
    # The meshing threads call back into Python: this only finishes if the GIL is released.
    body = interlin.Implicit(lambda P: 1.0 - np.sum(P ** 2, axis=1), box=[[-1.2] * 3, [1.2] * 3])
    V, F = interlin.mesh_implicit(body, resolution=24, threads=2)
    r = interlin.check_mesh(V, F)
    assert r["watertight"] and r["volume"] == pytest.approx(4 / 3 * np.pi, rel=0.02)


def test_monte_carlo_volume_of_a_ball():
    ball = rf.compile(rf.sphere(rf.x, rf.y, rf.z, 1.0), [[-1.1] * 3, [1.1] * 3])
    v, se, n = interlin.estimate_volume(ball, 0.05, seed=3, threads=2)
    assert abs(v - 4 / 3 * np.pi) < 5 * se and n > 10000
