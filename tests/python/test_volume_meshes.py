"""Volume meshes of implicit solids from Python (seed 003's solid-element method), their quality,
files and adaptive refinement (seed 003 §7.2), and the loft's STEP output."""
import numpy as np
import pytest

import interlin
from conftest import ROTOR37
from interlin import rf


@pytest.mark.parametrize("elements,corners", [("tet", 4), ("hex", 8)])
def test_ball_volume_mesh_is_valid_and_has_the_ball_volume(elements, corners, tmp_path):
    ball = rf.compile(rf.sphere(rf.x, rf.y, rf.z, 1.0), [[-1.2] * 3, [1.2] * 3])
    V, C, B, boundary, info = interlin.mesh_volume(ball, elements, resolution=16, threads=1)
    assert V.shape[1] == 3 and C.shape[1] == corners and C.dtype == np.int32
    assert boundary.dtype == bool and boundary.shape == (len(V),)
    # boundary nodes lie on F = 0 (projected to the root finder's tolerance)
    assert np.max(np.abs(np.linalg.norm(V[boundary], axis=1) - 1)) < 1e-9
    q = interlin.volume_quality(V, C, threads=1)
    assert q["inverted"] == 0 and q["elements"] == len(C)
    # polyhedral volume of a 16-cell ball: within 2 % of 4 pi / 3 (chordal deficit ~ h^2)
    assert abs(q["volume"] / (4 * np.pi / 3) - 1) < 0.02
    assert info["max_boundary_f"] < 1e-9
    path = tmp_path / "ball.vtu"
    interlin.write_volume_mesh(str(path), V, C, B, node_fields={"F": ball(V)})
    assert path.stat().st_size > 8 * V.size
    with pytest.raises(ValueError, match="elements: 'prism' is not one of"):
        interlin.mesh_volume(ball, "prism")


@pytest.mark.parametrize("elements", ["tet", "hex"])
def test_facet_sag_accounts_for_the_volume_the_chords_miss(elements):
    # The 16-cell ball's facets are chords of the sphere: mesh + sag is 4 pi / 3 to within 2 % of
    # the sag (the quadrature, exact for a quadratic height; measured 0.1-0.4 %).
    ball = rf.compile(rf.sphere(rf.x, rf.y, rf.z, 1.0), [[-1.2] * 3, [1.2] * 3])
    V, C, B, boundary, info = interlin.mesh_volume(ball, elements, resolution=16, threads=1)
    s = interlin.facet_sag(ball, V, B, threads=1)
    volume = interlin.volume_quality(V, C, threads=1)["volume"]
    assert s["volume"] > 0 and s["skipped_area"] == 0 and s["max_distance"] > 0
    assert abs(volume + s["volume"] - 4 * np.pi / 3) < 0.02 * s["volume"]
    with pytest.raises(ValueError, match="B: expected an"):
        interlin.facet_sag(ball, V, C[:, :2])
    with pytest.raises(ValueError, match="node index outside"):
        interlin.facet_sag(ball, V, B + len(V))


def test_loft_writes_step_faces_and_solids(tmp_path):
    S = interlin.loft(ROTOR37).surface
    S.write(str(tmp_path / "blade.stp"), units="cm")
    S.write(str(tmp_path / "solid.step"), cap=True)
    face, solid = (tmp_path / "blade.stp").read_text(), (tmp_path / "solid.step").read_text()
    assert face.startswith("ISO-10303-21;") and "B_SPLINE_SURFACE_WITH_KNOTS" in face
    assert "CENTI" in face and "MANIFOLD_SOLID_BREP" not in face
    assert "MANIFOLD_SOLID_BREP" in solid and "CLOSED_SHELL" in solid


def tet_volumes(V, C):
    a, b, c, d = (V[C[:, k]] for k in range(4))
    return np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a) / 6


def faces_once(C):
    """The triangles of C that belong to one tetrahedron only (sorted node triples)."""
    F = np.sort(np.vstack([C[:, [0, 1, 2]], C[:, [0, 1, 3]], C[:, [0, 2, 3]], C[:, [1, 2, 3]]]),
                axis=1)
    u, n = np.unique(F, axis=0, return_counts=True)
    assert n.max() <= 2  # no face in three elements
    return u[n == 1]


def area(V, F):
    return 0.5 * np.linalg.norm(np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]]),
                                axis=1).sum()


