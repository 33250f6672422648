"""Point clouds -> implicit models from Python, as `interlin implicit SCAN`: the partition-of-unity
implicit (kind cloud_pu), the Hermite RBF of sparse clouds (cloud_hrbf) and sectioned scans (fitted sections -> section body); cloud .ifl files
written by the CLI load with load_model (registered at import) and evaluate as `interlin eval`."""
import os
import subprocess

import numpy as np
import pytest

import interlin
from conftest import body_point

RNG = np.random.default_rng(31)


def sphere_cloud(n, sigma):
    """n points on the unit sphere (Fibonacci spiral) with normal noise sigma, exact normals."""
    i = np.arange(n) + 0.5
    z = 1 - 2 * i / n
    t = np.pi * (1 + 5 ** 0.5) * i
    N = np.stack([np.sqrt(1 - z * z) * np.cos(t), np.sqrt(1 - z * z) * np.sin(t), z], axis=1)
    return N * (1 + sigma * RNG.normal(size=(n, 1))), N


def cli(*args):
    r = subprocess.run([os.environ["INTERLIN_CLI"], *args], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return r.stdout


@pytest.fixture(scope="module")
def scan(tmp_path_factory):
    """A noisy sphere scan (.xyzn with normals) and the .ifl `interlin implicit` made of it."""
    d = tmp_path_factory.mktemp("cloud")
    P, N = sphere_cloud(2500, 0.002)
    path = str(d / "sphere.xyzn")
    np.savetxt(path, np.hstack([P, N]), fmt="%.17g")
    ifl = str(d / "sphere.ifl")
    summary = cli("implicit", path, "-o", ifl, "--slices", "none", "--threads", "1", "-q")
    return path, ifl, d, summary


def test_cli_cloud_ifl_loads_and_evaluates_as_interlin_eval(scan):
    path, ifl, d, _ = scan
    assert "cloud_pu" in interlin.ifl_kinds()
    F = interlin.load_model(ifl)
    P = RNG.uniform(-1.3, 1.3, (200, 3))
    points = str(d / "points.csv")
    np.savetxt(points, P, fmt="%.17g", delimiter=",", header="x,y,z", comments="")
    table = np.loadtxt(cli("eval", ifl, points, "-q").splitlines()[1:], delimiter=",")
    # The CLI prints 17 significant digits of the same evaluation: equal to 1 ulp of |F| <= 2.
    assert np.max(np.abs(F(P) - table[:, 3])) <= 4.5e-16
    assert np.array_equal(table[:, :3], P)


def test_implicit_of_a_cloud_file_is_the_clis_model(scan):
    path, ifl, d, summary = scan
    M = interlin.implicit(path, slices="none", threads=1)
    assert M.kind == "cloud_pu" and M.grid_shape is None and M.band is None
    # The noise's tail loses a few points to the statistical outlier filter (as in the CLI).
    assert M.report["read"] == 2500 and M.report["kept"] > 2450
    assert not M.report["normals_estimated"]
    assert M.report["within_3_sigma"] > 0.95
    # The octree counts are the CLI summary's: "N leaves (T with two sheets, F far ..., S re-signed
    # ..., E negated ...".
    octree = next(l for l in summary.splitlines() if l.strip().startswith("octree"))
    counts = [int(w) for w in octree.replace("(", " ").replace(",", " ").split() if w.isdigit()]
    assert counts[:5] == [M.report[k] for k in ("leaves", "two_sheet_leaves", "far_leaves",
                                                "sign_fixed_leaves", "exterior_negated_leaves")]
    assert M.report["patches_flipped"] == 0  # the file's normals agree: no re-orientation
    P = RNG.uniform(-1.3, 1.3, (300, 3))
    # The fit is deterministic (threads do not change it): the CLI's model, value for value.
    assert np.array_equal(M(P), interlin.load_model(ifl)(P))
    again = str(d / "again.ifl")
    M.write(again)
    assert np.array_equal(interlin.load_model(again)(P), M(P))
    # Near the sphere F is the signed distance to within the noise (sigma 0.002, 5 sigma).
    u = RNG.normal(size=(300, 3))
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    r = RNG.uniform(0.95, 1.05, (300, 1))
    F, G = M.gradient(u * r)
    assert np.max(np.abs(F - (1 - r[:, 0]))) < 0.01
    assert np.min(np.sum(-G * u, axis=1) / np.linalg.norm(G, axis=1)) > 0.9


def test_implicit_of_a_point_cloud_object():
    P, N = sphere_cloud(1500, 0.0)
    M = interlin.implicit(interlin.PointCloud(P, N), slices="none", threads=1)
    assert M.kind == "cloud_pu"
    assert M(np.array([[0.0, 0, 0], [2, 0, 0]])).tolist() == pytest.approx([1, -1], abs=0.05)
    with pytest.raises(interlin.InputError, match=r"<cloud>: .*no planar slices"):
        interlin.implicit(interlin.PointCloud(P, N), slices="planar")
    with pytest.raises(ValueError, match="slices"):
        interlin.implicit(interlin.PointCloud(P, N), slices="diagonal")
    with pytest.raises(ValueError, match="input 'scan.foo': unknown kind"):
        interlin.implicit("scan.foo")


def test_sparse_cloud_with_normals_gets_the_hermite_rbf_as_the_cli(tmp_path):
    # 300 points with their normals: the hold-out prefers the Hermite RBF (kind cloud_hrbf), as
    # `interlin implicit` does; the interpolant is 0 at every point (to round-off) and the model
    # written by the CLI evaluates to the same doubles.
    P, N = sphere_cloud(300, 0.0)
    path = str(tmp_path / "sparse.xyzn")
    np.savetxt(path, np.hstack([P, N]), fmt="%.17g")
    M = interlin.implicit(path, threads=1)
    assert M.kind == "cloud_hrbf" and M.report["fit"] == "hrbf"
    assert M.report["holdout_hrbf"] < 0.2 * M.report["holdout_pu"]
    assert np.max(np.abs(M(P))) < 1e-9
    ifl = str(tmp_path / "sparse.ifl")
    assert "-> Hermite RBF" in cli("implicit", path, "-o", ifl, "--threads", "1", "-q")
    Q = RNG.uniform(-1.3, 1.3, (200, 3))
    assert np.array_equal(M(Q), interlin.load_model(ifl)(Q))
    pu = interlin.implicit(path, threads=1, fit="pu")
    assert pu.kind == "cloud_pu" and pu.report["fit"] == "pu" and "holdout_pu" not in pu.report
    with pytest.raises(ValueError, match="fit"):
        interlin.implicit(path, fit="rbf")


def test_sectioned_scan_becomes_the_clis_section_body(tmp_path):
    # Slices of the twisted elliptic body at 8 heights, 300 points each, no noise: detected as
    # planar slices, fitted and lofted as `interlin implicit` does, value for value.
    zs = np.linspace(-1, 1, 8)
    P = np.vstack([body_point(2 * np.pi * RNG.uniform(0, 1, 300), z) for z in zs])
    path, ifl = str(tmp_path / "slices.xyz"), str(tmp_path / "slices.ifl")
    np.savetxt(path, P, fmt="%.17g")
    M = interlin.implicit(path, resolution=16, threads=1)
    assert M.kind == "section_body" and M.report["slices"] == "planar"
    assert np.allclose(np.abs(M.report["stations"]), np.abs(zs), atol=1e-9)
    cli("implicit", path, "-o", ifl, "--resolution", "16", "--threads", "1", "-q")
    Q = RNG.uniform(-2.5, 2.5, (300, 3))
    assert np.array_equal(M(Q), interlin.load_model(ifl)(Q))
    # omega vanishes on the fitted sections; the scan points are off them by the fit's residual
    # (closed cubics, measured 4.2e-3 at most on the 4.6-unit wide body).
    assert np.max(np.abs(M(P))) < 0.01 and M(np.array([[0.0, 0, 0]]))[0] > 0.3


def test_sectioned_scan_span_smoothing_is_the_clis(tmp_path):
    # span_smoothing="off" fits each section alone (report span_control 0), as the CLI's
    # --span-smoothing off, value for value; a bad choice is a ValueError.
    zs = np.linspace(-1, 1, 8)
    P = np.vstack([body_point(2 * np.pi * RNG.uniform(0, 1, 300), z) for z in zs])
    path, ifl = str(tmp_path / "slices.xyz"), str(tmp_path / "alone.ifl")
    np.savetxt(path, P, fmt="%.17g")
    M = interlin.implicit(path, resolution=16, threads=1, span_smoothing="off")
    assert M.report["span_control"] == 0
    cli("implicit", path, "-o", ifl, "--resolution", "16", "--threads", "1", "-q",
        "--span-smoothing", "off")
    Q = RNG.uniform(-2.5, 2.5, (300, 3))
    assert np.array_equal(M(Q), interlin.load_model(ifl)(Q))
    with pytest.raises(ValueError, match="span_smoothing"):
        interlin.implicit(path, resolution=16, span_smoothing="always")
