// seed 001 §2.5: section curves of a body on one knot vector; §2.2: closed section curves.
#include "section_curves.h"

#include "interlin/splines/interpolate_curve.h"
#include "interlin/splines/knot_insertion.h"
#include "interlin/splines/parameterization.h"
#include "interlin/splines/spline_basis.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace interlin::detail {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

void check_loft_inputs(const std::vector<Section>& sections, const LoftOptions& o) {
  if (sections.size() < 2)
    throw std::invalid_argument("a loft needs at least 2 sections, got " +
                                std::to_string(sections.size()));
  if (o.degree < 1 || (o.span_degree < 1 && o.span_degree != kAutoSpanDegree))
    throw std::invalid_argument("degrees must be >= 1");
  const Index need = std::max(4, o.degree + 1);
  for (const Section& s : sections)
    if (s.points.rows() < need)
      throw std::invalid_argument("section " + s.id + " has " + std::to_string(s.points.rows()) +
                                  " points; degree " + std::to_string(o.degree) +
                                  " needs at least " + std::to_string(need));
}

std::vector<std::vector<Index>> edge_landmarks(const std::vector<PreparedSection>& sections,
                                               StartAlign align) {
  std::vector<std::vector<Index>> landmarks(sections.size());
  if (align != StartAlign::first)
    for (size_t k = 0; k < sections.size(); ++k)
      landmarks[k] = {align == StartAlign::leading_edge ? sections[k].te : sections[k].le};
  return landmarks;
}

namespace {

// Section parameters: cumulative chord^exponent from the start, normalised; with landmark rows
// m_1 < m_2 < ..., each arc between consecutive landmarks (the start at 0 and the closing point
// at 1 included) is mapped linearly onto [F_a, F_b], so that landmark j sits at the common
// fraction F_j.
VectorXd section_parameters(const MatrixXd& P, double exponent, const std::vector<Index>& m,
                            const std::vector<double>& F) {
  VectorXd s = chord_parameters(P, true, exponent);
  if (m.empty())
    return s;
  const Index n = s.size();
  std::vector<Index> rows = {0};
  std::vector<double> sv = {0.0}, fv = {0.0};
  for (size_t j = 0; j < m.size(); ++j) {
    rows.push_back(m[j]);
    sv.push_back(s(m[j]));
    fv.push_back(F[j]);
  }
  rows.push_back(n - 1);
  sv.push_back(1.0);
  fv.push_back(1.0);
  VectorXd out(n);
  size_t a = 0;
  for (Index i = 0; i < n; ++i) {
    while (a + 2 < rows.size() && i > rows[a + 1])
      ++a;
    out(i) = fv[a] + (fv[a + 1] - fv[a]) * (s(i) - sv[a]) / (sv[a + 1] - sv[a]);
  }
  for (size_t j = 1; j + 1 < rows.size(); ++j)
    out(rows[j]) = fv[j];
  out(n - 1) = 1.0;
  return out;
}

} // namespace

void snap_values(std::vector<VectorXd>& u, Index ends, const std::function<double(double)>& tol) {
  struct Entry {
    double value;
    size_t vector;
    Index row;
  };
  std::vector<Entry> all;
  for (size_t k = 0; k < u.size(); ++k)
    for (Index i = ends; i + ends < u[k].size(); ++i)
      all.push_back({u[k](i), k, i});
  std::sort(all.begin(), all.end(),
            [](const Entry& a, const Entry& b) { return a.value < b.value; });
  for (size_t i = 0; i < all.size();) {
    size_t j = i + 1;
    std::vector<size_t> seen = {all[i].vector};
    while (j < all.size() && all[j].value - all[i].value < tol(all[i].value) &&
           std::find(seen.begin(), seen.end(), all[j].vector) == seen.end()) {
      seen.push_back(all[j].vector);
      u[all[j].vector](all[j].row) = all[i].value;
      ++j;
    }
    i = j;
  }
}

