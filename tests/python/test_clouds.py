"""Point clouds from Python: files, PCL filters and normals, orientation, noise, the
partition-of-unity implicit, and bad input reported with the reader's one-line messages."""
import numpy as np
import pytest

import interlin


def sphere_cloud(n, sigma, rng):
    """n points on the unit sphere (Fibonacci spiral) with normal noise sigma, exact normals."""
    i = np.arange(n) + 0.5
    z = 1 - 2 * i / n
    t = np.pi * (1 + 5 ** 0.5) * i
    N = np.stack([np.sqrt(1 - z * z) * np.cos(t), np.sqrt(1 - z * z) * np.sin(t), z], axis=1)
    return N * (1 + sigma * rng.normal(size=(n, 1))), N


def test_read_bunny_and_estimate_normals(data_dir):
    c, notes = interlin.read_point_cloud(data_dir + "/clouds/bun0.pcd", with_notes=True)
    assert c.points.shape == (397, 3) and c.has_normals and len(c) == 397
    N = interlin.estimate_normals(c.points, k=16, threads=1)
    assert N.shape == (397, 3) and np.allclose(np.linalg.norm(N, axis=1), 1)


def test_orientation_and_noise_on_spheres():
    rng = np.random.default_rng(2)
    for sigma in (0.0, 0.002, 0.01):
        P, exact = sphere_cloud(2000, sigma, rng)
        N = interlin.estimate_normals(P, k=16, threads=1)
        O, components, flipped = interlin.orient_normals(P, N, k=10)
        assert components == 1 and np.all(np.sum(O * exact, axis=1) > 0)
        assert interlin.orientation_disagreement(P, O, 10) < 0.01
        # estimate_noise: about sigma (relative 30 %) above the quadric error of clean points
        est = interlin.estimate_noise(P)
        assert est < 1e-3 if sigma == 0 else abs(est / sigma - 1) < 0.3


def test_sheet_normals_across_a_narrow_gap():
    # two unit squares 1.5 spacings apart (a slab seen from outside): PCA of 16 neighbours
    # straddles the gap, the sheet normals keep to one square (test_sheet_normals.cpp)
    rng = np.random.default_rng(5)
    n = 4000
    P = np.column_stack([rng.random((2 * n, 2)), np.repeat([0.0, 1.5 / np.sqrt(n)], n)])
    true = np.repeat([[0, 0, -1.0], [0, 0, 1.0]], n, axis=0)
    # one square is clean; two within every neighbourhood read as noise (the quadrics straddle
    # the gap), so prepare_cloud's automatic choice keeps PCA there, and "on" takes sheets 3
    # such sigmas thick: PCA's normals again (prepare_cloud on a clean cube: test_sheet_normals)
    assert interlin.is_clean_scan(P[:n]) and not interlin.is_clean_scan(P)
    assert abs(interlin.median_point_spacing(P[:n]) * np.sqrt(n) - 1) < 0.1  # Poisson: 1 / sqrt(n)
    off = lambda N: np.mean(np.abs(np.sum(N * true, axis=1)) < np.cos(np.radians(20)))
    N = interlin.estimate_normals(P, 16, threads=1)
    S = interlin.estimate_sheet_normals(P, 16, 0.0, threads=1)
    assert off(N) > 0.3 and off(S) < 0.02
    signed = interlin.sign_sheet_normals(P, S, true, 0.0, threads=1)
    assert np.all(np.sum(signed * true, axis=1) > 0)
    _, report, _ = interlin.prepare_cloud(interlin.PointCloud(P), sheet_normals="on", threads=1)
    assert report["sheet_normals"]
    _, report, _ = interlin.prepare_cloud(interlin.PointCloud(P), threads=1)
    assert not report["sheet_normals"] and report["sheet_changed"] == 0
    with pytest.raises(ValueError):
        interlin.prepare_cloud(interlin.PointCloud(P), sheet_normals="maybe")


def test_fit_a_noisy_sphere_and_mesh_it():
    rng = np.random.default_rng(4)
    P, N = sphere_cloud(3000, 0.002, rng)
    cloud, report, notes = interlin.prepare_cloud(interlin.PointCloud(P, N), threads=1)
    assert report["kept"] == len(cloud) and cloud.has_normals
    model = interlin.fit_cloud_implicit(cloud, threads=1)
    F = model.function
    assert F(np.zeros((1, 3)))[0] > 0 > F(np.array([[2.0, 0, 0]]))[0]
    V, T = interlin.mesh_implicit(F, resolution=40, threads=1)
    r = np.linalg.norm(V, axis=1)
    assert interlin.check_mesh(V, T)["watertight"] and np.max(np.abs(r - 1)) < 0.01
    assert model.info["within_3_sigma"] > 0.95
    # the noise-aware neighbourhood's inputs: spacing sqrt(4 pi / 3000) = 0.065 (area per point,
    # 10 % for the points' uneven spread), scan noise sigma within 30 %, rho = 0.03 < 0.21: 20
    info = model.info
    assert abs(info["spacing"] / np.sqrt(4 * np.pi / 3000) - 1) < 0.1
    assert abs(info["scan_noise"] / 0.002 - 1) < 0.3
    assert info["min_points"] == 20 and info["acceptance"] == 1.0


def test_bad_cloud_files_raise_input_errors(tmp_path):
    bad = tmp_path / "bad.xyz"
    bad.write_text("0 0 0\n1 abc 0\n")
    with pytest.raises(interlin.InputError, match=r"bad.xyz:2: "):
        interlin.read_point_cloud(str(bad))
    flat = interlin.PointCloud(np.c_[np.random.default_rng(0).uniform(size=(50, 2)), np.zeros(50)])
    with pytest.raises(interlin.InputError, match="flat.csv: .*plane"):
        interlin.check_cloud(flat, "flat.csv")


def test_smooth_scan_points_and_the_fit_on_a_noisy_sphere():
    # smooth_scan_points.h: each point onto its quadric of up to 512 neighbours; on the unit
    # sphere (40,000 points, spacing 0.018, sigma 0.3 spacings) the rungs reach 512, whose plane
    # closed form is 2 sigma / sqrt(512) = 0.09 sigma; Lepski's default threshold (1.5) stops
    # early at false alarms: about twice that (test_smooth_scan_points.cpp)
    rng = np.random.default_rng(5)
    sigma = 0.005
    P, exact = sphere_cloud(40000, sigma, rng)
    Q, N, k = interlin.smooth_scan_points(P, exact, sigma, threads=1)
    before = np.sqrt(np.mean((np.linalg.norm(P, axis=1) - 1) ** 2))
    after = np.sqrt(np.mean((np.linalg.norm(Q, axis=1) - 1) ** 2))
    assert abs(before / sigma - 1) < 0.05 and after < 0.25 * sigma
    assert np.median(k) == 512 and np.allclose(np.linalg.norm(N, axis=1), 1)
    with pytest.raises(ValueError):
        interlin.smooth_scan_points(P, exact, 0.0)
    cloud = interlin.PointCloud(P, exact)
    on = interlin.fit_cloud_implicit(cloud, threads=1).info
    off = interlin.fit_cloud_implicit(cloud, smooth_points=False, threads=1).info
    assert on["smoothed_points"] == 40000 and on["smoothing_neighbours"] == 512
    assert abs(on["smoothing_noise"] / sigma - 1) < 0.3 and off["smoothed_points"] == 0
