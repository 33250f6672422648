"""interlineation operators on Python callables: exact on their lines, convergence orders of
digest 001 (T13), Hermite Coons with normal derivatives, spline-curve traces."""
import numpy as np
import pytest

import interlin


def t13(x, y, dx=0, dy=0):
    """sin(3x) cos(2y) + x^3 y^3 and its partial derivatives up to (1, 1) (digest T13)."""
    sx = [np.sin(3 * x), 3 * np.cos(3 * x)][dx]
    cy = [np.cos(2 * y), -2 * np.sin(2 * y)][dy]
    px = [x ** 3, 3 * x ** 2][dx]
    py = [y ** 3, 3 * y ** 2][dy]
    return sx * cy + px * py


def max_error(O, f, m=41):
    s = np.linspace(0, 1, m)
    X, Y = np.meshgrid(s, s)
    return np.max(np.abs(O(X, Y) - f(X, Y)))


@pytest.mark.parametrize("degree", [1, 2, 3])
def test_gordon_is_exact_on_every_line(degree):
    g = np.linspace(0, 1, 5)
    O = interlin.gordon(g, g, *interlin.traces_from_function(t13, g, g), degree=degree)
    s = np.linspace(0, 1, 23)
    for a in g:  # on x = a and on y = a the operator is f itself (interlineation)
        assert np.max(np.abs(O(np.full_like(s, a), s) - t13(a, s))) < 1e-13
        assert np.max(np.abs(O(s, np.full_like(s, a)) - t13(s, a))) < 1e-13


def test_coons_reproduces_digest_t13_table():
    # digest 001 T13 (composite bilinear Coons on n x n cells), also docs/benchmarks.md
    table = {2: 2.91e-02, 4: 2.17e-03, 8: 1.40e-04}
    errors = []
    for n, expected in table.items():
        g = np.linspace(0, 1, n + 1)
        O = interlin.coons(g, g, *interlin.traces_from_function(t13, g, g))
        e = max_error(O, t13, 201)
        assert e == pytest.approx(expected, rel=5e-3)
        errors.append(e)
    order = np.polyfit(np.log([1 / 4, 1 / 8]), np.log(errors[1:]), 1)[0]
    assert order == pytest.approx(4.0, abs=0.1)  # O(h_x^2 h_y^2)


def test_cubic_gordon_order_eight():
    errors = []
    for n in (4, 8, 16):
        g = np.linspace(0, 1, n + 1)
        O = interlin.gordon(g, g, *interlin.traces_from_function(t13, g, g), degree=3)
        errors.append(max_error(O, t13, 101))
    order = np.polyfit(np.log([1 / 4, 1 / 8, 1 / 16]), np.log(errors), 1)[0]
    assert 7.5 < order < 9.0  # (I - P_x)(I - P_y) f: two cubic spline errors O(h^4) each


def test_hermite_coons_matches_values_and_normal_derivatives():
    g = np.linspace(0, 1, 4)
    on_x, on_y = interlin.traces_from_function(t13, g, g)
    dx_on_x, dy_on_y = interlin.normal_derivative_traces(t13, g, g)
    O = interlin.hermite_coons(g, g, on_x, on_y, dx_on_x, dy_on_y)
    s = np.linspace(0, 1, 17)
    for a in g:
        assert np.max(np.abs(O(np.full_like(s, a), s) - t13(a, s))) < 1e-13
        assert np.max(np.abs(O(np.full_like(s, a), s, dx=1) - t13(a, s, 1, 0))) < 1e-12
    assert max_error(O, t13) < 1e-5


def test_scalar_and_array_evaluation_agree():
    g = np.linspace(0, 1, 6)
    O = interlin.gordon(g, g, *interlin.traces_from_function(t13, g, g))
    pts = np.random.default_rng(1).uniform(0, 1, (25, 2))
    batch = O(pts[:, 0], pts[:, 1])
    single = [O(x, y) for x, y in pts]
    # (NumPy may take vector or scalar paths for different lengths: round-off only)
    assert np.max(np.abs(batch - np.array(single).ravel())) < 1e-14
    assert O(0.3, 0.4, dx=1, dy=1) == pytest.approx(O(0.3, np.array([0.4]), dx=1, dy=1)[0],
                                                     rel=1e-14)


def test_vector_valued_and_spline_traces():
    # Coons patch of a parametric surface from four B-spline boundary curves: exact on them.
    u = np.linspace(0, 1, 6)
    def curve(P):
        return interlin.interpolate_open(P, u, 3)
    bottom = curve(np.stack([u, 0 * u, np.sin(u)], 1))
    top = curve(np.stack([u, 1 + 0 * u, np.cos(u)], 1))
    left = curve(np.stack([0 * u, u, u ** 2], 1))
    right = curve(np.stack([1 + 0 * u, u, np.sin(1) + u ** 2 * (np.cos(1) - np.sin(1))], 1))
    O = interlin.coons([0.0, 1.0], [0.0, 1.0], [left, right], [bottom, top], tolerance=1e-9)
    assert O.dim == 3
    s = np.linspace(0, 1, 9)
    assert np.max(np.abs(O(s, 0.0) - bottom.evaluate(s))) < 1e-12
    assert np.max(np.abs(O(1.0, s) - right.evaluate(s))) < 1e-12


def test_incompatible_traces_are_refused():
    g = np.array([0.0, 1.0])
    on_x, on_y = interlin.traces_from_function(t13, g, g)
    on_y[1] = lambda s, d: t13(s, 1.0, d, 0) + 0.1
    with pytest.raises(ValueError, match="crossing"):
        interlin.gordon(g, g, on_x, on_y, degree=1)
    with pytest.raises(ValueError, match="shape"):
        interlin.gordon(g, g, [lambda s, d: np.zeros(len(s) + 1)] * 2, on_y, degree=1)
