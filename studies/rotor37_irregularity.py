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

No surface is involved (no interlin call); the study writes CSV, a plot of the
residuals along the chord and report.md like the other studies.

Usage: python3 studies/rotor37_irregularity.py [OUT_DIR] [--quick] [-q] [--data FILE]
(FILE default data/rotor37/rotor37geometry.dat; --quick changes nothing: the study takes 1 s)
"""
import math
import os

from study import DATA, Study, arguments, plt, run


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
    args = arguments("rotor37_irregularity", __doc__.splitlines()[0],
                     lambda p: p.add_argument("--data", default=os.path.join(
                         DATA, "rotor37", "rotor37geometry.dat")))
    study = Study("rotor37_irregularity", "Rotor 37: the data's own section-to-section "
                  "irregularity", args)
    sections = read_sections(args.data)
    radius = [sum(p[1] for p in s) / len(s) for s in sections]
    fractions = [i / 400 for i in range(1, 400)]
    sampled = []
    for s in sections:
        f, thick, camber = profile(s)
        sampled.append(([interp(x, f, thick) for x in fractions],
                        [interp(x, f, camber) for x in fractions],
                        s[0][0]))  # leading-edge Z
    rows, curves = [], []
    for k in range(2, len(sections) - 2):
        nb = [k - 2, k - 1, k + 1, k + 2]
        rs = [radius[i] for i in nb]
        row = [k]
        for q in (0, 1):
            res = [sampled[k][q][j] - lagrange(radius[k], rs, [sampled[i][q][j] for i in nb])
                   for j in range(len(fractions))]
            curves.append((k, q, res))
            jm = max(range(len(res)), key=lambda j: abs(res[j]))
            row += [abs(res[jm]), fractions[jm]]
        row.append(sampled[k][2] - lagrange(radius[k], rs, [sampled[i][2] for i in nb]))
        rows.append(row)
    if not study.writer:
        return
    r = study.report
    r.text("""Data: the NASA table `%s` (cm). For each interior section k the thickness
R (THETA1 - THETA2) and the camber line's position R (THETA1 + THETA2) / 2 at 399 fractions f of
meridional arc length, compared with the cubic in mean radius through sections k-2, k-1, k+1,
k+2. On a smooth blade this residual is O(h^4) and far below the hold-out distances
(studies/rotor37_holdout.py); where it is as large, the data itself is irregular.""" %
           os.path.relpath(args.data, os.path.dirname(DATA)))
    r.table("residuals", ["section", "thickness residual max [cm]", "at f",
                          "camber position residual max [cm]", "at f",
                          "leading-edge Z residual [cm]"], rows)
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5), sharey=True)
    for k, q, res in curves:
        axes[q].plot(fractions, res, label="section %d" % k)
    for ax, what in zip(axes, ("thickness", "camber line position")):
        ax.set_xlabel("fraction f of meridional arc length from the leading edge")
        ax.set_title("%s: section minus the cubic through its neighbours" % what, fontsize=10)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("residual [cm]")
    axes[0].legend(fontsize=7, ncol=2)
    r.figure("residuals", fig, "Residuals along the chord of each interior section")
    r.table("residual_curves", ["section", "quantity", "f", "residual [cm]"],
            [[k, ("thickness", "camber")[q], f, v] for k, q, res in curves
             for f, v in zip(fractions, res)], "All residual curves", markdown=False)
    study.progress("wrote " + r.write())


if __name__ == "__main__":
    run("rotor37_irregularity", main)
