#!/usr/bin/env python3
"""Convergence of the interlineation operators on an n x n grid of lines (seed 001 §2.5,
digest 001 §5.1-5.2; digest T13 reproduced).

For smooth test functions on [0, 1]^2 and n = 2, 4, ..., 64 cells per direction: the max error
on a 201 x 201 sample of
  - composite bilinear Coons (Gordon with linear blending, seed 001 Theorem 3 on every cell),
  - Gordon with C1 quadratic and C2 cubic cardinal splines,
  - composite C1 Hermite Coons (also uses the normal-derivative traces),
  - tensor-product spline interpolation of the grid-point values only (bilinear, bicubic),
and the order fitted to the errors from n = 4 on above the round-off floor 1e-13. The
transfinite operators use the whole traces on the lines (Python callables), the tensor products
only the (n + 1)^2 crossing values: the table compares methods, not equal data.

Usage: python3 studies/interlineation_convergence.py [OUT_DIR] [--quick] [-q]   (~1 min)
"""
import numpy as np

from study import Study, arguments, fit_order, interlin, label_axes, loglog, plt, run

ROUND_OFF = 1e-13  # errors below this are round-off of O(1) values: left out of the fits


def t13(x, y, dx=0, dy=0):
    """sin(3x) cos(2y) + x^3 y^3 (digest T13) and its partial derivatives up to (1, 1)."""
    return ([np.sin(3 * x), 3 * np.cos(3 * x)][dx] * [np.cos(2 * y), -2 * np.sin(2 * y)][dy]
            + [x ** 3, 3 * x ** 2][dx] * [y ** 3, 3 * y ** 2][dy])


def exp_sin(x, y, dx=0, dy=0):
    """exp(x - 2y) + sin(4x + 3y) and its partial derivatives up to (1, 1)."""
    s = 4 * x + 3 * y
    trig = {(0, 0): np.sin(s), (1, 0): 4 * np.cos(s), (0, 1): 3 * np.cos(s),
            (1, 1): -12 * np.sin(s)}[(dx, dy)]
    return [1, 1][dx] * [1, -2][dy] * np.exp(x - 2 * y) + trig


FUNCTIONS = [("sin(3x) cos(2y) + x^3 y^3 (digest T13)", t13),
             ("exp(x - 2y) + sin(4x + 3y)", exp_sin)]
# digest 001 T13: composite Coons, f = t13, max error on a 101 x 101 sample.
DIGEST_T13 = {1: 3.7624e-01, 2: 2.9136e-02, 4: 2.1650e-03, 8: 1.4041e-04, 16: 8.7321e-06}

METHODS = ["composite Coons (linear blending, C0)", "Gordon, quadratic (C1)",
           "Gordon, cubic (C2)", "Hermite Coons (C1, + normal derivatives)",
           "tensor product, bilinear (grid values)", "tensor product, bicubic (grid values)"]


def tensor_product(f, g, degree, X, Y):
    """Interpolant of the grid values f(g_i, g_j) of degree `degree` in x and y, at the sample
    grid X x Y (rows along x interpolated, then their control points along y)."""
    F = f(*np.meshgrid(g, g, indexing="ij"))  # F[i, j] = f(g_i, g_j)
    rows = interlin.interpolate_open(F, g, degree)
    cols = interlin.interpolate_open(rows.ctrl.T, g, degree)
    Bx = interlin.explicit_basis(rows.knots, rows.degree).matrix(X)
    By = interlin.explicit_basis(cols.knots, cols.degree).matrix(Y)
    return By @ cols.ctrl @ Bx.T  # [j, i] at (X_i, Y_j)


def digest_t13(n):
    """T13's setting: composite Coons of t13 on n x n cells, max error on 101 x 101 points."""
    g = np.linspace(0, 1, n + 1)
    s = np.linspace(0, 1, 101)
    X, Y = np.meshgrid(s, s)
    O = interlin.coons(g, g, *interlin.traces_from_function(t13, g, g))
    return [float(np.max(np.abs(O(X, Y) - t13(X, Y))))]


