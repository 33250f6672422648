#!/usr/bin/env python3
"""Floating-point accuracy of seed 001 Theorem 1 on nonuniform knots (docs/formulas.md).

For random knot vectors whose spans are spread over a factor R (span lengths R^U, U uniform on
[0, 1]) and degrees n = 2, 3, 5, 7:
  - max |N_explicit(x) - N_CoxdeBoor(x)| over random x: the explicit per-span form as built
    (interlin.explicit_bspline: y* by the derivative recurrence, integration (2)) against the
    Cox-de Boor recursion on the same knots (interlin.cox_de_boor);
  - the largest relative error of the seed's own route to y* (theorem1_y_solve: y_1 = 1 and a
    linear solve of the closure conditions (3)) and of the closed form (digest §2.1.3), both
    against the derivative recurrence (theorem1_y);
  - the closure residual of the explicit form (conditions (3) at the right end).

Usage: python3 studies/theorem1_conditioning.py [OUT_DIR] [--quick] [-q] [--trials T]
Deterministic (seeded random knots).
"""
import numpy as np

from study import Study, arguments, interlin, plt, run

RATIOS = [1.0, 10.0, 1e3, 1e5]
DEGREES = [2, 3, 5, 7]


def fmt_r(R):
    return "none" if R is None else "%g" % R


def case_errors(case, trials):
    """Worst errors over `trials` random knot vectors of span ratio R and degree n."""
    R, n = case
    rng = np.random.default_rng([int(np.log10(R)), n])
    e_val = e_solve = e_closed = e_closure = 0.0
    for _ in range(trials):
        X = np.concatenate([[0.0], np.cumsum(R ** rng.uniform(0, 1, n + 1))])
        N = interlin.explicit_bspline(X, n)
        x = X[-1] * rng.uniform(0, 1, 50)
        e_val = max(e_val, float(np.max(np.abs(N(x) - interlin.cox_de_boor(X, n, x)))))
        y = interlin.theorem1_y(X, n)
        scale = np.max(np.abs(y))
        e_solve = max(e_solve, float(np.max(np.abs(interlin.theorem1_y_solve(X, n) - y))) / scale)
        e_closed = max(e_closed,
                       float(np.max(np.abs(interlin.theorem1_y_closed_form(X, n) - y))) / scale)
        e_closure = max(e_closure, interlin.closure_residual(N, X))
    return [e_val, e_solve, e_closed, e_closure]


def main():
    args = arguments("theorem1_conditioning", __doc__.splitlines()[0],
                     lambda p: p.add_argument("--trials", type=int, default=200,
                                              help="knot vectors per (R, n) (default 200)"))
    study = Study("theorem1_conditioning", "Seed 001 Theorem 1: floating-point conditioning",
                  args)
    trials = 5 if args.quick else args.trials
    cases = [(R, n) for R in RATIOS for n in DEGREES]
    results = study.map(lambda c: case_errors(c, trials), cases, "(R, n)")
    if not study.writer:
        return
    r = study.report
    r.text("""%d random knot vectors per row (span lengths R^U, U uniform on [0, 1]), 50 random
points each. Columns: the explicit per-span form against Cox-de Boor (absolute, values <= 1);
the seed's linear solve of the closure conditions (3) and the closed form of digest §2.1.3,
relative to the derivative recurrence that explicit_bspline uses; the closure residual of the
explicit form.""" % trials)
    rows = [[R, n] + e for (R, n), e in zip(cases, results)]
    r.table("conditioning", ["span ratio R", "degree", "explicit vs Cox-de Boor",
                             "seed's solve of (3)", "closed-form y_k", "closure residual"],
            rows, digits=2)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), sharey=True)
    for n in DEGREES:
        e = [results[cases.index((R, n))] for R in RATIOS]
        floor = 1e-17  # exact zeros drawn at the bottom of the log scale
        axes[0].loglog(RATIOS, [max(v[0], floor) for v in e], "o-", label="degree %d" % n)
        axes[1].loglog(RATIOS, [max(v[1], floor) for v in e], "s--", label="degree %d" % n)
    axes[0].set_title("explicit form (recurrence) vs Cox-de Boor", fontsize=10)
    axes[1].set_title("seed's solve of (3): relative error of y*", fontsize=10)
    for ax in axes:
        ax.set_xlabel("span ratio R")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    axes[0].set_ylabel("max error")
    r.figure("conditioning", fig, "Error against the knot-span ratio R (log-log), per degree")
    def reach(column):
        """Per degree, the largest R whose error in `column` stays below 1e-12."""
        return ", ".join("degree %d: %s" % (n, fmt_r(max([R for R in RATIOS
                         if results[cases.index((R, n))][column] < 1e-12], default=None)))
                         for n in DEGREES)
    r.text("""Largest span ratio R with errors below 1e-12 (a loft's chord-length knots rarely
have neighbouring spans differing by more than 10, docs/formulas.md):

- explicit per-span form against Cox-de Boor: %s;
- the seed's solve of (3): %s;
- the closed form of digest §2.1.3: %s.""" % (reach(0), reach(1), reach(2)))
    study.progress("wrote " + r.write())


if __name__ == "__main__":
    run("theorem1_conditioning", main)
