"""Implicit models from Python: interlin.implicit() of sections (the section body) and of .rf
models (normalised), against closed-form signed distances; .ifl and .rf through one loader
(load_model, as the CLI's registry); the loft's spanwise model and its leave-one-out error."""
import numpy as np
import pytest

import interlin
from conftest import cli_error, write_text

RNG = np.random.default_rng(10)


def circle_sections(zs, n=40, radius=1.0):
    t = 2 * np.pi * np.arange(n) / n
    return [np.column_stack([radius * np.cos(t), radius * np.sin(t), np.full(n, z)]) for z in zs]


@pytest.fixture(scope="module")
def cylinder():
    """The section body of a unit cylinder 0 <= z <= 2 (five circles), coarse grid."""
    return interlin.implicit(circle_sections([0, 0.5, 1.0, 1.5, 2.0]), resolution=16)


def test_section_body_is_the_signed_distance_near_the_side(cylinder):
    M = cylinder
    assert M.kind == "section_body" and M.grid_shape[0] >= 16
    # Points within the inner band of the side, away from the caps: omega = 1 - r up to the
    # loft's error on the circle (cubic spline through 40 points: ~2e-6).
    inner = M.band[0]
    r = 1 + RNG.uniform(-0.9, 0.9, 300) * inner
    a, z = RNG.uniform(0, 2 * np.pi, 300), RNG.uniform(0.6, 1.4, 300)
    P = np.column_stack([r * np.cos(a), r * np.sin(a), z])
    assert np.max(np.abs(M(P) - (1 - r))) < 1e-5
    F, G = M.gradient(P)
    radial = np.column_stack([np.cos(a), np.sin(a), np.zeros_like(a)])
    assert np.allclose(F, M(P)) and np.max(np.abs(G + radial)) < 1e-4
    # Exact on every input point (the guarantee: <= 1e-12 x bbox diagonal).
    S = np.vstack(circle_sections([0, 0.5, 1.0, 1.5, 2.0]))
    assert np.max(np.abs(M(S))) <= 1e-12 * M.report["bbox_diagonal"]
    assert M.report["max_surface_omega"] <= 1e-12 * M.report["bbox_diagonal"]
    assert M(np.array([[0, 0, 1.0], [3, 0, 1.0]])).tolist() == pytest.approx([1, -2], abs=0.05)
    assert M.report["span"].used.parameters in ("station", "chord", "centripetal", "uniform")


def test_ifl_round_trip_through_load_model(cylinder, tmp_path):
    path = str(tmp_path / "cylinder.ifl")
    cylinder.write(path)
    f = interlin.load_model(path)
    P = RNG.uniform(-1.5, 1.5, (200, 3)) + [0, 0, 1]
    assert np.array_equal(f(P), cylinder(P))
    assert np.allclose(f.box, cylinder.box)
    assert "section_body" in interlin.ifl_kinds()
    with pytest.raises(ValueError):
        interlin.load_model(path, parameters={"a": 1.0})


def test_normalised_rf_model_is_the_distance_near_the_surface(tmp_path):
    # F = 1 - r^2 (|grad F| = 2 on the sphere): normalised, omega = 1 - r near the sphere (the
    # near field is the distance to the tangent plane at the foot along grad F: exact for a
    # sphere, to Newton's tolerance).
    rf = write_text(tmp_path / "ball.rf", "box(-1.5, -1.5, -1.5, 1.5, 1.5, 1.5);\n"
                    "res = 1 - x*x - y*y - z*z;\n")
    M = interlin.implicit(rf, resolution=16, mesh_resolution=32)
    assert M.kind == "normalized_rf"
    d = RNG.normal(size=(300, 3))
    d /= np.linalg.norm(d, axis=1)[:, None]
    r = 1 + RNG.uniform(-0.9, 0.9, 300) * M.band[0]
    assert np.max(np.abs(M(d * r[:, None]) - (1 - r))) < 1e-9
    path = str(tmp_path / "ball.ifl")
    M.write(path)
    assert np.array_equal(interlin.load_model(path)(d), M(d))


def test_load_model_reports_like_the_cli(tmp_path):
    bad = write_text(tmp_path / "bad.ifl", "not an ifl file\n")
    pts = write_text(tmp_path / "p.csv", "x,y,z\n0,0,0\n")
    with pytest.raises(interlin.InputError) as e:
        interlin.load_model(bad)
    message, status = cli_error("eval", bad, pts)
    assert str(e.value) == message and status == 1
    with pytest.raises(interlin.InputError, match="unknown model type '.xyz'"):
        interlin.load_model(write_text(tmp_path / "model.xyz", "res = 1;\n"))


def ellipse_stack(zs, n=48):
    """Elliptic sections whose semi-axes are polynomials of degree <= 2 in z: every spanwise
    line is a parabola in z, which span degree >= 2 on station parameters reproduces (spline
    interpolation is a projector onto a space that holds the polynomials); other spacings of
    nonuniform stations do not."""
    t = 2 * np.pi * np.arange(n) / n
    return [np.column_stack([(2 + 0.5 * z * z) * np.cos(t), (1 - 0.2 * z) * np.sin(t),
                             np.full(n, z)]) for z in zs]


def test_span_model_station_parameters_reproduce_a_quadratic_stack():
    zs = np.array([0.0, 0.2, 0.5, 1.1, 1.3, 2.0, 2.4])  # nonuniform stations
    S = ellipse_stack(zs)
    L = interlin.loft(S, span="station", span_degree=3)
    m = L.span
    assert not m.chosen and m.used.parameters == "station" and m.used.degree == 3
    assert m.stacking == "parallel planes" and m.folds == len(zs) - 2
    assert np.allclose(m.stations - m.stations[0], zs)
    # Leave-one-out on a quadratic stack: round-off (1e-9 x size), against closed-form points.
    assert m.used.loo_max < 1e-9
    assert np.allclose(L.section_v, zs / zs[-1], atol=1e-12)
    # Uniform spacing of nonuniform stations distorts the parabolas: a clear error (0.12).
    U = interlin.loft(S, span="uniform", span_degree=3).span.used
    assert U.loo_max > 1e-2 and U.loo_rms <= U.loo_max


def test_span_auto_picks_the_best_scored_candidate():
    zs = np.array([0.0, 0.3, 0.45, 1.0, 1.6, 1.8, 2.5])
    m = interlin.loft(ellipse_stack(zs)).span
    assert m.chosen and len(m.candidates) > 1
    best = min(m.candidates, key=lambda c: c.score)  # first of equal scores
    assert (m.used.parameters, m.used.degree) == (best.parameters, best.degree)
    assert m.used.loo_max < 1e-9  # station parameters are among the candidates and exact
    with pytest.raises(ValueError, match="span_degree"):
        interlin.loft(ellipse_stack(zs), span_degree=0)
