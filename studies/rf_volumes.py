#!/usr/bin/env python3
"""Volumes of the R-function seed models by stratified Monte Carlo (interlin.estimate_volume),
the reference that mesh volumes of `interlin mesh` converge to (digest 000 T19: impeller
1234 +- 0.5 %, T21: UAV 7.565 +- 0.5 %).

Each (model, cell) is one case; the estimate depends on the seed only, not on the thread count
or the MPI rank that computes it.

Usage: python3 studies/rf_volumes.py [OUT_DIR] [--quick] [-q] [--threads T]   (~1 min)
"""
import os

from study import DATA, Study, arguments, interlin, plt, run

# model, cell sizes, digest value and its tolerance (000 T19, T21)
MODELS = [("impeller", (0.1, 0.05), 1234.0, 0.005), ("uav", (0.02, 0.01), 7.565, 0.005)]
QUICK = [("uav", (0.05,), 7.565, 0.005)]


def estimate(case, threads):
    name, cell = case
    f = interlin.load_model(os.path.join(DATA, "models", name + ".rf"))
    v, se, n = interlin.estimate_volume(f, cell, seed=1, threads=threads)
    return v, se, n


def main():
    args = arguments("rf_volumes", __doc__.splitlines()[0],
                     lambda p: p.add_argument("--threads", type=int, default=0,
                                              help="threads per process (0: cores / ranks)"))
    study = Study("rf_volumes", "Volumes of the R-function seed models (Monte Carlo)", args)
    models = QUICK if args.quick else MODELS
    threads = args.threads or max(1, (os.cpu_count() or 1) // study.size)
    cases = [(name, cell) for name, cells, _, _ in models for cell in cells]
    results = study.map(lambda c: estimate(c, threads), cases, "model/cell")
    if not study.writer:
        return
    r = study.report
    r.text("""Stratified Monte Carlo (`interlin.estimate_volume`, seed 1): the model's box cut into
cells, two uniform points per cell; the standard error comes from the pairs. The digest's value
and tolerance are its own Monte Carlo estimates of the thesis programs.""")
    digest = {name: (value, tol) for name, _, value, tol in models}
    rows = []
    for (name, cell), (v, se, n) in zip(cases, results):
        value, tol = digest[name]
        rows.append([name, cell, n, v, se, v - 4 * se, v + 4 * se, value,
                     abs(v - value) + 4 * se <= tol * value])
    r.table("volumes", ["model", "cell", "samples", "volume", "standard error", "4-sigma low",
                        "4-sigma high", "digest value", "4-sigma interval within digest +-0.5 %"],
            rows, digits=6)
    fig, axes = plt.subplots(1, len(models), figsize=(5 * len(models), 4), squeeze=False)
    for ax, (name, cells, value, tol) in zip(axes[0], models):
        est = [results[cases.index((name, c))] for c in cells]
        ax.errorbar(range(len(cells)), [e[0] for e in est], yerr=[4 * e[1] for e in est],
                    fmt="o", capsize=4, label="estimate +- 4 sigma")
        ax.axhspan(value * (1 - tol), value * (1 + tol), alpha=0.2, color="g",
                   label="digest %g +- %g %%" % (value, 100 * tol))
        ax.set_xticks(range(len(cells)), ["cell %g" % c for c in cells])
        ax.set_title(name, fontsize=10)
        ax.legend(fontsize=8)
    axes[0][0].set_ylabel("volume")
    r.figure("volumes", fig, "Monte Carlo volumes with 4-sigma intervals against the digest")
    study.progress("wrote " + r.write())


if __name__ == "__main__":
    run("rf_volumes", main)