def test_adaptive_refinement_is_conforming_and_follows_the_field():
    ball = rf.compile(rf.sphere(rf.x, rf.y, rf.z, 1.0), [[-1.2] * 3, [1.2] * 3])
    V, C, B, boundary, info = interlin.mesh_volume(ball, "tet", resolution=8, threads=1)
    # The seed's indicator: range-normalised max difference over an element's nodes.
    one = np.array([[0, 1, 2, 3]])
    assert interlin.refinement_indicator(one, np.array([0.0, 1, 2, 4])).tolist() == [1.0]
    assert not np.any(interlin.refinement_indicator(C, np.ones(len(V))))
    front = lambda V, C: np.tanh(20 * (V[:, 0] - 0.5))  # noqa: E731  a steep front at x = 0.5
    # Without the body no node moves: the refined mesh fills the same polyhedron, so its volume
    # and the area of its open faces are unchanged (round-off of ~1e4 positive terms); a
    # hanging node would open inner faces and add to the area (conforming).
    V1, C1, b1, (values, report) = interlin.refine_tetrahedra(V, C, boundary, front(V, C), 0.3)
    assert report["split"] > 0 and report["new_nodes"] == len(V1) - len(V)
    assert np.allclose(values, np.r_[front(V, C), values[len(V):]])
    assert abs(tet_volumes(V1, C1).sum() - tet_volumes(V, C).sum()) < 1e-12
    assert np.all(tet_volumes(V1, C1) > 0)
    assert abs(area(V1, faces_once(C1)) - area(V, faces_once(C))) < 1e-12
    # The adaptive loop with the body: midpoints of boundary edges land on the sphere.
    V2, C2, b2, passes = interlin.adapt_tetrahedra(V, C, boundary, front, 0.3, 2, ball)
    assert len(passes) == 2 and passes[1]["split"] > 0 and sum(p["projected"] for p in passes) > 0
    assert all(0 <= p["held"] <= p["projected"] for p in passes)
    assert np.max(np.abs(np.linalg.norm(V2[b2], axis=1) - 1)) < 1e-9
    assert interlin.volume_quality(V2, C2, threads=1)["inverted"] == 0
    assert np.all(b2[faces_once(C2)])
    # Refined where the field changes: elements near x = 0.5 shrink 4 times (two halvings;
    # measured 0.17 -> 0.043), those beyond the two rings of neighbours the passes add
    # (0.3 each at this resolution) keep their size.
    size = lambda V, C: np.cbrt(np.abs(tet_volumes(V, C)))  # noqa: E731
    near = lambda V, C: np.abs(V[C].mean(axis=1)[:, 0] - 0.5) < 0.1  # noqa: E731
    far = lambda V, C: V[C].mean(axis=1)[:, 0] < -0.6  # noqa: E731
    assert np.median(size(V2, C2)[near(V2, C2)]) < 0.3 * np.median(size(V, C)[near(V, C)])
    assert np.median(size(V2, C2)[far(V2, C2)]) == np.median(size(V, C)[far(V, C)])
    with pytest.raises(ValueError, match="boundary"):
        interlin.refine_tetrahedra(V, C, boundary[:-1], front(V, C), 0.3)
    with pytest.raises(ValueError, match="values must be #V finite numbers"):
        interlin.adapt_tetrahedra(V, C, boundary, lambda V, C: np.zeros(3), 0.3, 1)

    def failing(V, C):
        raise KeyError("from the field")
    with pytest.raises(KeyError, match="from the field"):  # the field's own error, unchanged
        interlin.adapt_tetrahedra(V, C, boundary, failing, 0.3, 1)


def hex_faces_once(C):
    """The quadrilaterals of hexahedra C (VTK order) used by one element only, as given."""
    Q = np.vstack([C[:, f] for f in ([0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5],
                                     [2, 3, 7, 6], [3, 0, 4, 7])])
    u, first, n = np.unique(np.sort(Q, axis=1), axis=0, return_index=True, return_counts=True)
    assert n.max() <= 2  # no face in three elements
    return Q[first[n == 1]]


