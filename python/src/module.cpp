// The extension module interlin._core; python/interlin/__init__.py re-exports it.
#include "bindings.h"

#include "interlin/interflatation/input_error.h"
#include "interlin/reconstruction/clouds/cloud_implicit_ifl.h"

#include <numeric>
#include <sstream>

namespace interlin::python {

void require_shape(const Eigen::MatrixXd& M, Eigen::Index cols, const char* name,
                   Eigen::Index min_rows) {
  if ((cols < 0 || M.cols() == cols) && M.rows() >= min_rows)
    return;
  std::ostringstream s;
  s << name << ": expected an (N, " << (cols < 0 ? std::string("M") : std::to_string(cols))
    << ") array";
  if (min_rows > 0)
    s << " with N >= " << min_rows;
  s << ", got (" << M.rows() << ", " << M.cols() << ")";
  throw py::value_error(s.str());
}

std::vector<py::ssize_t> pair_shape(const DoubleArray& a, const DoubleArray& b, const char* names) {
  const auto shape = [](const DoubleArray& x) {
    return std::vector<py::ssize_t>(x.shape(), x.shape() + x.ndim());
  };
  if (a.size() == 1 && b.size() != 1)
    return shape(b);
  if (b.size() == 1 && a.size() != 1)
    return shape(a);
  if (a.size() == b.size() && (a.ndim() != b.ndim() || shape(a) == shape(b)))
    return shape(a.ndim() >= b.ndim() ? a : b);
  throw py::value_error(std::string(names) +
                        " must have one shape (or one of them a single value)");
}

std::vector<long> row_numbers(Eigen::Index n) {
  std::vector<long> lines(static_cast<size_t>(n));
  std::iota(lines.begin(), lines.end(), 1L);
  return lines;
}

Eigen::Matrix<double, 2, 3> box_to_array(const Eigen::AlignedBox3d& box) {
  Eigen::Matrix<double, 2, 3> b;
  b << box.min().transpose(), box.max().transpose();
  return b;
}

Eigen::AlignedBox3d box_from_array(const Eigen::MatrixXd& box) {
  if (box.rows() != 2 || box.cols() != 3)
    throw py::value_error("box: expected a (2, 3) array [[xmin, ymin, zmin], [xmax, ymax, zmax]]");
  return {box.row(0).transpose(), box.row(1).transpose()};
}

} // namespace interlin::python

PYBIND11_MODULE(_core, m) {
  namespace py = pybind11;
  using namespace interlin::python;
  m.doc() = "interlin: spline-interlineation surface reconstruction (C++ core).";
  m.attr("__version__") = INTERLIN_VERSION;
  // Bad user input (files): the message is the CLI's one line "FILE:LINE: what is wrong".
  py::register_exception<interlin::InputError>(m, "InputError", PyExc_ValueError);
  // .ifl files of point clouds (`interlin implicit SCAN.ply`) load like the CLI's.
  interlin::register_cloud_ifl_kind();
  bind_splines(m);
  bind_curves(m);
  bind_interlineation(m);
  bind_rfunctions(m);
  bind_io(m);
  bind_loft(m);
  bind_meshing(m);
  bind_clouds(m);
  bind_interflatation(m);
  bind_implicit_models(m);
}
