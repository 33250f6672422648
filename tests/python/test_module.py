"""The module itself: import, version, documented shapes, array types, errors as exceptions."""
import numpy as np
import pytest

import interlin


def test_import_and_version():
    assert interlin.__version__.count(".") == 2
    assert interlin.InputError.__mro__[1] is ValueError


@pytest.mark.parametrize("name", ["loft", "holdout", "Surface", "gordon", "hermite_coons",
                                  "mesh_implicit", "load_model", "explicit_bspline",
                                  "read_sections", "cascade_profile", "check_mesh"])
def test_docstrings_give_shapes_or_types(name):
    doc = getattr(interlin, name).__doc__
    assert doc and len(doc) > 80, name


def test_result_arrays_are_float64_and_int32(data_dir):
    L = interlin.loft(data_dir + "/rotor37/sections.csv")
    V, F = L.surface.mesh(nu=40, nv=10)
    assert V.dtype == np.float64 and V.shape[1] == 3
    assert F.dtype == np.int32 and F.shape[1] == 3
    assert L.surface.ctrl.shape == (L.surface.num_u * L.surface.num_v, 3)


def test_attributes_are_views_not_copies(data_dir):
    s = interlin.read_sections(data_dir + "/rotor37/sections.csv")[0]
    a, b = s.points, s.points
    assert np.shares_memory(a, b) and not a.flags.owndata  # both view the C++ matrix


def test_bad_arguments_raise_value_error():
    with pytest.raises(ValueError, match=r"\(N, 3\)"):
        interlin.Surface(1, 1, [0, 0, 1, 1], [0, 0, 1, 1], np.zeros((4, 3)), 2, 2).distance(
            np.zeros((5, 2)))
    with pytest.raises(ValueError, match="align: 'middle' is not one of"):
        interlin.loft([np.zeros((5, 3))] * 2, align="middle")


def test_surface_arrays_are_views_that_keep_the_surface_alive(data_dir):
    S = interlin.loft(data_dir + "/rotor37/sections.csv").surface
    a, b = S.ctrl, S.ctrl
    assert np.shares_memory(a, b) and not a.flags.writeable
    del S
    assert np.isfinite(a).all()  # the view keeps its surface
