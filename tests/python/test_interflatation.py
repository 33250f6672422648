"""Interflatation from Python: box and grid interflatation on Python traces (digest 001 T14,
exact on every plane, the error formula), Theorem 4 on plane regions (T16, T17 closed forms,
T19 for random traces), the tricubic grid, and the batching of Python traces."""
import numpy as np
import pytest

import interlin

RNG = np.random.default_rng(12)


def test_t14_box_interflatation_digest_values():
    cube = lambda x, y, z: (x * y * z) ** 2  # noqa: E731
    lo, hi = [0, 0, 0], [1, 1, 1]
    assert interlin.box_interflatation(cube, lo, hi, [[0.5, 0.5, 0.5]])[0] == pytest.approx(
        1 / 32, rel=1e-15)
    # f - Of = -x(1-x) y(1-y) z(1-z) (digest T14), to round-off of sums of 7 terms <= 1.
    P = RNG.uniform(0, 1, (200, 3))
    x, y, z = P.T
    err = cube(x, y, z) - interlin.box_interflatation(cube, lo, hi, P)
    assert np.max(np.abs(err + x * (1 - x) * y * (1 - y) * z * (1 - z))) < 1e-15
    f = lambda x, y, z: np.sin(x + 2 * y) * np.exp(z) + x * y * z  # noqa: E731
    assert interlin.box_interflatation(f, lo, hi, [[0.3, 0.4, 0.5]])[0] == pytest.approx(
        1.5386766581747588, rel=1e-15)


def smooth(x, y, z):
    return np.sin(1.3 * x + y) * np.cos(0.7 * z) + x * y * y


@pytest.mark.parametrize("degree", [1, 3])
def test_grid_interflatation_is_exact_on_every_plane(degree):
    # Nonuniform planes; exactness must not depend on spacing. Round-off: sums of <= 7 x 5^3
    # terms of size <= 2.
    nodes = [np.array([0, 0.15, 0.45, 0.6, 1]), np.array([0, 0.3, 0.7, 1]),
             np.array([0, 0.2, 0.35, 0.8, 1])]
    O = interlin.grid_interflatation(nodes, interlin.plane_traces_from_function(smooth, nodes),
                                     degree)
    for axis in range(3):
        for c in nodes[axis]:
            P = RNG.uniform(0, 1, (30, 3))
            P[:, axis] = c
            assert np.max(np.abs(O(P) - smooth(*P.T))) < 1e-13


@pytest.mark.parametrize("degree,order", [(1, 5.5), (3, 8.0)])
def test_grid_interflatation_error_orders(degree, order):
    # f - Of = (I - P1)(I - P2)(I - P3) f: O(h^6) for linear, O(h^12) for cubic blending on
    # uniform grids; the first halving is taken (the cubic error nears round-off after it).
    P = RNG.uniform(0, 1, (300, 3))
    e = []
    for n in (3, 5):
        v = np.linspace(0, 1, n)
        O = interlin.grid_interflatation([v, v, v],
                                         interlin.plane_traces_from_function(smooth, [v, v, v]),
                                         degree)
        e.append(np.max(np.abs(O(P) - smooth(*P.T))))
    assert np.log2(e[0] / e[1]) >= order, e


def test_python_traces_are_called_once_per_evaluation():
    calls = []
    v = np.array([0.0, 0.5, 1.0])
    base = interlin.plane_traces_from_function(lambda x, y, z: x + 2 * y + 3 * z, [v, v, v])
    counted = [[(lambda a, b, t=t: calls.append(len(a)) or t(a, b)) for t in axis]
               for axis in base]
    O = interlin.grid_interflatation([v, v, v], counted, 3)
    P = RNG.uniform(0, 1, (500, 3))
    assert np.max(np.abs(O(P) - P @ [1, 2, 3])) < 1e-13  # linear: reproduced
    assert len(calls) == 9 and min(calls) > 1  # each trace once, with all its points
    with pytest.raises(ValueError, match="one number per point"):
        interlin.grid_interflatation([v, v, v], [[lambda a, b: 1.0] * 3] * 3, 1)(P)
    with pytest.raises(ValueError):
        interlin.grid_interflatation([v, v, v], base, 2)


def example3(x, y):
    """Example 3's R-function (digest 001 §2.7, T15): u + v - sqrt(u^2 + v^2)."""
    u, v = x * (1 - x), y * (1 - y)
    return u + v - np.sqrt(u * u + v * v)


