// seed 001 §2.5: surface of a body from section lines; §2.2: closed section curves.
#include "interlin/reconstruction/loft.h"

#include "interlin/interlineation/interlinate_curves.h"
#include "interlin/splines/interpolate_curve.h"
#include "interlin/splines/knot_insertion.h"
#include "interlin/splines/knots.h"
#include "interlin/splines/parameterization.h"
#include "interlin/splines/spline_basis.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// Section parameters: cumulative chord^exponent from the start, normalised; with a landmark row
// m (the opposite edge), the two arcs start -> m and m -> start are mapped linearly onto
// [0, f] and [f, 1] so that the landmark sits at the common fraction f.
VectorXd section_parameters(const MatrixXd& P, double exponent, Index m, double f) {
  VectorXd s = chord_parameters(P, true, exponent);
  if (m <= 0)
    return s;
  const double sm = s(m);
  for (Index i = 0; i < s.size(); ++i)
    s(i) = i <= m ? f * s(i) / sm : f + (1 - f) * (s(i) - sm) / (1 - sm);
  s(m) = f;
  s(s.size() - 1) = 1.0;
  return s;
}

// Parameters closer than `tol` in different sections are made equal (the first value wins), so
// that the knot union does not create spans many orders of magnitude shorter than their
// neighbours. Values of one section are never merged with each other.
void snap_parameters(std::vector<VectorXd>& u, double tol) {
  struct Entry {
    double value;
    size_t section;
    Index row;
  };
  std::vector<Entry> all;
  for (size_t k = 0; k < u.size(); ++k)
    for (Index i = 1; i + 1 < u[k].size(); ++i)
      all.push_back({u[k](i), k, i});
  std::sort(all.begin(), all.end(),
            [](const Entry& a, const Entry& b) { return a.value < b.value; });
  for (size_t i = 0; i < all.size();) {
    size_t j = i + 1;
    std::vector<size_t> seen = {all[i].section};
    while (j < all.size() && all[j].value - all[i].value < tol &&
           std::find(seen.begin(), seen.end(), all[j].section) == seen.end()) {
      seen.push_back(all[j].section);
      u[all[j].section](all[j].row) = all[i].value;
      ++j;
    }
    i = j;
  }
}

} // namespace