def errors(case, sample):
    """Max errors of the six methods for one function on n x n cells."""
    if case[0] == "T13":
        return digest_t13(case[1])
    name, f = FUNCTIONS[case[0]]
    n = case[1]
    g = np.linspace(0, 1, n + 1)
    s = np.linspace(0, 1, sample)
    X, Y = np.meshgrid(s, s)  # X[j, i] = s_i, Y[j, i] = s_j
    exact = f(X, Y)
    on_x, on_y = interlin.traces_from_function(f, g, g)
    ops = [interlin.gordon(g, g, on_x, on_y, degree=p) for p in (1, 2, 3)]
    ops.append(interlin.hermite_coons(g, g, on_x, on_y,
                                      *interlin.normal_derivative_traces(f, g, g)))
    e = [float(np.max(np.abs(O(X, Y) - exact))) for O in ops]
    e += [float(np.max(np.abs(tensor_product(f, g, p, s, s) - exact))) for p in (1, 3)]
    return e


def main():
    args = arguments("interlineation_convergence", __doc__.splitlines()[0])
    study = Study("interlineation_convergence",
                  "Convergence of Gordon, Coons and tensor-product interpolation", args)
    ns = [2, 4, 8] if args.quick else [2, 4, 8, 16, 32, 64]
    sample = 51 if args.quick else 201
    cases = [(k, n) for k in range(len(FUNCTIONS)) for n in ns]
    cases += [("T13", n) for n in DIGEST_T13]
    results = study.map(lambda c: errors(c, sample), cases, "function/grid")
    if not study.writer:
        return
    r = study.report
    r.text("""On [0, 1]^2 with n x n uniform cells: the max error on a %d x %d sample. The
transfinite operators (Coons, Gordon, Hermite Coons) use the whole traces of f on the n + 1 lines
of each family (Python callables, `interlin.gordon` / `coons` / `hermite_coons`; Hermite Coons
also the normal derivatives); the tensor products only the (n + 1)^2 crossing values. The fitted
order is the least-squares slope of log(error) against log(h) from n = 4 on, over errors above
1e-13 (round-off below).""" % (sample, sample))
    h = [1.0 / n for n in ns]
    rows, order_rows = [], []
    for k, (fname, _) in enumerate(FUNCTIONS):
        err = {m: [results[cases.index((k, n))][i] for n in ns] for i, m in enumerate(METHODS)}
        fig, ax = plt.subplots(figsize=(7, 5))
        table = []
        for m in METHODS:
            order = fit_order(h[1:], err[m][1:], ROUND_OFF)
            loglog(ax, h[1:], err[m][1:], m, ROUND_OFF)
            table.append([m] + err[m] + [order])
            order_rows.append([fname, m, order])
            rows += [[fname, m, n, 1.0 / n, e] for n, e in zip(ns, err[m])]
        label_axes(ax, "h = 1/n", "max error on the sample", "f = " + fname)
        r.text("## f = %s" % fname)
        r.table("table_%d" % (k + 1), ["method"] + ["n = %d" % n for n in ns] + ["fitted order"],
                table, digits=3)
        r.figure("convergence_%d" % (k + 1), fig,
                 "Max error against h (log-log), fitted orders in the legend: f = " + fname)
    r.text("## Digest 001 T13 reproduced (composite Coons, 101 x 101 sample)")
    r.table("digest_t13", ["n", "digest T13", "interlin.coons", "relative difference"],
            [[n, e, results[cases.index(("T13", n))][0],
              results[cases.index(("T13", n))][0] / e - 1] for n, e in DIGEST_T13.items()])
    r.table("errors", ["function", "method", "n", "h", "max_error"], rows,
            "All errors", markdown=False)
    r.table("orders", ["function", "method", "fitted_order"], order_rows,
            "Fitted orders", markdown=False)
    r.text("""What the numbers show (see also docs/benchmarks.md):

- Composite bilinear Coons is O(h^4) = O(h_x^2 h_y^2), as digest 001 T13 says.
- Gordon with cubic cardinal splines is O(h^8), quadratic O(h^6): f - O f = (I - P_x)(I - P_y) f,
  the product of two 1-D spline interpolation errors.
- C1 Hermite Coons is O(h^8) and more accurate than cubic Gordon on coarse grids, at the price
  of the normal-derivative traces.
- Tensor-product interpolation of the grid values is O(h^2) (bilinear) and O(h^4) (bicubic).""")
    study.progress("wrote " + r.write())


if __name__ == "__main__":
    run("interlineation_convergence", main)
