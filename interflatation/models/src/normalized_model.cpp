// Evaluator and .ifl block of normalised R-function models (models/normalized_model.h).
#include "interlin/interflatation/models/normalized_model.h"

#include "far_field.h"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

namespace interlin {

using Eigen::Index;
using Eigen::Vector3d;
using Eigen::VectorXd;

namespace {

constexpr int kNewtonSteps = 8; // crossing search along grad F: quadratic, 3-4 steps typical

struct State {
  NormalizedModel model;
  ImplicitFunction F;
  CubicGrid far;
};

// The near field at the rows `rows` of P: d (distance to the tangent plane at the crossing) and
// its gradient n(q). F0, G0: F and grad F at P.
void near_field(const State& s, const Eigen::Ref<const Points3>& P, const VectorXd& F0,
                const Points3& G0, const std::vector<Index>& rows, VectorXd& d, Points3& gd) {
  const Index m = static_cast<Index>(rows.size());
  Points3 dir(m, 3), Q(m, 3), Gq(m, 3);
  VectorXd t = VectorXd::Zero(m), Fq(m);
  std::vector<char> ok(static_cast<size_t>(m), 1);
  for (Index k = 0; k < m; ++k) {
    const Index i = rows[static_cast<size_t>(k)];
    const double gn = G0.row(i).norm();
    dir.row(k) = G0.row(i) / gn;
    t(k) = -F0(i) / gn; // first Newton step from p itself (grad F . dir = |grad F|)
    Fq(k) = F0(i);
    Gq.row(k) = G0.row(i);
  }
  const double reach = 2 * s.model.band_outer;
  for (int it = 1; it < kNewtonSteps; ++it) {
    for (Index k = 0; k < m; ++k)
      Q.row(k) = P.row(rows[static_cast<size_t>(k)]) + t(k) * dir.row(k);
    s.F.gradient(Q, Fq, Gq);
    bool moved = false;
    for (Index k = 0; k < m; ++k) {
      const double slope = Gq.row(k).dot(dir.row(k));
      if (!ok[static_cast<size_t>(k)] || Fq(k) == 0)
        continue;
      if (!(slope > 0) || !(std::abs(t(k)) <= reach)) {
        ok[static_cast<size_t>(k)] = 0;
        continue;
      }
      const double step = Fq(k) / slope;
      t(k) -= step;
      moved = moved || std::abs(step) > 1e-16 * (std::abs(t(k)) + reach);
    }
    if (!moved)
      break;
  }
  for (Index k = 0; k < m; ++k)
    Q.row(k) = P.row(rows[static_cast<size_t>(k)]) + t(k) * dir.row(k);
  s.F.gradient(Q, Fq, Gq);
  for (Index k = 0; k < m; ++k) {
    const Index i = rows[static_cast<size_t>(k)];
    const double gq = Gq.row(k).norm();
    // Converged: F(q) at round-off of the function's scale near q.
    const bool good = ok[static_cast<size_t>(k)] && gq > 0 && std::abs(t(k)) <= reach &&
                      std::abs(Fq(k)) <= 1e-9 * gq * s.model.band_outer;
    if (good) {
      const Vector3d n = Gq.row(k).transpose() / gq;
      d(i) = -t(k) * dir.row(k).dot(n.transpose());
      gd.row(i) = n.transpose();
    } else {
      const double gn = G0.row(i).norm();
      d(i) = F0(i) / gn;
      gd.row(i) = G0.row(i) / gn;
    }
  }
}

void evaluate_batch(const State& s, const Eigen::Ref<const Points3>& P, Eigen::Ref<VectorXd> out,
                    Points3* grad) {
  const Index n = P.rows();
  VectorXd F0(n);
  Points3 G0(n, 3);
  s.F.gradient(P, F0, G0);
  VectorXd f(n), d(n);
  Points3 gf(n, 3), gd(n, 3);
  std::vector<Index> rows;
  for (Index i = 0; i < n; ++i) {
    Vector3d g;
    f(i) = detail::far_field(s.far, P.row(i).transpose(), g);
    gf.row(i) = g.transpose();
    if (std::abs(f(i)) < s.model.band_outer && G0.row(i).norm() > 0 && std::isfinite(F0(i)))
      rows.push_back(i);
  }
  std::vector<char> near(static_cast<size_t>(n), 0);
  if (!rows.empty())
    near_field(s, P, F0, G0, rows, d, gd);
  for (Index i : rows)
    near[static_cast<size_t>(i)] = 1;
  for (Index i = 0; i < n; ++i) {
    Vector3d g = gf.row(i).transpose();
    double w = f(i);
    if (near[static_cast<size_t>(i)])
      w = detail::blend(d(i), gd.row(i).transpose(), f(i), gf.row(i).transpose(),
                        s.model.band_inner, s.model.band_outer, g);
    out(i) = w;
    if (grad)
      grad->row(i) = g.transpose();
  }
}

} // namespace

ImplicitFunction normalized_model_function(const NormalizedModel& m) {
  if (!valid_band(m.band_inner, m.band_outer))
    throw std::invalid_argument("normalized model: the band needs 0 < inner < outer");
  if (static_cast<long>(m.grid.values.size()) !=
      static_cast<long>(m.grid.n(0)) * m.grid.n(1) * m.grid.n(2))
    throw std::invalid_argument("normalized model: grid values do not match the node counts");
  auto s = std::make_shared<State>();
  s->model = m;
  s->F = parse_model(m.source, m.path, m.options);
  s->far = cubic_grid(m.grid.values, m.grid.origin, m.grid.h, m.grid.n);
  ImplicitFunction f;
  f.box = m.box;
  f.value = [s](const Eigen::Ref<const Points3>& P, Eigen::Ref<VectorXd> F) {
    evaluate_batch(*s, P, F, nullptr);
  };
  f.gradient = [s](const Eigen::Ref<const Points3>& P, Eigen::Ref<VectorXd> F,
                   Eigen::Ref<Points3> G) {
    Points3 g(P.rows(), 3);
    evaluate_batch(*s, P, F, &g);
    G = g;
  };
  return f;
}

IflBlock to_ifl(const NormalizedModel& m) {
  IflBlock b;
  b.kind = "normalized_rf";
  b.name = "model";
  b.set("version", 1);
  set_band(b, {m.box, m.band_inner, m.band_outer});
  b.set_text("source", m.source);
  b.set_text("path", m.path);
  b.set_text("output", m.options.output);
  IflBlock params;
  params.kind = "parameters";
  params.name = "parameters";
  for (const auto& [name, v] : m.options.parameters)
    params.set(name, v);
  b.blocks.push_back(std::move(params));
  b.blocks.push_back(grid_block("distance", m.grid));
  return b;
}

NormalizedModel normalized_model_from_ifl(const IflBlock& b) {
  b.expect("normalized_rf", 1);
  NormalizedModel m;
  const IflBand band = band_from_block(b);
  m.box = band.box;
  m.band_inner = band.inner;
  m.band_outer = band.outer;
  m.source = b.text("source");
  m.path = b.text("path");
  m.options.output = b.text("output");
  m.options.parameters = std::map<std::string, double>(b.block("parameters").numbers);
  m.grid = distance_grid_from_block(b, m.box);
  return m;
}

} // namespace interlin
