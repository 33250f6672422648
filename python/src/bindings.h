#pragma once
// Shared by the binding files of the Python module `interlin` (one file per library module, so
// they compile in parallel): pybind11 with NumPy and Eigen casters, shape checks, and the
// functions that add each module's bindings.
//
// Conventions: points are (N, 3) float64 arrays, triangles (M, 3) int32; results are returned
// without copying (Eigen results are moved into the arrays, which are then Fortran-ordered);
// inputs are converted once when the library needs its own matrix type. Long calls release the
// GIL. Errors: InputError (bad user files, the CLI's one-line message), ValueError (bad
// arguments, std::invalid_argument), RuntimeError (failures, std::runtime_error).

#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/operators.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "interlin/interflatation/implicit_function.h"
#include "interlin/reconstruction/clouds/cloud_implicit.h"
#include "interlin/reconstruction/clouds/prepare_cloud.h"
#include "interlin/reconstruction/io/mesh_io.h"
#include "interlin/reconstruction/io/section_csv.h"
#include "interlin/reconstruction/loft/guided_loft.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace interlin::python {

namespace py = pybind11;

// Releases the GIL for the duration of a bound call: only for bodies that touch no Python object
// (arguments are converted before, results after). Bodies that build Python objects release
// the GIL in an inner scope (py::gil_scoped_release) instead.
using release_gil = py::call_guard<py::gil_scoped_release>;

// A Python callable kept by C++ objects that may be copied and destroyed on threads without the
// GIL (the meshing workers): the last owner takes the GIL to release it.
struct PythonCallable {
  py::function f;
  ~PythonCallable() {
    py::gil_scoped_acquire gil;
    f = py::function();
  }
};

// Throws ValueError "NAME: expected an (N, COLS) array, got (R, C)" unless M has `cols` columns
// (cols < 0: any) and at least `min_rows` rows.
void require_shape(const Eigen::MatrixXd& M, Eigen::Index cols, const char* name,
                   Eigen::Index min_rows = 0);

// MeshPrecision by name: "float64" or "float32" (bind_io.cpp).
MeshPrecision mesh_precision(const std::string& name);

// Source lines 1..n for points made in Python (they name the row in messages).
std::vector<long> row_numbers(Eigen::Index n);

// Boxes cross as (2, 3) arrays [min, max].
Eigen::Matrix<double, 2, 3> box_to_array(const Eigen::AlignedBox3d& box);
Eigen::AlignedBox3d box_from_array(const Eigen::MatrixXd& box); // ValueError unless (2, 3)

// f applied to every element of x (any shape; a Python float gives a float). The library's scalar
// functions (x -> value) become NumPy ufunc-like functions this way.
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
template <class F>
py::object map_elements(const DoubleArray& x, F f) {
  py::array_t<double> out(std::vector<py::ssize_t>(x.shape(), x.shape() + x.ndim()));
  const double* in = x.data();
  double* o = out.mutable_data();
  for (py::ssize_t i = 0; i < x.size(); ++i)
    o[i] = f(in[i]);
  if (x.ndim() == 0)
    return py::float_(o[0]);
  return out;
}

// The enum value named `value` among `names`; ValueError "WHAT: 'value' is not one of a, b, c".
template <class E>
E choice(const std::map<std::string, E>& names, const std::string& value, const char* what) {
  const auto it = names.find(value);
  if (it != names.end())
    return it->second;
  std::string list;
  for (const auto& [name, e] : names)
    list += (list.empty() ? "" : ", ") + name;
  throw py::value_error(std::string(what) + ": '" + value + "' is not one of " + list);
}

// The shape of an elementwise result of two arrays: their common shape, or the other one's when
// one of them is a single value. ValueError otherwise. Index a single value with 0.
std::vector<py::ssize_t> pair_shape(const DoubleArray& a, const DoubleArray& b, const char* names);

// An Implicit's values (N,) and (values, gradients (N, 3)) at points P (N, 3), in blocks, without
// the GIL (bind_rfunctions.cpp).
Eigen::VectorXd values_at(const ImplicitFunction& f, const DoubleArray& P);
py::tuple gradients_at(const ImplicitFunction& f, const DoubleArray& P);

// A struct's fields as a dict {name: value}: fields_dict(r, field("vertices", &R::vertices), ...).
template <class S, class T>
std::pair<const char*, T S::*> field(const char* name, T S::*member) {
  return {name, member};
}
template <class S, class... T>
py::dict fields_dict(const S& s, const std::pair<const char*, T S::*>&... fields) {
  py::dict d;
  ((d[fields.first] = s.*(fields.second)), ...);
  return d;
}

// What prepare_cloud reports and what fit_cloud_implicit measured, as dicts (bind_clouds.cpp).
py::dict cloud_report_dict(const CloudPrepReport& r);
py::dict cloud_fit_dict(const CloudFitInfo& i);
// "auto" | "on" | "off" (bind_clouds.cpp).
SheetNormals sheet_normals_choice(const std::string& s);

// The path of a str or os.PathLike, else nullopt (bind_loft.cpp).
std::optional<std::string> path_of(const py::handle& o);

// Loft inputs as the CLI reads them: a path (str or os.PathLike), a SectionSet, or a list of
// Section objects or (P, 3) arrays (ids "0", "1", ...). bind_loft.cpp.
struct SectionsArg {
  std::vector<Section> sections;
  std::string path; // empty unless read from a file
  std::vector<std::string> warnings;
};
SectionsArg sections_arg(const py::object& o);

// The loft options of loft(), holdout() and implicit() (as `interlin loft`), and the guides.
struct LoftArgs {
  GuidedLoftOptions options;
  std::optional<GuideSet> guides;
};
LoftArgs loft_args(int degree, const py::object& span_degree, const std::string& align,
                   const std::string& match, const py::object& param, const std::string& span,
                   const py::object& guides, double guide_tolerance);

void bind_splines(py::module_& m);         // bind_splines.cpp: B-splines, Theorems 1 and 2
void bind_curves(py::module_& m);          // bind_curves.cpp: natural curves, cascade profiles
void bind_interlineation(py::module_& m);  // bind_interlineation.cpp: Coons, Hermite, Gordon
void bind_rfunctions(py::module_& m);      // bind_rfunctions.cpp: interlin.rf, implicit bodies
void bind_io(py::module_& m);              // bind_io.cpp: section/guide/points files, meshes
void bind_loft(py::module_& m);            // bind_loft.cpp: surfaces, loft, hold-out
void bind_meshing(py::module_& m);         // bind_meshing.cpp: implicit meshes, mesh checks
void bind_clouds(py::module_& m);          // bind_clouds.cpp: point clouds, their implicits
void bind_interflatation(py::module_& m);  // bind_interflatation.cpp: operators, tricubic grid
void bind_implicit_models(py::module_& m); // bind_implicit.cpp: .ifl models, implicit()

} // namespace interlin::python
