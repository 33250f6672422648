#include "interlin/interflatation/models/ifl_codecs.h"

#include <cmath>
#include <stdexcept>

namespace interlin {

using Eigen::Index;

IflBlock surface_block(const std::string& name, const BSplineSurface& s) {
  IflBlock b;
  b.kind = "bspline_surface";
  b.name = name;
  b.set("degree_u", s.degree_u);
  b.set("degree_v", s.degree_v);
  b.set("closed_u", s.closed_u ? 1 : 0);
  b.set_f64("knots_u", {static_cast<long>(s.knots_u.size())},
            std::vector<double>(s.knots_u.data(), s.knots_u.data() + s.knots_u.size()));
  b.set_f64("knots_v", {static_cast<long>(s.knots_v.size())},
            std::vector<double>(s.knots_v.data(), s.knots_v.data() + s.knots_v.size()));
  std::vector<double> ctrl(static_cast<size_t>(s.ctrl.rows() * 3));
  for (Index i = 0; i < s.ctrl.rows(); ++i)
    for (int c = 0; c < 3; ++c)
      ctrl[static_cast<size_t>(3 * i + c)] = s.ctrl(i, c);
  b.set_f64("ctrl", {static_cast<long>(s.ctrl.rows()), 3}, std::move(ctrl));
  return b;
}

BSplineSurface surface_from_block(const IflBlock& b) {
  if (b.kind != "bspline_surface")
    b.fail("expected a bspline_surface block");
  BSplineSurface s;
  s.degree_u = static_cast<int>(b.integer("degree_u", 1, 15));
  s.degree_v = static_cast<int>(b.integer("degree_v", 1, 15));
  s.closed_u = b.integer("closed_u", 0, 1) == 1;
  const std::vector<double>& ku = b.f64("knots_u", {-1});
  const std::vector<double>& kv = b.f64("knots_v", {-1});
  s.knots_u = Eigen::Map<const Eigen::VectorXd>(ku.data(), static_cast<Index>(ku.size()));
  s.knots_v = Eigen::Map<const Eigen::VectorXd>(kv.data(), static_cast<Index>(kv.size()));
  s.num_u = s.knots_u.size() - s.degree_u - 1;
  s.num_v = s.knots_v.size() - s.degree_v - 1;
  if (s.num_u < s.degree_u + 1 || s.num_v < s.degree_v + 1)
    b.fail("too few knots for the degrees");
  const std::vector<double>& c = b.f64("ctrl", {s.num_u * s.num_v, 3});
  s.ctrl.resize(s.num_u * s.num_v, 3);
  for (Index i = 0; i < s.ctrl.rows(); ++i)
    for (int k = 0; k < 3; ++k)
      s.ctrl(i, k) = c[static_cast<size_t>(3 * i + k)];
  try {
    check_surface(s);
  } catch (const std::invalid_argument& e) {
    b.fail(e.what());
  }
  return s;
}

IflBlock grid_block(const std::string& name, const NodeGrid& g) {
  IflBlock b;
  b.kind = "node_grid";
  b.name = name;
  b.set_f64("origin", {3}, {g.origin(0), g.origin(1), g.origin(2)});
  b.set("h", g.h);
  b.set_i64("n", {3}, {g.n(0), g.n(1), g.n(2)});
  b.set_f64("values", {g.n(2), g.n(1), g.n(0)}, g.values);
  return b;
}

NodeGrid grid_from_block(const IflBlock& b) {
  if (b.kind != "node_grid")
    b.fail("expected a node_grid block");
  NodeGrid g;
  const std::vector<double>& o = b.f64("origin", {3});
  g.origin = Eigen::Vector3d(o[0], o[1], o[2]);
  g.h = b.number("h");
  if (!(g.h > 0 && std::isfinite(g.h)))
    b.fail("number 'h' must be > 0");
  const std::vector<std::int64_t>& n = b.i64("n", {3});
  for (int a = 0; a < 3; ++a) {
    if (n[static_cast<size_t>(a)] < 2 || n[static_cast<size_t>(a)] > 100000)
      b.fail("array 'n': node counts must be from 2 to 100000");
    g.n(a) = static_cast<int>(n[static_cast<size_t>(a)]);
  }
  g.values = b.f64("values", {g.n(2), g.n(1), g.n(0)});
  // The values are signed distances to a boundary inside the grid: none is beyond its diagonal
  // (twice, for slack). Larger ones are no distances and overflow the tricubic interpolant.
  const double diagonal = g.h * (g.n.cast<double>() - 1).matrix().norm();
  for (const double v : g.values)
    if (!(std::abs(v) <= 2 * diagonal))
      b.fail("array 'values': a value beyond twice the grid's diagonal is no distance");
  return g;
}

NodeGrid distance_grid_from_block(const IflBlock& model, const Eigen::AlignedBox3d& box) {
  NodeGrid g = grid_from_block(model.block("distance"));
  const Eigen::Vector3d end = g.origin + g.h * (g.n.cast<double>() - 1).matrix();
  if (!((box.min().array() >= g.origin.array()).all() && (box.max().array() <= end.array()).all()))
    model.fail("the box must lie within the node grid 'distance'");
  return g;
}

void set_box(IflBlock& b, const std::string& name, const Eigen::AlignedBox3d& box) {
  b.set_f64(name, {6},
            {box.min()(0), box.min()(1), box.min()(2), box.max()(0), box.max()(1), box.max()(2)});
}

Eigen::AlignedBox3d box_from_block(const IflBlock& b, const std::string& name) {
  const std::vector<double>& v = b.f64(name, {6});
  if (!(v[0] < v[3] && v[1] < v[4] && v[2] < v[5]))
    b.fail("array '" + name + "': each upper bound must exceed its lower bound");
  return Eigen::AlignedBox3d(Eigen::Vector3d(v[0], v[1], v[2]), Eigen::Vector3d(v[3], v[4], v[5]));
}

bool valid_band(double inner, double outer) {
  return inner > 0 && outer > inner;
}

void set_band(IflBlock& b, const IflBand& band) {
  set_box(b, "box", band.box);
  b.set("band_inner", band.inner);
  b.set("band_outer", band.outer);
}

IflBand band_from_block(const IflBlock& b) {
  IflBand band;
  band.box = box_from_block(b, "box");
  band.inner = b.number("band_inner");
  band.outer = b.number("band_outer");
  if (!valid_band(band.inner, band.outer))
    b.fail("the band needs 0 < band_inner < band_outer");
  return band;
}

} // namespace interlin