@pytest.mark.parametrize("kind", ["implicit", "polygon"])
def test_t16_theorem4_on_the_unit_square(kind):
    square = (interlin.implicit_boundary(lambda x, y: example3(x, y), [[0, 0], [1, 1]])
              if kind == "implicit" else
              interlin.polygon_boundary([[0, 0], [1, 0], [1, 1], [0, 1]]))
    g = np.array([0, 0.5, 1])
    O = interlin.region_interlineation(square, g, g, example3)
    assert O.cell_kinds() == {"rectangle": 4}
    assert O([[0.25, 0.25]])[0] == pytest.approx(0.0883883, abs=5e-8)
    s = np.linspace(0, 1, 201)
    X, Y = np.meshgrid(s, s)
    P = np.column_stack([X.ravel(), Y.ravel()])
    err = np.abs(O(P) - example3(X.ravel(), Y.ravel()))
    assert err.max() == pytest.approx(0.0300247, abs=5e-8)
    assert np.allclose(np.minimum(P[err.argmax()], 1 - P[err.argmax()]), [0.13, 0.13])
    # The normal function min(x, 1-x, y, 1-y): Ou = 2xy on [0, 1/2]^2 (T16).
    N = interlin.region_interlineation(square, g, g,
                                       lambda x, y: np.minimum.reduce([x, 1 - x, y, 1 - y]))
    Q = RNG.uniform(0, 0.5, (100, 2))
    assert np.max(np.abs(N(Q) - 2 * Q[:, 0] * Q[:, 1])) < 1e-15


def test_t17_curved_triangles_of_the_unit_disc():
    disc = interlin.implicit_boundary(lambda x, y: 1 - x * x - y * y, [[-1, -1], [1, 1]])
    g = np.array([-1.0, 0.0, 1.0])
    O = interlin.region_interlineation(disc, g, g, lambda x, y: 1 - np.hypot(x, y))
    assert O.cell_kinds()["triangle"] == 4
    # First quadrant: Ou = (1 - x)(1 - y / sqrt(1 - x^2)) (closed form of the mapped cell), the
    # digest's values to its 7 digits, the closed form to round-off (chords are roots to ~1e-15).
    assert O([[0.5, 0.5], [0.3, 0.2]]) == pytest.approx([0.2113249, 0.5532401], abs=5e-8)
    x = RNG.uniform(0, 1, 200)
    y = RNG.uniform(0, 1, 200) * np.sqrt(1 - x * x)
    exact = (1 - x) * (1 - y / np.sqrt(1 - x * x))
    assert np.max(np.abs(O(np.column_stack([x, y])) - exact)) < 1e-12
    a = 2 * np.pi * (np.arange(64) + 0.37) / 64
    assert np.max(np.abs(O(np.column_stack([np.cos(a), np.sin(a)])))) < 1e-12
    assert O.trace(0, 0.0, np.array([0.5]))[0] == pytest.approx(0.5, abs=1e-15)


def test_t19_zero_on_the_boundary_for_random_traces():
    # Any free traces (here nonzero on dG): Ou = 0 on dG, for a hexagon with random grids.
    hexagon = np.array([[0, -1], [1.2, -0.4], [1.0, 0.8], [-0.1, 1.1], [-1.3, 0.3],
                        [-0.9, -0.8]])
    B = interlin.polygon_boundary(hexagon)
    for trial in range(3):
        a = RNG.uniform(-1, 1, 4)
        u = lambda x, y, a=a: a[0] + a[1] * x + a[2] * y * y + a[3] * np.sin(3 * x + y)  # noqa
        x = np.sort(np.concatenate([[-1.4, 1.3], RNG.uniform(-1.2, 1.1, 5)]))
        y = np.sort(np.concatenate([[-1.1, 1.2], RNG.uniform(-0.9, 1.0, 4)]))
        O = interlin.region_interlineation(B, x, y, u)
        P = []
        for c in RNG.uniform(-0.8, 0.8, 40):
            P += [[c, s] for s in B.chords(0, c)] + [[s, c] for s in B.chords(1, c)]
        assert np.max(np.abs(O(np.array(P)))) < 1e-12


def test_cubic_grid_interpolates_nodes_and_reproduces_linear_functions():
    n, h, origin = (5, 4, 6), 0.25, np.array([-0.5, 0.0, 1.0])
    I, J, K = np.meshgrid(*[np.arange(k) for k in n], indexing="ij")
    nodes = origin + h * np.stack([I, J, K], axis=-1)
    lin = lambda P: 0.3 + P @ [1.0, -2.0, 0.5]  # noqa: E731
    G = interlin.cubic_grid(lin(nodes), origin, h)
    P = origin + RNG.uniform(0, 1, (100, 3)) * h * (np.array(n) - 1)
    F, D = G.gradient(P)
    # Natural ends keep linear functions exact; round-off of a 64-term sum of size ~3.
    assert np.max(np.abs(F - lin(P))) < 1e-12 and np.allclose(D, [1.0, -2.0, 0.5], atol=1e-11)
    V = np.sin(nodes.sum(axis=-1))
    G = interlin.cubic_grid(V, origin, h)
    assert np.max(np.abs(G(nodes.reshape(-1, 3)) - V.ravel())) < 1e-13
    assert np.allclose(G.box, [origin, origin + h * (np.array(n) - 1)])