def hex_grid(n):
    """The unit cube as n^3 hexahedra (VTK order)."""
    t = np.linspace(0, 1, n + 1)
    V = np.stack(np.meshgrid(t, t, t, indexing="ij"), axis=-1).transpose(2, 1, 0, 3).reshape(-1, 3)
    i, j, k = (a.ravel() for a in np.meshgrid(*(np.arange(n),) * 3, indexing="ij"))
    node = lambda i, j, k: i + (n + 1) * (j + (n + 1) * k)  # noqa: E731
    corners = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0),
               (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
    C = np.stack([node(i + a, j + b, k + c) for a, b, c in corners], axis=1).astype(np.int32)
    return V, C


def test_hexahedral_refinement_is_conforming_and_follows_the_field():
    front = lambda V, C: np.tanh(20 * (V[:, 0] - 0.5))  # noqa: E731
    quads = lambda V, Q: area(V, Q[:, [0, 1, 2]]) + area(V, Q[:, [0, 2, 3]])  # noqa: E731
    # A grid of the unit cube (planar faces): the children fill it exactly, the open faces are its
    # 6 sides (a hanging node would open inner faces), the values x's front interpolated.
    V, C = hex_grid(5)
    V1, C1, b1, (values, report) = interlin.refine_hexahedra(V, C, np.zeros(len(V), bool),
                                                             front(V, C), 0.3)
    assert report["split"] > 0 and report["new_nodes"] == len(V1) - len(V)
    assert report["widened"] >= 0 and report["refined_nodes"] > 0
    q1 = interlin.volume_quality(V1, C1, threads=1)
    assert q1["inverted"] == 0 and abs(q1["volume"] - 1) < 1e-12
    assert abs(quads(V1, hex_faces_once(C1)) - 6) < 1e-12
    assert np.allclose(values[:len(V)], front(V, C))
    # Two passes on the default hexahedra of a ball: new boundary nodes on the sphere but those
    # held short.
    ball = rf.compile(rf.sphere(rf.x, rf.y, rf.z, 1.0), [[-1.2] * 3, [1.2] * 3])
    V, C, B, boundary, info = interlin.mesh_volume(ball, "hex", resolution=8, threads=1)
    V2, C2, b2, passes = interlin.adapt_hexahedra(V, C, boundary, front, 0.3, 2, ball)
    assert len(passes) == 2 and sum(p["projected"] for p in passes) > 0
    assert not any(p["undone"] for p in passes) and all(p["still_folded"] == 0 for p in passes)
    held = sum(p["held"] for p in passes)
    assert np.sum(np.abs(np.linalg.norm(V2[b2], axis=1) - 1) > 1e-9) <= held
    assert interlin.volume_quality(V2, C2, threads=1)["inverted"] == 0
    assert np.all(b2[hex_faces_once(C2)])
    with pytest.raises(ValueError, match=r"\(E, 8\) array of hexahedra"):
        interlin.refine_hexahedra(V, C[:, :4], boundary, front(V, C), 0.3)


def test_mesh_volume_lattice_choice():
    # Tetrahedra cut from the BCC lattice (the default) or the grid's Kuhn tetrahedra: both valid
    # with the boundary on F = 0; BCC's dihedral angles within the isosurface-stuffing bound
    # [10.7, 164.8] degrees on a resolved ball, Kuhn's not (measured 22.6 .. 132.2 against
    # 6.4 .. 155.2 at 12 cells).
    ball = rf.compile(rf.sphere(rf.x, rf.y, rf.z, 1.0), [[-1.2] * 3, [1.2] * 3])
    q = {}
    for lattice in ("bcc", "kuhn"):
        V, C, B, on, info = interlin.mesh_volume(ball, "tet", resolution=12, threads=1,
                                                 lattice=lattice)
        q[lattice] = interlin.volume_quality(V, C, threads=1)
        assert q[lattice]["inverted"] == 0
        assert np.max(np.abs(np.linalg.norm(V[on], axis=1) - 1)) < 1e-9
    assert 10.7 < q["bcc"]["min_dihedral_deg"] and q["bcc"]["max_dihedral_deg"] < 164.8
    assert q["kuhn"]["min_dihedral_deg"] < 10.7
    with pytest.raises(ValueError, match="lattice: 'fcc' is not one of"):
        interlin.mesh_volume(ball, "tet", lattice="fcc")


def test_mesh_volume_boundary_choice_and_held_nodes():
    ball = rf.compile(rf.sphere(rf.x, rf.y, rf.z, 1.0), [[-1.2] * 3, [1.2] * 3])
    for boundary in ("cut", "projected"):
        V, C, B, on, info = interlin.mesh_volume(ball, "tet", resolution=12, threads=1,
                                                 boundary=boundary)
        assert interlin.volume_quality(V, C, threads=1)["inverted"] == 0
        # a resolved ball: no node held short of F = 0, all on the sphere
        assert info["held"] == 0
        assert np.max(np.abs(np.linalg.norm(V[on], axis=1) - 1)) < 1e-9
    with pytest.raises(ValueError, match="boundary: 'flat' is not one of"):
        interlin.mesh_volume(ball, "tet", boundary="flat")
    # A tilted plate 4 cells thick (h = 0.2): the projected hexahedral layer folds unless layer
    # nodes are held short of F = 0 (measured: 63 of them); those are reported, the others lie on
    # F = 0.
    n = np.array([1.0, 2.0, 3.0]) / np.sqrt(14.0)
    s = n[0] * rf.x + n[1] * rf.y + n[2] * rf.z
    plate = rf.compile(rf.and0(0.4 ** 2 - s * s, rf.sphere(rf.x, rf.y, rf.z, 1.0)),
                       [[-1.2] * 3, [1.2] * 3])
    with pytest.warns(UserWarning, match="leaves out"):  # a skew plate 4 cells thin
        V, C, B, on, info = interlin.mesh_volume(plate, "hex", cell=0.2, threads=1,
                                                 boundary="projected")
    assert interlin.volume_quality(V, C, threads=1)["inverted"] == 0
    assert info["held"] > 0 and info["max_boundary_f"] < 1e-8
    assert np.count_nonzero(np.abs(plate(V[on])) > 1e-8) <= info["held"]
    # on_zero: the boundary nodes not held, every one of them on F = 0; the plate is in its box
    assert info["on_zero"] == np.count_nonzero(on) - info["held"]
    assert np.count_nonzero(np.abs(plate(V[on])) <= 1e-8) >= info["on_zero"]
    assert info["clipped"] == 0


def test_mesh_volume_reports_the_volume_the_layer_loses():
    # A spherical shell 0.1 thick: at cell 0.05 no cell lies inside the wall, so the projected
    # layer loses most of it (measured 96 %); the report says so, measures the wall (0.096) and
    # suggests a cell (the local thickness / 4.5: 0.0215) at which nothing is lost. The clipped
    # grid loses nothing.
    r = rf.sqrt(rf.x * rf.x + rf.y * rf.y + rf.z * rf.z) - 0.25
    shell = rf.compile(0.05 ** 2 - r * r, [[-0.32] * 3, [0.32] * 3])
    with pytest.warns(UserWarning, match=r"leaves out .* use cell=0\.02.* or elements='tet'"):
        V, C, B, on, info = interlin.mesh_volume(shell, "hex", cell=0.05, threads=1,
                                                 boundary="projected")
    assert info["lost_volume"] > 0.5 * info["body_volume"]
    assert info["lost_thickness"] == pytest.approx(0.1, rel=0.05)
    assert info["suggested_cell"] == pytest.approx(0.1 / 4.5, rel=0.05)
    V, C, B, on, info = interlin.mesh_volume(shell, "hex", cell=info["suggested_cell"], threads=1,
                                             boundary="projected")
    assert info["lost_volume"] < 0.005 * info["body_volume"]
    assert interlin.volume_quality(V, C, threads=1)["volume"] == pytest.approx(
        info["body_volume"], rel=0.002)
    V, C, B, on, info = interlin.mesh_volume(shell, "tet", cell=0.05, threads=1)
    assert info["body_volume"] == 0 and info["lost_volume"] == 0  # cut: not measured
    # Dual hexahedra keep the wall's node layers at cell 0.05 (measured: 6 % left out, where the
    # wall holds no node); tetrahedra have no dual boundary.
    with pytest.warns(UserWarning, match="slivers under held boundary points"):
        V, C, B, on, info = interlin.mesh_volume(shell, "hex", cell=0.05, threads=1,
                                                 boundary="dual")
    assert interlin.volume_quality(V, C, threads=1)["inverted"] == 0
    assert info["lost_volume"] < 0.1 * info["body_volume"]
    with pytest.raises(ValueError, match="dual"):
        interlin.mesh_volume(shell, "tet", boundary="dual")


def test_pillowed_hexahedra_put_every_boundary_node_on_the_sphere():
    # Pillowed hexahedra of the unit-radius-0.25 ball at 16 cells: every boundary node on F = 0
    # (|F| at round-off of the projection), none inverted, the volume within 2 % of 4/3 pi r^3
    # (the C++ test measures -0.6 % at a similar cell and order 1.9).
    r = rf.sqrt(rf.x * rf.x + rf.y * rf.y + rf.z * rf.z)
    ball = rf.compile(0.25 - r, [[-0.3] * 3, [0.3] * 3])
    V, C, B, on, info = interlin.mesh_volume(ball, "hex", resolution=16, threads=1,
                                             boundary="pillow")
    assert C.shape[1] == 8
    assert np.abs(np.linalg.norm(V[on], axis=1) - 0.25).max() < 1e-8
    q = interlin.volume_quality(V, C, threads=1)
    assert q["inverted"] == 0
    assert q["volume"] == pytest.approx(4 / 3 * np.pi * 0.25 ** 3, rel=0.02)
    with pytest.raises(ValueError, match="hexahedra only"):
        interlin.mesh_volume(ball, "tet", boundary="pillow")


def test_default_hexahedra_are_pillowed():
    # The default hexahedral boundary is the pillow layer (dual where a pillow stays folded): on
    # the ball every boundary node lies on F = 0 and info says which boundary the mesh has.
    r = rf.sqrt(rf.x * rf.x + rf.y * rf.y + rf.z * rf.z)
    ball = rf.compile(0.25 - r, [[-0.3] * 3, [0.3] * 3])
    V, C, B, on, info = interlin.mesh_volume(ball, "hex", resolution=16, threads=1)
    assert info["boundary"] == "pillow" and info["folded_pillows"] == 0
    assert np.abs(np.linalg.norm(V[on], axis=1) - 0.25).max() < 1e-8
    assert interlin.volume_quality(V, C, threads=1)["inverted"] == 0