LoftResult loft_sections(const std::vector<Section>& sections, const LoftOptions& o) {
  const Index K = static_cast<Index>(sections.size());
  if (K < 2)
    throw std::invalid_argument("a loft needs at least 2 sections, got " + std::to_string(K));
  if (o.degree < 1 || o.span_degree < 1)
    throw std::invalid_argument("degrees must be >= 1");
  for (const Section& s : sections)
    if (s.points.rows() < std::max(4, o.degree + 1))
      throw std::invalid_argument("section " + s.id + " has " + std::to_string(s.points.rows()) +
                                  " points; degree " + std::to_string(o.degree) +
                                  " needs at least " + std::to_string(std::max(4, o.degree + 1)));
  LoftResult r;
  r.sections = prepare_sections(sections, o.align, r.notes);

  // The opposite edge is a second landmark when the start is an aligned edge.
  std::vector<Index> landmark(static_cast<size_t>(K), 0);
  double f = 0;
  if (o.align != StartAlign::first) {
    for (Index k = 0; k < K; ++k) {
      const PreparedSection& s = r.sections[static_cast<size_t>(k)];
      landmark[static_cast<size_t>(k)] = o.align == StartAlign::leading_edge ? s.te : s.le;
      f += chord_parameters(s.points, true, o.section_exponent)(landmark[static_cast<size_t>(k)]) /
           K;
    }
  }
  bool same_rows = true;
  for (Index k = 1; k < K; ++k)
    same_rows = same_rows && r.sections[k].points.rows() == r.sections[0].points.rows() &&
                landmark[static_cast<size_t>(k)] == landmark[0];
  if (o.match == Correspondence::index && !same_rows)
    throw std::invalid_argument(
        "index correspondence needs sections with equal point counts" +
        std::string(o.align != StartAlign::first ? " and the opposite edge at the same row" : ""));
  r.used = (o.match == Correspondence::arc_length || !same_rows) ? Correspondence::arc_length
                                                                 : Correspondence::index;

  r.point_u.resize(static_cast<size_t>(K));
  for (Index k = 0; k < K; ++k)
    r.point_u[static_cast<size_t>(k)] = section_parameters(r.sections[k].points, o.section_exponent,
                                                           landmark[static_cast<size_t>(k)], f);
  if (r.used == Correspondence::index) {
    VectorXd mean = VectorXd::Zero(r.point_u[0].size());
    for (const VectorXd& u : r.point_u)
      mean += u / static_cast<double>(K);
    mean(0) = 0;
    mean(mean.size() - 1) = 1;
    std::fill(r.point_u.begin(), r.point_u.end(), mean);
  } else {
    // 1e-5 of the unit parameter range: spans at least ~1e-3 of their typical neighbours, well
    // inside the range where the explicit basis is exact to round-off (docs/formulas.md).
    snap_parameters(r.point_u, 1e-5);
  }

  // Closed section curves (seed 001 §2.2), clamped at u = 0 so that all share the domain [0, 1].
  std::vector<BSplineCurve> curves;
  if (r.used == Correspondence::index) {
    // One knot vector and one collocation matrix for all sections: solve once with the sections
    // side by side as 3K columns.
    const Index n = r.sections[0].points.rows();
    MatrixXd P(n, 3 * K);
    for (Index k = 0; k < K; ++k)
      P.middleCols(3 * k, 3) = r.sections[k].points;
    const BSplineCurve all =
        periodic_to_clamped(interpolate_closed(P, r.point_u[0], o.degree), 0.0);
    for (Index k = 0; k < K; ++k)
      curves.push_back({all.degree, all.knots, all.ctrl.middleCols(3 * k, 3), false});
  } else {
    for (Index k = 0; k < K; ++k)
      curves.push_back(periodic_to_clamped(
          interpolate_closed(r.sections[k].points, r.point_u[static_cast<size_t>(k)], o.degree),
          0.0));
    curves = make_compatible(curves);
  }

  // Span parameters from the mean distance between neighbouring section curves, measured at 256
  // common parameters (all curves share one basis now).
  const VectorXd probe = VectorXd::LinSpaced(257, 0, 1).head(256);
  const SplineBasis basis = explicit_basis(curves[0].knots, curves[0].degree);
  std::vector<Index> rows, cols;
  std::vector<double> vals;
  collocation_entries(basis, probe, 0, 0, rows, cols, vals);
  const auto probe_points = [&](const MatrixXd& ctrl) {
    MatrixXd out = MatrixXd::Zero(probe.size(), 3);
    for (size_t e = 0; e < vals.size(); ++e)
      out.row(rows[e]) += vals[e] * ctrl.row(cols[e]);
    return out;
  };
  MatrixXd prev = probe_points(curves[0].ctrl);
  r.section_v.resize(K);
  r.section_v(0) = 0;
  for (Index k = 1; k < K; ++k) {
    const MatrixXd cur = probe_points(curves[static_cast<size_t>(k)].ctrl);
    const double d = (cur - prev).rowwise().norm().mean();
    if (!(d > 0))
      throw std::invalid_argument("sections " + r.sections[k - 1].id + " and " + r.sections[k].id +
                                  " coincide");
    r.section_v(k) = r.section_v(k - 1) + std::pow(d, o.span_exponent);
    prev = cur;
  }
  r.section_v /= r.section_v(K - 1);
  r.section_v(K - 1) = 1.0;

  r.surface = interlinate_curves(curves, r.section_v, o.span_degree, true);

  // The interlineation property, checked at every input point: S(u_i, v_k) = sum_i N_i(u) R_i
  // with the row curve R = sum_j M_j(v_k) ctrl(., j) of the surface at v_k.
  const BSplineSurface& S = r.surface;
  const SplineBasis basis_v = explicit_basis(S.knots_v, S.degree_v);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (Index k = 0; k < K; ++k) {
    Index span;
    const MatrixXd M = basis_derivatives(basis_v, r.section_v(k), 0, &span);
    MatrixXd R = MatrixXd::Zero(S.num_u, 3);
    for (int j = 0; j <= S.degree_v; ++j)
      R += M(0, j) * S.ctrl.middleRows(S.num_u * (span - S.degree_v + j), S.num_u);
    const MatrixXd& P = r.sections[k].points;
    const VectorXd& u = r.point_u[static_cast<size_t>(k)];
    VectorXd dev(P.rows());
    for (Index i = 0; i < P.rows(); ++i) {
      const MatrixXd N = basis_derivatives(basis, u(i), 0, &span);
      Eigen::RowVector3d x = Eigen::RowVector3d::Zero();
      for (int q = 0; q <= S.degree_u; ++q)
        x += N(0, q) * R.row(span - S.degree_u + q);
      dev(i) = (x - P.row(i)).norm();
      lo = lo.cwiseMin(P.row(i).transpose());
      hi = hi.cwiseMax(P.row(i).transpose());
    }
    r.max_deviation = std::max(r.max_deviation, dev.maxCoeff());
    r.deviation.push_back(dev);
  }
  r.bbox_diagonal = (hi - lo).norm();
  if (!(r.max_deviation <= 1e-9 * r.bbox_diagonal))
    throw std::runtime_error("loft: surface deviates from the input points by " +
                             std::to_string(r.max_deviation) +
                             " (more than 1e-9 x bounding-box diagonal); refusing to continue");
  return r;
}

} // namespace interlin
