// Evaluator and .ifl block of section bodies (models/section_body.h).
#include "interlin/interflatation/models/section_body.h"

#include "far_field.h"

#include <cmath>
#include <memory>
#include <stdexcept>

namespace interlin {

using Eigen::Index;
using Eigen::Vector3d;

double band_weight(double r, double inner, double outer, double* slope) {
  if (slope)
    *slope = 0;
  if (r <= inner)
    return 1;
  if (r >= outer)
    return 0;
  const double w = outer - inner, x = (r - inner) / w;
  if (slope)
    *slope = -30 * x * x * (x - 1) * (x - 1) / w;
  return 1 - x * x * x * (x * (6 * x - 15) + 10);
}

namespace {

long cell_count(const NodeGrid& g) {
  return static_cast<long>(g.n(0) - 1) * (g.n(1) - 1) * (g.n(2) - 1);
}

void check_model(const SectionBodyModel& m) {
  if (static_cast<long>(m.grid.values.size()) !=
      static_cast<long>(m.grid.n(0)) * m.grid.n(1) * m.grid.n(2))
    throw std::invalid_argument("section body: grid values do not match the node counts");
  if (m.band_start.size() != m.band_cells.size() + 1 || m.band_start.front() != 0 ||
      m.band_start.back() != static_cast<std::int64_t>(m.seeds.size()))
    throw std::invalid_argument("section body: band offsets do not match the starts");
  for (size_t i = 1; i < m.band_start.size(); ++i)
    if (m.band_start[i] < m.band_start[i - 1])
      throw std::invalid_argument("section body: band offsets must not decrease");
  for (size_t i = 0; i < m.band_cells.size(); ++i)
    if (m.band_cells[i] < 0 || m.band_cells[i] >= cell_count(m.grid) ||
        (i > 0 && m.band_cells[i] <= m.band_cells[i - 1]))
      throw std::invalid_argument("section body: band cells must be increasing grid cells");
  for (const PatchSeed& s : m.seeds)
    if (s.patch < 0 || s.patch > 2 || !std::isfinite(s.u) || !std::isfinite(s.v))
      throw std::invalid_argument("section body: a seed names no patch");
  if (!valid_band(m.band_inner, m.band_outer))
    throw std::invalid_argument("section body: the band needs 0 < inner < outer");
  if (m.box.isEmpty())
    throw std::invalid_argument("section body: empty box");
}

struct State {
  SectionBodyModel model;
  BodyPatches patches;
  CubicGrid far;
  std::vector<int> band_of_cell; // per grid cell: index into band_cells, -1 outside the band

