#!/usr/bin/env python3
"""Pairs of blades with the same input and different truths (docs/benchmarks.md, "No input-only
rule meets both targets"), from `blade_family --csv A.csv --pairs L,... --pairs-csv P.csv`.

Truth A is the analytic blade; truth B, for a surface X (a fixed option or OCCT) and a fraction
L, has the same input points and each point between sections moved the fraction L of the way to
its foot on X (along X's normal). A loft sees only the input, so it gives one surface S for both.
Issue 9's per-blade targets on each truth T: (1) max and rms error at or below OCCT's, (2) within
10 % of the best fixed option's (max and rms); so e_T(S) <= b_T = min(OCCT_T, 1.1 best_T) in max
and in rms. The two truths' points are s_i apart along X's normal, so d_S(A_i) + d_S(B_i) >= s_i
where S is locally a graph over X's normal: on the middle halves of the blade's sides (sin^2 t
>= 1/2, t the profile angle), not at the edges, whose radius is of the size of the errors. So
e_A(S) + e_B(S) >= D = max of s on the sides (rms: by Minkowski, D = the root of the sum of s^2
on the sides over all points): no such surface meets both truths' targets when b_A + b_B < D.
Printed per file set and fraction: blades on which some pair proves this for (1) and (2) jointly
and for (2) alone, the pairs that prove it, the same with a margin (b_A + b_B < 0.9 D), and the
smallest measured (e_A + e_B) / D over every surface and pair (how well the bound holds on the
lofts measured); then what the default reaches on truth A instead.

Usage: python3 bench/span_pairs.py A0.csv P0.csv [A1.csv P1.csv ...]
"""
import csv
import math
import sys
from collections import defaultdict

sys.path.insert(0, __file__.rsplit("/", 1)[0])
import span_rules  # noqa: E402


def load_pairs(path):
    """(case, target, fraction) -> (model -> (max, rms) against truth B, (max s, rms s))."""
    out = {}
    for r in csv.DictReader(open(path)):
        key = (int(r["case"]), r["target"], float(r["fraction"]))
        shift = (float(r["shift_max"]), float(r["shift_rms"]))
        out.setdefault(key, ({}, shift))[0][r["model"]] = (float(r["max"]), float(r["rms"]))
    return out


def bounds(errors, fixed):
    """b = min(OCCT, 1.1 best fixed) and 1.1 best fixed, each (max, rms)."""
    best = [min(errors[k][j] for k in fixed) for j in (0, 1)]
    two = [1.1 * best[j] for j in (0, 1)]
    return [min(errors["occt"][j], two[j]) for j in (0, 1)], two


MARGIN = 0.9  # the bound with 10 % to spare: e_A + e_B >= 0.9 D


def study(cases, pairs):
    rows = defaultdict(lambda: {"joint": set(), "two": set(), "joint_m": set(), "two_m": set(),
                                "occt": set(), "pairs": 0, "joint_pairs": 0, "two_pairs": 0,
                                "slack": math.inf})
    for (i, target, L), (b_err, D) in pairs.items():
        if i not in cases:
            continue
        c = cases[i]
        a_err = {k: (v["max"], v["rms"]) for k, v in c["m"].items()}
        fixed = [k for k in span_rules.fixed_options(c) if not k.startswith("thru")]
        bA, twoA = bounds(a_err, fixed)
        bB, twoB = bounds(b_err, fixed)
        r = rows[L]
        r["pairs"] += 1
        if any(bA[j] + bB[j] < D[j] for j in (0, 1)):
            r["joint"].add(i)
            r["joint_pairs"] += 1
            if target == "occt":
                r["occt"].add(i)
        if any(twoA[j] + twoB[j] < D[j] for j in (0, 1)):
            r["two"].add(i)
            r["two_pairs"] += 1
        if any(bA[j] + bB[j] < MARGIN * D[j] for j in (0, 1)):
            r["joint_m"].add(i)
        if any(twoA[j] + twoB[j] < MARGIN * D[j] for j in (0, 1)):
            r["two_m"].add(i)
        for k in b_err:
            for j in (0, 1):
                if D[j] > 0:
                    r["slack"] = min(r["slack"], (a_err[k][j] + b_err[k][j]) / D[j])
    return rows


def default_record(cases):
    """The default on truth A: blades at or below OCCT (max and rms), within 10 % of the best
    fixed option, geometric means and worst of the worse of the max and rms ratios."""
    r = [span_rules.ratios(c, "default") for c in cases.values()]
    gm = lambda xs: math.exp(sum(map(math.log, xs)) / len(xs))
    return (f"{sum(a <= 1 for a, _ in r)} | {sum(b <= 1.1 for _, b in r)} | "
            f"{gm([a for a, _ in r]):.3f}, {max(a for a, _ in r):.2f} | "
            f"{gm([b for _, b in r]):.3f}, {max(b for _, b in r):.2f} |")


def main(args):
    if len(args) < 2 or len(args) % 2:
        sys.exit(__doc__)
    print("| blades (pairs) | fraction L | (1) and (2) out of reach: blades (pairs); by X = OCCT "
          "| (2) alone: blades (pairs) | with the margin 0.9: (1) and (2), (2) alone | least "
          "(e_A + e_B) / D measured |")
    print("|---|---|---|---|---|---|")
    for a, p in zip(args[0::2], args[1::2]):
        cases = span_rules.load(a)
        for L, r in sorted(study(cases, load_pairs(p)).items()):
            print(f"| {a}: {len(cases)} ({r['pairs']}) | {L:g} | {len(r['joint'])} "
                  f"({r['joint_pairs']}); {len(r['occt'])} | {len(r['two'])} ({r['two_pairs']}) | "
                  f"{len(r['joint_m'])}, {len(r['two_m'])} | {r['slack']:.3f} |")
    print("\n| default on truth A | at or below OCCT | within 10 % of the best fixed option | "
          "/ OCCT: geometric mean, worst | / best fixed: geometric mean, worst |")
    print("|---|---|---|---|---|")
    for a in args[0::2]:
        print(f"| {a} | " + default_record(span_rules.load(a)))


if __name__ == "__main__":
    main(sys.argv[1:])
