#!/usr/bin/python3
"""Where prepare_cloud's normals point inward on the unstructured blade scans (issue 11,
docs/benchmarks.md "What limits the unstructured fit").

Usage: bench_clouds --cases blade,blade-noisy,blade-exact,blade-noisy-exact --methods none \
           --points 50000 --save DIR
       cloud_flipped_normals.py DIR

Each estimated-normal cloud is matched point by point with the same scan given the true normals
(prepare_cloud keeps points, it does not move them). A point's wall thickness is its distance to
the nearest lateral point whose true normal is opposite (n . n' < -0.5), the other side of the
blade; cap points are those whose true normal is within 18 degrees of a cap's (|n . a| > 0.95).
"""
import sys

import numpy as np
from scipy.spatial import cKDTree

THIN = 0.1  # cm: the other side within this distance is a thin edge
NEAR_CAP = 0.1  # cm: lateral points this close to a cap point are at a cap's rim
NEIGHBOURS = 64  # searched for the other side of the wall


def report(directory, sigma):
    name = f"{directory}/rotor37 50k sigma {sigma}"
    E = np.loadtxt(f"{name}.xyzn")
    X = np.loadtxt(f"{name} exact normals.xyzn")
    dist, row = cKDTree(X[:, :3]).query(E[:, :3])
    if dist.max() > 1e-9:
        sys.exit(f"{name}: the two clouds are not the same scan")
    true_n = X[row, 3:]
    inward = (E[:, 3:] * true_n).sum(1) < 0
    cap_all = np.abs(X[:, 3:] @ X[-1, 3:]) > 0.95  # sample_blade puts cap points last
    cap = cap_all[row]
    to_cap, _ = cKDTree(X[cap_all, :3]).query(E[:, :3])
    lateral = X[~cap_all]
    d, j = cKDTree(lateral[:, :3]).query(E[:, :3], k=NEIGHBOURS)
    opposite = (lateral[j, 3:] * true_n[:, None, :]).sum(2) < -0.5
    thickness = np.where(opposite, d, np.inf).min(1)
    print(f"sigma {sigma} cm: {len(E)} points, {inward.sum()} inward ({100 * inward.mean():.2f} %)")
    print("| where | share of the points | share of the inward normals | inward there |")
    print("|---|---|---|---|")
    away = ~cap & (to_cap >= NEAR_CAP)
    rows = [("caps", cap), (f"lateral, within {NEAR_CAP} cm of a cap", ~cap & (to_cap < NEAR_CAP)),
            (f"lateral, other side within {THIN} cm", away & (thickness < THIN)),
            ("lateral, elsewhere", away & (thickness >= THIN))]
    for label, m in rows:
        print(f"| {label} | {100 * m.mean():.1f} % | {100 * m[inward].mean():.1f} % | "
              f"{100 * inward[m].mean():.1f} % |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    for s in ("0.005", "0.020"):
        report(sys.argv[1], s)
