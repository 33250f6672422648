#!/usr/bin/python3
"""Angle quality and fit of a triangle mesh of an implicit model (docs/benchmarks.md "Surface
smoothing: an angle floor").

Usage: surface_mesh_quality.py MESH.obj MODEL.rf [INTERLIN]

Prints the number of triangles; the smallest angle, its 1st percentile and mean over the faces'
smallest angles (degrees); the share of faces below 5 and 1 degrees; and the fit: the distance
of every face's centroid to F = 0, |F| / |grad F| by `interlin eval --gradient` (first order,
exact on planes), rms and max, divided by the mesh's bounding-box diagonal.
"""
import io
import os
import subprocess
import sys
import tempfile

import numpy as np


def read_obj(path):
    V, F = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                V.append([float(x) for x in line.split()[1:4]])
            elif line.startswith("f "):
                F.append([int(x.split("/")[0]) - 1 for x in line.split()[1:4]])
    return np.array(V), np.array(F)


def smallest_angles(P):
    def corner(a, b, c):
        u, v = b - a, c - a
        return np.degrees(np.arctan2(np.linalg.norm(np.cross(u, v), axis=1), (u * v).sum(1)))

    A = [corner(P[:, j], P[:, (j + 1) % 3], P[:, (j + 2) % 3]) for j in range(3)]
    return np.min(A, axis=0)


def centroid_distances(C, model, interlin):
    with tempfile.TemporaryDirectory() as d:
        pts = os.path.join(d, "c.csv")
        np.savetxt(pts, C, delimiter=",", header="x,y,z", comments="", fmt="%.17g")
        out = subprocess.run([interlin, "eval", model, pts, "--gradient", "-q"],
                             capture_output=True, text=True, check=True).stdout
    E = np.loadtxt(io.StringIO(out), delimiter=",", skiprows=1)
    return np.abs(E[:, 3]) / np.maximum(np.linalg.norm(E[:, 4:7], axis=1), 1e-300)


def main(argv):
    if len(argv) not in (3, 4):
        sys.exit(__doc__.strip().splitlines()[2])
    interlin = argv[3] if len(argv) == 4 else "build/tools/interlin"
    V, F = read_obj(argv[1])
    P = V[F]
    a = smallest_angles(P)
    d = centroid_distances(P.mean(axis=1), argv[2], interlin)
    diag = np.linalg.norm(np.ptp(V, axis=0))
    print(f"triangles {len(F)}  smallest {a.min():.3g}  p1 {np.percentile(a, 1):.3g}  "
          f"mean {a.mean():.2f} deg  below 5 deg {100 * (a < 5).mean():.2f} %  "
          f"below 1 deg {100 * (a < 1).mean():.3f} %  centroid fit / diagonal: "
          f"rms {np.sqrt((d ** 2).mean()) / diag:.3g}  max {d.max() / diag:.3g}")


if __name__ == "__main__":
    main(sys.argv)
