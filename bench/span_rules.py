#!/usr/bin/env python3
"""Choice rules for the spanwise model, replayed on blade_family CSVs (docs/benchmarks.md,
"Spanwise model on analytic blades").

Every fixed option's row of `blade_family --csv` carries its leave-one-out error (what a rule may
use) and its error between sections against the true blade (what it should minimise); the rules
below choose from the leave-one-out errors only, exactly as choose_span_model would with that
candidate set and score. Prints Markdown: what any rule among the 12 fixed options could reach
(an oracle that sees the truth), and per rule and case set the blades at or below OCCT
(max and rms), within 10 % of the best fixed option (max and rms), and the worst ratios.

Usage: python3 bench/span_rules.py family0.csv [family1.csv ...]
  the first file is split into its even cases (for choosing a rule) and odd cases (to check it);
  further files (fresh families, blade_family --family F) are checks only.
"""
import csv
import math
import sys


def load(path):
    cases = {}
    for r in csv.DictReader(open(path)):
        c = cases.setdefault(int(r["case"]), {"K": int(r["K"]), "stacking": r["stacking"], "m": {}})
        num = lambda x: float(x) if x else math.nan
        c["m"][r["model"]] = dict(loo_max=num(r["loo_max"]), loo_rms=num(r["loo_rms"]),
                                  max=num(r["between_max"]), rms=num(r["between_rms"]))
    return {i: c for i, c in cases.items() if "occt" in c["m"]}


def fixed_options(c):
    """The issue's fixed options: station (if detected), chord, centripetal, uniform x 3, 5, K-1."""
    return [k for k in c["m"] if k not in ("default", "occt") and int(k.split()[1]) in (3, 5, c["K"] - 1)]


def rule(params, score="max", tie="first", degrees=None):
    """Lowest leave-one-out score among params x degrees K-1 (at most 9), 5, 3 (or `degrees`, a
    function of K); ties to the earlier, or with tie="lower" to the lower degree (a fold has one
    section fewer, so degrees K-1 and K-2 give the same fold model and tie)."""
    def choose(c):
        K, out = c["K"], []
        qs = degrees(K) if degrees else (min(K - 1, 9), 5, 3)
        for p in params:
            if p == "station" and c["stacking"] == "none":
                continue
            for q in dict.fromkeys(min(q, K - 1) for q in qs):
                out.append(f"{p} {q}")
        m = c["m"]
        value = {"max": lambda k: m[k]["loo_max"], "rms": lambda k: m[k]["loo_rms"],
                 "max x rms": lambda k: math.sqrt(m[k]["loo_max"] * m[k]["loo_rms"])}[score]
        if tie == "lower":
            return min(out, key=lambda k: (value(k), int(k.split()[1]), out.index(k)))
        return min(out, key=lambda k: (value(k), out.index(k)))
    return choose


def station_prior(params, margin):
    """Best station model unless another model's leave-one-out max is below margin x its max."""
    free, stations = rule(params), rule(("station",))
    def choose(c):
        best = free(c)
        if c["stacking"] == "none":
            return best
        s = stations(c)
        return best if c["m"][best]["loo_max"] < margin * c["m"][s]["loo_max"] else s
    return choose


def degree_penalty(params, alpha):
    """Leave-one-out max scaled by 2^(-alpha (q_fold + 1)): the error of a degree-q_fold fold on
    doubled gaps shrinks by 2^(q_fold + 1) when the gaps are halved (alpha = 1, asymptotic)."""
    def choose(c):
        K, m = c["K"], c["m"]
        out = [f"{p} {q}" for p in params if not (p == "station" and c["stacking"] == "none")
               for q in dict.fromkeys(min(q, K - 1) for q in (min(K - 1, 9), 5, 3))]
        score = lambda k: m[k]["loo_max"] * 2.0 ** (-alpha * (min(int(k.split()[1]), K - 2) + 1))
        return min(out, key=lambda k: (score(k), out.index(k)))
    return choose


RULES = [
    ("station, chord, centripetal; max (before)", rule(("station", "chord", "centripetal"))),
    ("station, chord, centripetal; sqrt(max x rms)", rule(("station", "chord", "centripetal"), "max x rms")),
    ("station, chord, centripetal; rms", rule(("station", "chord", "centripetal"), "rms")),
    ("station, chord; max", rule(("station", "chord"))),
    ("station, chord; sqrt(max x rms)", rule(("station", "chord"), "max x rms")),
    ("station, chord, uniform; max (default)", rule(("station", "chord", "uniform"))),
    ("station, chord, uniform; sqrt(max x rms)", rule(("station", "chord", "uniform"), "max x rms")),
    ("station, chord, centripetal, uniform; max", rule(("station", "chord", "centripetal", "uniform"))),
    ("station prior, margin 0.9 (station, chord, centripetal)", station_prior(("station", "chord", "centripetal"), 0.9)),
    ("station prior, margin 0.7 (station, chord, centripetal)", station_prior(("station", "chord", "centripetal"), 0.7)),
    ("station prior, margin 0.9 (station, chord, uniform)", station_prior(("station", "chord", "uniform"), 0.9)),
    ("degree penalty 0.25 (station, chord, uniform)", degree_penalty(("station", "chord", "uniform"), 0.25)),
    ("degree penalty 0.5 (station, chord, centripetal)", degree_penalty(("station", "chord", "centripetal"), 0.5)),
    ("station, chord, uniform; max; ties to the lower degree", rule(("station", "chord", "uniform"), tie="lower")),
    ("station, chord, uniform; max; degrees 5, 3 (no K-1)", rule(("station", "chord", "uniform"), degrees=lambda K: (5, 3))),
]


def ratios(c, model):
    m, o, fx = c["m"][model], c["m"]["occt"], fixed_options(c)
    best_max = min(c["m"][k]["max"] for k in fx)
    best_rms = min(c["m"][k]["rms"] for k in fx)
    return max(m["max"] / o["max"], m["rms"] / o["rms"]), max(m["max"] / best_max, m["rms"] / best_rms)


def summary(cases, choose):
    r = [ratios(c, choose(c)) for c in cases.values()]
    return (f"{sum(a <= 1 for a, _ in r)} | {sum(b <= 1.1 for _, b in r)} | "
            f"{max(a for a, _ in r):.2f} | {max(b for _, b in r):.2f}")


def main(paths):
    sets = []
    first = load(paths[0])
    sets.append((f"{paths[0]} even", {i: c for i, c in first.items() if i % 2 == 0}))
    sets.append((f"{paths[0]} odd", {i: c for i, c in first.items() if i % 2 == 1}))
    sets.append((f"{paths[0]} all", first))
    for p in paths[1:]:
        sets.append((p, load(p)))
    print("| cases | blades | some option <= OCCT | some option within 10 % | some option both |")
    print("|---|---|---|---|---|")
    for name, cases in sets:
        a = b = ab = 0
        for c in cases.values():
            r = {k: ratios(c, k) for k in fixed_options(c)}
            a += any(x <= 1 for x, _ in r.values())
            b += any(y <= 1.1 for _, y in r.values())
            ab += any(x <= 1 and y <= 1.1 for x, y in r.values())
        print(f"| {name} | {len(cases)} | {a} | {b} | {ab} |")
    print("\nper case set: <= OCCT | within 10 % of the best fixed option | worst / OCCT | worst / best fixed\n")
    print("| rule | " + " | ".join(name for name, _ in sets) + " |")
    print("|---|" + "---|" * len(sets))
    for label, choose in RULES:
        print(f"| {label} | " + " | ".join(summary(c, choose).replace(" | ", ", ") for _, c in sets) + " |")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
