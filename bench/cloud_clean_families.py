#!/usr/bin/python3
"""Points per fit on clean and slightly noisy clouds of exact shapes (issue 11,
docs/benchmarks.md "Ten points per fit on clean clouds").

Usage: PYTHONPATH=build/python /usr/bin/python3 bench/cloud_clean_families.py \
           [SHAPES [COUNTS [RHOS]]]
       defaults: sphere,torus,cylinder,ellipsoid 3000,12000,50000 0,0.001,0.0015

Each cloud: COUNT area-uniform points (seed 1) with exact normals, noise rho x spacing along the
normal (spacing = sqrt(area / COUNT)). fit_cloud_implicit with min_points=20 against the default
(automatic), meshed by mesh_implicit at the default cell. Distance of the zero set to the truth:
the exact distance at the mesh vertices and |F| / |grad F| at 100,000 exact surface points; the
Chamfer column is the mean of the two means, H the larger maximum, both in spacings. Shapes:
sphere r = 1; torus 1, 0.35; cylinder radius 0.6, height 1.6 (sharp rims); ellipsoid 1, 0.6, 0.3
(its distance to first order).
"""
import sys

import numpy as np

import interlin as il

AREA = {"sphere": 4 * np.pi, "ellipsoid": 4.4, "torus": 4 * np.pi**2 * 0.35,
        "cylinder": 2 * np.pi * 0.6 * 1.6 + 2 * np.pi * 0.36}
AXES = np.array([1, 0.6, 0.3])  # the ellipsoid's


def draw(shape, m, rng):
    """About m candidate points and normals of `shape` (rejection keeps the density uniform)."""
    if shape == "sphere":
        p = rng.normal(size=(m, 3))
        p /= np.linalg.norm(p, axis=1)[:, None]
        return p, p.copy()
    if shape == "ellipsoid":
        u = rng.normal(size=(m, 3))
        u /= np.linalg.norm(u, axis=1)[:, None]
        p = u * AXES
        g = p / AXES**2
        w = np.linalg.norm(g, axis=1)  # area element of the map from the sphere, up to a factor
        keep = rng.uniform(size=m) < w / w.max()
        return p[keep], (g / w[:, None])[keep]
    if shape == "torus":
        th, ph = rng.uniform(0, 2 * np.pi, m), rng.uniform(0, 2 * np.pi, m)
        keep = rng.uniform(size=m) < (1 + 0.35 * np.cos(ph)) / 1.35
        th, ph = th[keep], ph[keep]
        n = np.c_[np.cos(ph) * np.cos(th), np.cos(ph) * np.sin(th), np.sin(ph)]
        return np.c_[np.cos(th), np.sin(th), 0 * th] + 0.35 * n, n
    a, h = 0.6, 0.8  # cylinder: side, top, bottom by area
    side, cap = 2 * np.pi * a * 2 * h, np.pi * a * a
    k = rng.choice(3, size=m, p=np.array([side, cap, cap]) / (side + 2 * cap))
    th, z, r = rng.uniform(0, 2 * np.pi, m), rng.uniform(-h, h, m), a * np.sqrt(rng.uniform(size=m))
    on_side = (k == 0)[:, None]
    p = np.where(on_side, np.c_[a * np.cos(th), a * np.sin(th), z],
                 np.c_[r * np.cos(th), r * np.sin(th), np.where(k == 1, h, -h)])
    n = np.where(on_side, np.c_[np.cos(th), np.sin(th), 0 * th],
                 np.c_[0 * th, 0 * th, np.where(k == 1, 1.0, -1.0)])
    return p, n


def sample(shape, n, rng):
    P, N = [], []
    while sum(len(p) for p in P) < n:
        p, q = draw(shape, 4 * n, rng)
        P.append(p)
        N.append(q)
    return np.vstack(P)[:n], np.vstack(N)[:n]


def distance(shape, X):
    if shape == "sphere":
        return np.abs(np.linalg.norm(X, axis=1) - 1)
    if shape == "torus":
        return np.abs(np.hypot(np.linalg.norm(X[:, :2], axis=1) - 1, X[:, 2]) - 0.35)
    if shape == "cylinder":
        q = np.c_[np.linalg.norm(X[:, :2], axis=1) - 0.6, np.abs(X[:, 2]) - 0.8]
        return np.abs(np.minimum(q.max(1), 0) + np.linalg.norm(np.maximum(q, 0), axis=1))
    f = (X**2 / AXES**2).sum(1) - 1
    return np.abs(f) / np.linalg.norm(2 * X / AXES**2, axis=1)


def measure(shape, n, rho, variants=({"min_points": 20}, {}), threads=2):
    """Per variant (fit_cloud_implicit's keyword options) of one noisy cloud: the Chamfer and H in
    spacings (mesh vertices and 100,000 exact points) and the fit's info."""
    rng = np.random.default_rng(1)
    P, N = sample(shape, n, rng)
    spacing = np.sqrt(AREA[shape] / n)
    cloud = il.PointCloud(P + rho * spacing * rng.normal(size=(n, 1)) * N, N)
    exact, _ = sample(shape, 100000, np.random.default_rng(99))
    row = []
    for options in variants:
        model = il.fit_cloud_implicit(cloud, threads=threads, **options)
        V, _ = il.mesh_implicit(model.function, threads=threads)
        d1 = distance(shape, V)
        F, G = model.function.gradient(exact)
        d2 = np.abs(F) / np.maximum(np.linalg.norm(G, axis=1), 1e-12)
        row.append((0.5 * (d1.mean() + d2.mean()) / spacing, max(d1.max(), d2.max()) / spacing,
                    model.info))
    return row


def family(argv, rhos):
    """SHAPES COUNTS RHOS from the command line (comma-separated), defaulting to the four
    shapes, 3000,12000,50000 points and `rhos`."""
    shapes = (argv[0] if argv else "sphere,torus,cylinder,ellipsoid").split(",")
    counts = [int(x) for x in (argv[1] if len(argv) > 1 else "3000,12000,50000").split(",")]
    rhos = [float(x) for x in (argv[2] if len(argv) > 2 else rhos).split(",")]
    return shapes, counts, rhos


def main(argv):
    shapes, counts, rhos = family(argv, "0,0.001,0.0015")
    print("| shape | points | rho (estimated) | 20 points: Chamfer, H | automatic: points, "
          "Chamfer, H | ratio |")
    print("|---|---|---|---|---|---|")
    for shape in shapes:
        for n in counts:
            for rho in rhos:
                (c0, h0, i0), (c1, h1, i1) = measure(shape, n, rho)
                est, k = i0["scan_noise"] / i0["spacing"], i1["min_points"]
                print(f"| {shape} | {n} | {rho} ({est:.4f}) | {c0:.4f}, {h0:.2f} | {k}, {c1:.4f}, "
                      f"{h1:.2f} | {c1 / c0:.2f} |", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