  // The near-field starts of the grid cell holding p (none outside the band).
  std::pair<const PatchSeed*, int> starts(const Vector3d& p) const {
    const NodeGrid& g = model.grid;
    long c[3];
    for (int a = 0; a < 3; ++a) {
      const double t = std::floor((p(a) - g.origin(a)) / g.h);
      if (!(t >= 0 && t < g.n(a) - 1))
        return {nullptr, 0};
      c[a] = static_cast<long>(t);
    }
    const int b =
        band_of_cell[static_cast<size_t>(c[0] + (g.n(0) - 1) * (c[1] + (g.n(1) - 1) * c[2]))];
    if (b < 0)
      return {nullptr, 0};
    const std::int64_t s = model.band_start[static_cast<size_t>(b)],
                       e = model.band_start[static_cast<size_t>(b) + 1];
    return {model.seeds.data() + s, static_cast<int>(e - s)};
  }
};

double evaluate_point(const State& s, const Vector3d& p, Vector3d& g) {
  const auto [seeds, count] = s.starts(p);
  const BodyDistance d = count > 0 ? body_distance(s.patches, p, seeds, count) : BodyDistance{};
  // Within the inner band omega is the near field alone (blend weight 1): no far field needed.
  if (d.found && std::abs(d.distance) <= s.model.band_inner) {
    g = d.gradient;
    return d.distance;
  }
  Vector3d gf;
  const double f = detail::far_field(s.far, p, gf);
  if (!d.found) {
    g = gf;
    return f;
  }
  return detail::blend(d.distance, d.gradient, f, gf, s.model.band_inner, s.model.band_outer, g);
}

} // namespace

ImplicitFunction section_body_function(const SectionBodyModel& m) {
  check_model(m);
  auto s = std::make_shared<State>();
  s->model = m;
  s->patches = body_patches(m.side, m.edge_u);
  s->far = cubic_grid(m.grid.values, m.grid.origin, m.grid.h, m.grid.n);
  s->band_of_cell.assign(static_cast<size_t>(cell_count(m.grid)), -1);
  for (size_t b = 0; b < m.band_cells.size(); ++b)
    s->band_of_cell[static_cast<size_t>(m.band_cells[b])] = static_cast<int>(b);
  ImplicitFunction f;
  f.box = m.box;
  f.value = [s](const Eigen::Ref<const Points3>& P, Eigen::Ref<Eigen::VectorXd> F) {
    Vector3d g;
    for (Index i = 0; i < P.rows(); ++i)
      F(i) = evaluate_point(*s, P.row(i).transpose(), g);
  };
  f.gradient = [s](const Eigen::Ref<const Points3>& P, Eigen::Ref<Eigen::VectorXd> F,
                   Eigen::Ref<Points3> G) {
    Vector3d g;
    for (Index i = 0; i < P.rows(); ++i) {
      F(i) = evaluate_point(*s, P.row(i).transpose(), g);
      G.row(i) = g.transpose();
    }
  };
  return f;
}

IflBlock to_ifl(const SectionBodyModel& m) {
  check_model(m);
  IflBlock b;
  b.kind = "section_body";
  b.name = "model";
  b.set("version", 1);
  set_band(b, {m.box, m.band_inner, m.band_outer});
  b.set_f64("edge_u", {2, 2}, {m.edge_u[0](0), m.edge_u[0](1), m.edge_u[1](0), m.edge_u[1](1)});
  b.set_i64("band_cells", {static_cast<long>(m.band_cells.size())}, m.band_cells);
  b.set_i64("band_start", {static_cast<long>(m.band_start.size())}, m.band_start);
  std::vector<std::int64_t> patch(m.seeds.size());
  std::vector<double> uv(2 * m.seeds.size());
  for (size_t i = 0; i < m.seeds.size(); ++i) {
    patch[i] = m.seeds[i].patch;
    uv[2 * i] = m.seeds[i].u;
    uv[2 * i + 1] = m.seeds[i].v;
  }
  const long count = static_cast<long>(m.seeds.size());
  b.set_i64("seed_patch", {count}, std::move(patch));
  b.set_f64("seed_uv", {count, 2}, std::move(uv));
  b.blocks.push_back(surface_block("side", m.side));
  b.blocks.push_back(grid_block("distance", m.grid));
  return b;
}

SectionBodyModel section_body_from_ifl(const IflBlock& b) {
  b.expect("section_body", 1);
  SectionBodyModel m;
  const IflBand band = band_from_block(b);
  m.box = band.box;
  m.band_inner = band.inner;
  m.band_outer = band.outer;
  const std::vector<double>& e = b.f64("edge_u", {2, 2});
  m.edge_u = {Eigen::Vector2d(e[0], e[1]), Eigen::Vector2d(e[2], e[3])};
  m.side = surface_from_block(b.block("side"));
  m.grid = distance_grid_from_block(b, m.box);
  m.band_cells = b.i64("band_cells", {-1});
  m.band_start = b.i64("band_start", {static_cast<long>(m.band_cells.size()) + 1});
  const std::vector<std::int64_t>& patch = b.i64("seed_patch", {-1});
  const std::vector<double>& uv = b.f64("seed_uv", {static_cast<long>(patch.size()), 2});
  m.seeds.resize(patch.size());
  for (size_t i = 0; i < patch.size(); ++i) {
    if (patch[i] < 0 || patch[i] > 2)
      b.fail("seed_patch: patches are 0, 1 or 2");
    m.seeds[i] = {static_cast<int>(patch[i]), uv[2 * i], uv[2 * i + 1]};
  }
  try {
    check_model(m);
    body_patches(m.side, m.edge_u);
  } catch (const std::invalid_argument& err) {
    b.fail(err.what());
  }
  return m;
}

} // namespace interlin
