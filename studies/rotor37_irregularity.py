#!/usr/bin/env python3
"""Rotor 37: how far each stream-surface section departs from the cubic through its neighbours.

A correspondence-free check of the hold-out floor (docs/benchmarks.md, "Spanwise accuracy").
The NASA table gives, per section and point J, the meridional position (Z, R) and the two blade
sides' angles THETA 1 and THETA 2 at that same (Z, R). So thickness R (THETA1 - THETA2) and the
camber line's circumferential position R (THETA1 + THETA2) / 2 are functions of the fraction f
of meridional arc length from the leading edge, independent of any surface or parameterisation.
For each interior section k (2..10) and each f, the value is compared with the cubic in mean
radius through sections k-2, k-1, k+1, k+2 (Lagrange). On a smooth blade this residual is
O(h^4) and far below the hold-out distances; where it is as large as they are, the data itself
is irregular and no interpolating surface can do better.

Usage: python3 studies/rotor37_irregularity.py [data/rotor37/rotor37geometry.dat]
Prints a Markdown table (cm).
"""
import math
import os
import sys


def read_sections(path):
    sections, current = [], None
    with open(path) as f:
        for line in f:
            if "SURFACE NUMBER" in line:
                current = []
                sections.append(current)
                continue
            p = line.split()
            if current is not None and len(p) == 5 and p[0].isdigit():
                current.append(tuple(float(x) for x in p[1:]))
    return sections


def profile(section):
    """f (meridional arc fraction), thickness and camber position (cm) per point J."""
    m = [0.0]
    for (z0, r0, _, _), (z1, r1, _, _) in zip(section, section[1:]):
        m.append(m[-1] + math.hypot(z1 - z0, r1 - r0))
    f = [x / m[-1] for x in m]
    thick = [r * (t1 - t2) for (_, r, t1, t2) in section]
    camber = [r * (t1 + t2) / 2 for (_, r, t1, t2) in section]
    return f, thick, camber


def interp(x, xs, ys):
    for i in range(len(xs) - 1):
        if xs[i] <= x <= xs[i + 1]:
            s = (x - xs[i]) / (xs[i + 1] - xs[i])
            return ys[i] + s * (ys[i + 1] - ys[i])
    raise ValueError("outside")


def lagrange(x, xs, ys):
    total = 0.0
    for i, (xi, yi) in enumerate(zip(xs, ys)):
        w = 1.0
        for j, xj in enumerate(xs):
            if j != i:
                w *= (x - xj) / (xi - xj)
        total += w * yi
    return total


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "data/rotor37/rotor37geometry.dat")
    sections = read_sections(path)
    radius = [sum(p[1] for p in s) / len(s) for s in sections]
    fractions = [i / 400 for i in range(1, 400)]
    sampled = []
    for s in sections:
        f, thick, camber = profile(s)
        sampled.append(([interp(x, f, thick) for x in fractions],
                        [interp(x, f, camber) for x in fractions],
                        s[0][0]))  # leading-edge Z
    print("| section | thickness residual max [cm] (at f) | camber position residual max [cm] (at f) | leading-edge Z residual [cm] |")
    print("|---|---|---|---|")
    for k in range(2, len(sections) - 2):
        nb = [k - 2, k - 1, k + 1, k + 2]
        rs = [radius[i] for i in nb]
        row = []
        for q in (0, 1):
            res = [sampled[k][q][j] - lagrange(radius[k], rs, [sampled[i][q][j] for i in nb])
                   for j in range(len(fractions))]
            jm = max(range(len(res)), key=lambda j: abs(res[j]))
            row.append("%.5f (%.3f)" % (abs(res[jm]), fractions[jm]))
        le = sampled[k][2] - lagrange(radius[k], rs, [sampled[i][2] for i in nb])
        print("| %d | %s | %s | %+.5f |" % (k, row[0], row[1], le))


if __name__ == "__main__":
    main()