SectionCurves section_curves(const std::vector<PreparedSection>& sections,
                             const std::vector<std::vector<Index>>& landmarks,
                             const LoftOptions& o) {
  const Index K = static_cast<Index>(sections.size());
  SectionCurves r;
  // Common fraction of each landmark: the mean of the sections' own chord fractions there.
  const size_t nm = landmarks[0].size();
  r.landmark_u.assign(nm, 0.0);
  for (Index k = 0; k < K; ++k) {
    if (landmarks[static_cast<size_t>(k)].size() != nm)
      throw std::invalid_argument("every section needs the same number of landmarks");
    const VectorXd s =
        chord_parameters(sections[static_cast<size_t>(k)].points, true, o.section_exponent);
    for (size_t j = 0; j < nm; ++j)
      r.landmark_u[j] += s(landmarks[static_cast<size_t>(k)][j]) / static_cast<double>(K);
  }
  bool same_rows = true;
  for (Index k = 1; k < K; ++k)
    same_rows = same_rows && sections[k].points.rows() == sections[0].points.rows() &&
                landmarks[static_cast<size_t>(k)] == landmarks[0];
  if (o.match == Correspondence::index && !same_rows)
    throw std::invalid_argument(
        "index correspondence needs sections with equal point counts" +
        std::string(nm > 0 ? " and the opposite edge (and guide crossings) at the same rows" : ""));
  r.used = (o.match == Correspondence::arc_length || !same_rows) ? Correspondence::arc_length
                                                                 : Correspondence::index;

  r.point_u.resize(static_cast<size_t>(K));
  for (Index k = 0; k < K; ++k)
    r.point_u[static_cast<size_t>(k)] = section_parameters(
        sections[k].points, o.section_exponent, landmarks[static_cast<size_t>(k)], r.landmark_u);
  if (r.used == Correspondence::index) {
    VectorXd mean = VectorXd::Zero(r.point_u[0].size());
    for (const VectorXd& u : r.point_u)
      mean += u / static_cast<double>(K);
    mean(0) = 0;
    mean(mean.size() - 1) = 1;
    std::fill(r.point_u.begin(), r.point_u.end(), mean);
    for (size_t j = 0; j < nm; ++j) // the landmarks' common parameters are the mean's
      r.landmark_u[j] = mean(landmarks[0][j]);
  } else {
    // 1e-5 of the unit parameter range: spans at least ~1e-3 of their typical neighbours, well
    // inside the range where the explicit basis is exact to round-off (docs/formulas.md).
    snap_values(r.point_u, 1, [](double) { return 1e-5; });
  }

  // Closed section curves (seed 001 §2.2), clamped at u = 0 so that all share the domain [0, 1].
  if (r.used == Correspondence::index) {
    // One knot vector and one collocation matrix for all sections: solve once with the sections
    // side by side as 3K columns.
    const Index n = sections[0].points.rows();
    MatrixXd P(n, 3 * K);
    for (Index k = 0; k < K; ++k)
      P.middleCols(3 * k, 3) = sections[k].points;
    const BSplineCurve all =
        periodic_to_clamped(interpolate_closed(P, r.point_u[0], o.degree), 0.0);
    for (Index k = 0; k < K; ++k)
      r.curves.push_back({all.degree, all.knots, all.ctrl.middleCols(3 * k, 3), false});
  } else {
    for (Index k = 0; k < K; ++k)
      r.curves.push_back(periodic_to_clamped(
          interpolate_closed(sections[k].points, r.point_u[static_cast<size_t>(k)], o.degree),
          0.0));
    r.curves = make_compatible(r.curves);
  }

  return r;
}

VectorXd neighbour_distances(const std::vector<BSplineCurve>& curves,
                             const std::vector<PreparedSection>& sections) {
  // Measured at 256 common parameters: all curves share one basis.
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
  const Index K = static_cast<Index>(curves.size());
  VectorXd d(K - 1);
  MatrixXd prev = probe_points(curves[0].ctrl);
  for (Index k = 1; k < K; ++k) {
    const MatrixXd cur = probe_points(curves[static_cast<size_t>(k)].ctrl);
    d(k - 1) = (cur - prev).rowwise().norm().mean();
    if (!(d(k - 1) > 0))
      throw std::invalid_argument("sections " + sections[static_cast<size_t>(k - 1)].id + " and " +
                                  sections[static_cast<size_t>(k)].id + " coincide");
    prev = cur;
  }
  return d;
}

void section_deviation(LoftResult& r, Eigen::Vector3d& lo, Eigen::Vector3d& hi) {
  const BSplineSurface& S = r.surface;
  const VectorXd& section_v = r.section_v;
  // S(u_i, v_k) = sum_i N_i(u) R_i with the row curve R = sum_j M_j(v_k) ctrl(., j) at v_k.
  const SplineBasis basis_u = explicit_basis(S.knots_u, S.degree_u);
  const SplineBasis basis_v = explicit_basis(S.knots_v, S.degree_v);
  lo = Eigen::Vector3d::Constant(INFINITY);
  hi = -lo;
  for (Index k = 0; k < section_v.size(); ++k) {
    Index span;
    const MatrixXd M = basis_derivatives(basis_v, section_v(k), 0, &span);
    MatrixXd R = MatrixXd::Zero(S.num_u, 3);
    for (int j = 0; j <= S.degree_v; ++j)
      R += M(0, j) * S.ctrl.middleRows(S.num_u * (span - S.degree_v + j), S.num_u);
    const MatrixXd& P = r.sections[static_cast<size_t>(k)].points;
    const VectorXd& u = r.point_u[static_cast<size_t>(k)];
    VectorXd dev(P.rows());
    for (Index i = 0; i < P.rows(); ++i) {
      const MatrixXd N = basis_derivatives(basis_u, u(i), 0, &span);
      Eigen::RowVector3d x = Eigen::RowVector3d::Zero();
      for (int q = 0; q <= S.degree_u; ++q)
        x += N(0, q) * R.row(span - S.degree_u + q);
      dev(i) = (x - P.row(i)).norm();
      lo = lo.cwiseMin(P.row(i).transpose());
      hi = hi.cwiseMax(P.row(i).transpose());
    }
    r.deviation.push_back(dev);
    r.max_deviation = std::max(r.max_deviation, dev.maxCoeff());
  }
}

void require_exact(const LoftResult& r, const std::string& what) {
  if (!(r.max_deviation <= 1e-9 * r.bbox_diagonal))
    throw std::runtime_error(what + " by " + std::to_string(r.max_deviation) +
                             " (more than 1e-9 x bounding-box diagonal); refusing to continue");
}

} // namespace interlin::detail
