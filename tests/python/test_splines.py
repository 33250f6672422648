"""splines: explicit B-splines (seed 001 Theorem 1) against Cox-de Boor, bases, curves,
Theorem 2, natural curves and cascade profiles."""
import json
import os

import numpy as np
import pytest

import interlin


@pytest.mark.parametrize("n", [1, 2, 3, 5])
def test_explicit_bspline_matches_cox_de_boor(n):
    rng = np.random.default_rng(n)
    for _ in range(20):
        X = np.concatenate([[0.0], np.cumsum(10.0 ** rng.uniform(0, 2, n + 1))])
        N = interlin.explicit_bspline(X, n)
        x = rng.uniform(X[0], X[-1], 50)
        # Tolerance: values are O(1); 1e-12 allows the spread of knot scales (1..100).
        assert np.max(np.abs(N(x) - interlin.cox_de_boor(X, n, x))) < 1e-12
        assert interlin.closure_residual(N, X) < 1e-10


def test_theorem1_three_routes_agree_on_mild_knots():
    X = np.array([0.0, 0.7, 1.5, 2.0, 3.1])
    y = interlin.theorem1_y(X, 3)
    assert np.allclose(interlin.theorem1_y_solve(X, 3), y, rtol=1e-12)
    assert np.allclose(interlin.theorem1_y_closed_form(X, 3), y, rtol=1e-12)


def test_basis_matrix_partition_of_unity_and_derivatives():
    knots = np.array([0, 0, 0, 0, 0.2, 0.5, 0.55, 1, 1, 1, 1.0])
    B = interlin.explicit_basis(knots, 3)
    u = np.linspace(0, 1, 37)
    A = B.matrix(u)
    assert A.shape == (37, B.num_ctrl)
    assert np.allclose(A.sum(axis=1), 1, atol=1e-14)
    # derivative matrix against central differences (h^2 error ~ 1e-8 for these knots)
    h = 1e-5
    inner = u[(u > 0.01) & (u < 0.99) & (np.abs(u - 0.2) > 0.02) & (np.abs(u - 0.5) > 0.06)]
    fd = (B.matrix(inner + h) - B.matrix(inner - h)) / (2 * h)
    assert np.allclose(B.matrix(inner, deriv=1), fd, atol=1e-6)


def test_interpolate_open_and_closed_pass_through_points():
    rng = np.random.default_rng(3)
    P = rng.normal(size=(9, 3))
    u = interlin.chord_parameters(P)
    c = interlin.interpolate_open(P, u, 3)
    assert np.max(np.abs(c.evaluate(u) - P)) < 1e-12
    t = np.linspace(0, 2 * np.pi, 11)[:-1]
    Q = np.stack([np.cos(t), 2 * np.sin(t)], axis=1)
    uc = interlin.chord_parameters(Q, closed=True)
    cc = interlin.interpolate_closed(Q, uc, 3)
    assert cc.periodic and np.max(np.abs(cc.evaluate(uc[:-1]) - Q)) < 1e-12


def test_theorem2_exact_on_quadratics_and_minimal():
    rng = np.random.default_rng(7)
    x = np.sort(rng.uniform(0, 3, 12))
    y = 2 * x ** 2 - x + 0.5
    S = interlin.min_jump_quadratic(x, y)
    t = np.linspace(x[0], x[-1], 200)
    assert np.max(np.abs(S(t) - (2 * t ** 2 - t + 0.5))) < 1e-10  # seed claim (test T7)
    assert S.jump_functional < 1e-18
    # On data that is not quadratic the optimal M_12 beats its neighbours (J is a parabola).
    y = np.sin(3 * x)
    m = interlin.theorem2_m12(x, y)
    J = lambda m12: np.sum(np.diff(interlin.theorem2_recurrence(x, y, m12)) ** 2)
    assert J(m) <= min(J(m - 1e-3), J(m + 1e-3))
    assert np.allclose(interlin.theorem2_explicit(x, y, m), interlin.theorem2_recurrence(x, y, m))


def test_natural_curve_constant_curvature_is_a_circle():
    c = interlin.NaturalCurve([0, 0], 0.0, interlin.polynomial_law([0.5]), 4.0)
    s = np.linspace(0, 4, 9)
    P = c.sample(s)["points"]
    # k = 1/2: circle of radius 2 centred at (0, 2)
    assert np.max(np.abs(np.hypot(P[:, 0], P[:, 1] - 2) - 2)) < 1e-13


def test_cascade_profile_and_stack(data_dir):
    with open(os.path.join(data_dir, "profiles", "turbine_nozzle.json")) as f:
        p = interlin.CascadeParameters(**json.load(f)["parameters"])
    prof = interlin.cascade_profile(p)
    assert prof.points.shape == (2 * (60 + 16), 2) and prof.miss < 1e-8
    S = interlin.stack_cascade_profiles([(1.0, p), (1.2, p)])
    assert len(S) == 2 and S[0].shape == (152, 3) and np.allclose(S[1][:, 2], 1.2)
    with pytest.raises(TypeError, match="unknown parameter 'chord'"):
        interlin.CascadeParameters(chord=1.0)
