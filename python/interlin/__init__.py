"""interlin: spline-interlineation surface reconstruction from Python.

The C++ library (interlin._core) with NumPy arrays in and out: points are (N, 3) float64,
triangles (M, 3) int32. Errors raise InputError (bad input files; the message is the line the
`interlin` CLI prints), ValueError (bad arguments) or RuntimeError.

    import interlin
    L = interlin.loft("data/rotor37/sections.csv")      # exact on every section
    P = L.surface(u, v)                                  # points, shape u.shape + (3,)
    d = L.surface.distance(points)                       # exact point-to-surface distances
    L.surface.write("blade.igs", units="cm")             # IGES, JSON, STL/OBJ/PLY/OFF, PNG
    H = interlin.holdout("data/rotor37/sections.csv", every=2)
    V, F = interlin.mesh_implicit(interlin.load_model("data/models/uav.rf"), resolution=96)
    M = interlin.implicit("data/rotor37/sections.csv")   # the blade body's equation omega
    M.write("blade.ifl"); omega = interlin.load_model("blade.ifl")(points)

Modules: splines (B-splines, seed 001 Theorems 1 and 2, seed 004 natural curves and cascade
profiles), interlineation (gordon, coons, hermite_coons on Python callables as traces),
interlin.rf (R-function expressions) and Implicit bodies, interflatation (grid_interflatation,
box_interflatation on Python callables as plane traces; region_interlineation: seed 001
Theorem 4 on plane regions; cubic_grid), implicit models (implicit(), .rf and .ifl files
through load_model), loft and hold-out with the spanwise model, meshing.
README.md ("Use it from Python") and docs/design.md describe the module.
"""
import numpy as _np

from ._core import *  # noqa: F401,F403
from ._core import __version__  # noqa: F401
from . import _core

rf = _core.rf


def traces_from_function(f, x, y):
    """Traces of f on the lines x = x[i] and y = y[j], for gordon(), coons(), hermite_coons().

    f(x, y, dx, dy) -> the (dx, dy) partial derivative of f at arrays x, y (NumPy arrays of one
    shape), as an array of that shape (scalar f) or shape + (dim,).
    Returns (on_x, on_y): on_x[i](s, d) = d^d/ds^d f(x[i], s), on_y[j](s, d) = d^d/ds^d f(s, y[j]).
    """
    on_x = [(lambda s, d, a=float(a): f(_np.full_like(s, a), s, 0, d)) for a in _np.asarray(x)]
    on_y = [(lambda s, d, b=float(b): f(s, _np.full_like(s, b), d, 0)) for b in _np.asarray(y)]
    return on_x, on_y


def normal_derivative_traces(f, x, y):
    """The normal-derivative traces hermite_coons() needs, from f(x, y, dx, dy) as above.

    Returns (dx_on_x, dy_on_y): dx_on_x[i](s, d) = d^d/ds^d f_x(x[i], s),
    dy_on_y[j](s, d) = d^d/ds^d f_y(s, y[j]).
    """
    dx_on_x = [(lambda s, d, a=float(a): f(_np.full_like(s, a), s, 1, d)) for a in _np.asarray(x)]
    dy_on_y = [(lambda s, d, b=float(b): f(s, _np.full_like(s, b), d, 1)) for b in _np.asarray(y)]
    return dx_on_x, dy_on_y


def plane_traces_from_function(u, nodes):
    """Traces of u on the planes of `nodes`, for grid_interflatation().

    u(x, y, z) -> array (NumPy arrays of one shape in); nodes = [x, y, z] plane positions.
    Returns [on_x, on_y, on_z]: on_x[i](y, z) = u(x[i], y, z), on_y[j](x, z) = u(x, y[j], z),
    on_z[k](x, y) = u(x, y, z[k]).
    """
    x, y, z = (_np.asarray(v, float) for v in nodes)
    return [[(lambda b, c, a=float(a): u(_np.full_like(b, a), b, c)) for a in x],
            [(lambda a, c, b=float(b): u(a, _np.full_like(a, b), c)) for b in y],
            [(lambda a, b, c=float(c): u(a, b, _np.full_like(a, c))) for c in z]]


def cox_de_boor(X, n, x):
    """N_{0,n}(x; X), the B-spline of degree n on the n + 2 knots X, by the Cox-de Boor recursion:
    the independent reference for explicit_bspline (seed 001 Theorem 1). x: array (any shape).

    X is padded with n knots on each side so that N is basis function n of the padded vector
    (cox_de_boor_derivatives); 0 outside [X[0], X[-1]).
    """
    X = _np.asarray(X, float)
    K = _np.concatenate([X[0] - _np.arange(n, 0, -1), X, X[-1] + _np.arange(1, n + 1)])
    x = _np.asarray(x, float)
    out = _np.zeros(x.shape)
    for i, t in _np.ndenumerate(x):
        if X[0] <= t < X[-1]:
            D, span = cox_de_boor_derivatives(K, n, len(K) - n - 1, t)
            out[i] = D[0, 2 * n - span]
    return out
