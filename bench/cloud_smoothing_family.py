#!/usr/bin/python3
"""Noisy scans smoothed point by point before the fit, against the fit of the points as they come
(issue 11, docs/benchmarks.md "Noisy scans smoothed point by point").

Usage: PYTHONPATH=build/python /usr/bin/python3 bench/cloud_smoothing_family.py \
           [SHAPES [COUNTS [RHOS]]]
       defaults: sphere,torus,cylinder,ellipsoid 3000,12000,50000 0.1,0.3,0.6

The shapes, sampling and distances of cloud_clean_families.py (sphere r = 1; torus 1, 0.35;
cylinder radius 0.6, height 1.6 with sharp rims; ellipsoid 1, 0.6, 0.3): COUNT area-uniform points
(seed 1) with exact normals, Gaussian noise rho x spacing along the normal. fit_cloud_implicit with
smooth_points=False and True (the default), meshed by mesh_implicit at the default cell; Chamfer
(mean of the two one-sided means, mesh vertices and 100,000 exact points) and H (the larger
maximum) in spacings.
"""
import sys

import numpy as np

from cloud_clean_families import family, measure


def main(argv):
    shapes, counts, rhos = family(argv, "0.1,0.3,0.6")
    print("| shape | points | rho | as they come: Chamfer, H | smoothed: median k, Chamfer, H | "
          "ratio |")
    print("|---|---|---|---|---|---|")
    ratios = []
    for shape in shapes:
        for n in counts:
            for rho in rhos:
                (c0, h0, _), (c1, h1, info) = measure(
                    shape, n, rho, ({"smooth_points": False}, {}), threads=1)
                k = info["smoothing_neighbours"]
                ratios.append(c1 / c0)
                print(f"| {shape} | {n} | {rho} | {c0:.4f}, {h0:.2f} | {k}, {c1:.4f}, {h1:.2f} | "
                      f"{c1 / c0:.2f} |", flush=True)
    r = np.array(ratios)
    print(f"\ngeometric mean {np.exp(np.log(r).mean()):.3f}; better {int((r < 0.99).sum())}, "
          f"worse {int((r > 1.01).sum())}, equal {int((abs(r - 1) <= 0.01).sum())}")


if __name__ == "__main__":
    main(sys.argv[1:])
