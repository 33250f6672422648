"""Volume meshes of implicit solids from Python (seed 003's solid-element method), their quality
and files, and the loft's STEP output."""
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


def test_loft_writes_step_faces_and_solids(tmp_path):
    S = interlin.loft(ROTOR37).surface
    S.write(str(tmp_path / "blade.stp"), units="cm")
    S.write(str(tmp_path / "solid.step"), cap=True)
    face, solid = (tmp_path / "blade.stp").read_text(), (tmp_path / "solid.step").read_text()
    assert face.startswith("ISO-10303-21;") and "B_SPLINE_SURFACE_WITH_KNOTS" in face
    assert "CENTI" in face and "MANIFOLD_SOLID_BREP" not in face
    assert "MANIFOLD_SOLID_BREP" in solid and "CLOSED_SHELL" in solid
