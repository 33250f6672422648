#include "interlin/splines/knot_insertion.h"

#include "interlin/splines/knots.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// c with `value` inserted up to multiplicity c.degree (a knot of the curve then carries one
// control point that is the curve's point there).
BSplineCurve with_breakpoints(const BSplineCurve& c, const std::vector<double>& values) {
  std::vector<double> X;
  for (double x : values) {
    const long have = std::count(c.knots.data(), c.knots.data() + c.knots.size(), x);
    for (long k = have; k < c.degree; ++k)
      X.push_back(x);
  }
  std::sort(X.begin(), X.end());
  return X.empty() ? c : refine_knots(c, Eigen::Map<const VectorXd>(X.data(), long(X.size())));
}

// Index of the control point that is the curve's point at the knot value x (multiplicity >=
// degree): the last occurrence minus the degree.
long point_index(const BSplineCurve& c, double x) {
  const double* k = c.knots.data();
  const long last = long(std::upper_bound(k, k + c.knots.size(), x) - k) - 1;
  return std::min<long>(last - c.degree, c.ctrl.rows() - 1);
}

// Control points [ka, kb] and the knots strictly inside (a, b) of a refined curve.
void append_piece(const BSplineCurve& c, double a, double b, bool skip_first,
                  std::vector<Eigen::RowVectorXd>& P, std::vector<double>& K, double shift) {
  for (long i = point_index(c, a) + (skip_first ? 1 : 0); i <= point_index(c, b); ++i)
    P.push_back(c.ctrl.row(i));
  for (long i = 0; i < c.knots.size(); ++i)
    if (c.knots(i) > a && c.knots(i) < b)
      K.push_back(c.knots(i) + shift);
}

} // namespace

BSplineCurve refine_knots(const BSplineCurve& c, const VectorXd& X) {
  if (c.periodic)
    throw std::invalid_argument("refine_knots: convert periodic curves with periodic_to_clamped");
  const int p = c.degree;
  const Index n = c.ctrl.rows() - 1; // last control index
  const Index m = n + p + 1;         // last knot index
  check_knots(c.knots, p, n + 1);
  const Index r = X.size() - 1;
  if (r < 0)
    return c;
  for (Index j = 0; j <= r; ++j)
    if (X(j) < c.knots(p) || X(j) > c.knots(n + 1) || (j > 0 && X(j) < X(j - 1)))
      throw std::invalid_argument("refine_knots: knots to insert must be sorted and in the domain");
  const VectorXd& U = c.knots;
  const MatrixXd& P = c.ctrl;
  // Piegl & Tiller A5.4: copy the unaffected parts, then sweep from the right end.
  const Index a = find_span(U, p, n + 1, X(0));
  const Index b = find_span(U, p, n + 1, X(r)) + 1;
  MatrixXd Q(n + r + 2, P.cols());
  VectorXd Ub(m + r + 2);
  for (Index j = 0; j <= a - p; ++j)
    Q.row(j) = P.row(j);
  for (Index j = b - 1; j <= n; ++j)
    Q.row(j + r + 1) = P.row(j);
  for (Index j = 0; j <= a; ++j)
    Ub(j) = U(j);
  for (Index j = b + p; j <= m; ++j)
    Ub(j + r + 1) = U(j);
  Index i = b + p - 1, k = b + p + r;
  for (Index j = r; j >= 0; --j) {
    while (X(j) <= U(i) && i > a) {
      Q.row(k - p - 1) = P.row(i - p - 1);
      Ub(k) = U(i);
      --k;
      --i;
    }
    Q.row(k - p - 1) = Q.row(k - p);
    for (int l = 1; l <= p; ++l) {
      const Index ind = k - p + l;
      double alpha = Ub(k + l) - X(j);
      if (alpha == 0.0) {
        Q.row(ind - 1) = Q.row(ind);
      } else {
        alpha /= Ub(k + l) - U(i - p + l);
        Q.row(ind - 1) = alpha * Q.row(ind - 1) + (1.0 - alpha) * Q.row(ind);
      }
    }
    Ub(k) = X(j);
    --k;
  }
  BSplineCurve out;
  out.degree = p;
  out.knots = Ub;
  out.ctrl = Q;
  return out;
}

BSplineCurve periodic_to_clamped(const BSplineCurve& c, double a) {
  if (!c.periodic)
    throw std::invalid_argument("periodic_to_clamped: curve is not periodic");
  const int p = c.degree;
  const Index N = c.ctrl.rows() - p; // distinct control points
  check_knots(c.knots, p, N + p);
  const double t0 = c.knots(p), T = c.knots(N + p) - t0;
  // One period of knots tau_0..tau_{N-1}; tau_{i + kN} = tau_i + k T.
  const auto tau = [&](Index i) {
    const Index w = ((i % N) + N) % N;
    return c.knots(p + w) + T * static_cast<double>((i - w) / N);
  };
  // Unroll over four periods (one before, two after the base period) so that any window
  // [a, a+T] with a in the base period lies strictly inside the domain.
  BSplineCurve u;
  u.degree = p;
  u.knots.resize(4 * N + 2 * p + 1);
  for (Index j = 0; j < u.knots.size(); ++j)
    u.knots(j) = tau(j - p - N);
  u.ctrl.resize(4 * N + p, c.ctrl.cols());
  for (Index j = 0; j < u.ctrl.rows(); ++j)
    u.ctrl.row(j) = c.ctrl.row(j % N);
  // Window start in the base period, snapped to a knot closer than round-off.
  a = t0 + (a - t0) - T * std::floor((a - t0) / T);
  Index snapped = -1;
  for (Index i = 0; i <= N; ++i)
    if (std::abs(tau(i) - a) <= 1e-14 * T) {
      a = tau(i);
      snapped = i;
    }
  const double e = snapped >= 0 ? tau(snapped + N) : a + T;
  std::vector<double> ins;
  for (const double w : {a, e}) {
    const Index mult = std::count(u.knots.data(), u.knots.data() + u.knots.size(), w);
    for (Index k = mult; k < p; ++k)
      ins.push_back(w);
  }
  const BSplineCurve r =
      refine_knots(u, Eigen::Map<const VectorXd>(ins.data(), static_cast<Index>(ins.size())));
  const auto first_of = [&](double w) {
    return std::find(r.knots.data(), r.knots.data() + r.knots.size(), w) - r.knots.data();
  };
  const Index s = first_of(a), f = first_of(e);
  BSplineCurve out;
  out.degree = p;
  out.ctrl = r.ctrl.middleRows(s - 1, f - s + 1);
  out.knots.resize(out.ctrl.rows() + p + 1);
  out.knots.head(p + 1).setConstant(a);
  out.knots.segment(p + 1, f - s - p) = r.knots.segment(s + p, f - s - p);
  out.knots.tail(p + 1).setConstant(e);
  return out;
}

VectorXd knot_union(const std::vector<VectorXd>& knot_vectors) {
  std::map<double, Index> mult;
  for (const VectorXd& t : knot_vectors) {
    std::map<double, Index> here;
    for (Index i = 0; i < t.size(); ++i)
      ++here[t(i)];
    for (const auto& [value, m] : here)
      mult[value] = std::max(mult[value], m);
  }
  std::vector<double> out;
  for (const auto& [value, m] : mult)
    out.insert(out.end(), static_cast<size_t>(m), value);
  return Eigen::Map<const VectorXd>(out.data(), static_cast<Index>(out.size()));
}

std::vector<BSplineCurve> make_compatible(const std::vector<BSplineCurve>& curves) {
  if (curves.empty())
    return {};
  std::vector<VectorXd> knots;
  for (const BSplineCurve& c : curves) {
    if (c.periodic)
      throw std::invalid_argument("make_compatible: curves must be clamped (periodic_to_clamped)");
    if (c.degree != curves[0].degree || domain_begin(c) != domain_begin(curves[0]) ||
        domain_end(c) != domain_end(curves[0]))
      throw std::invalid_argument("make_compatible: curves must share degree and domain");
    knots.push_back(c.knots);
  }
  const VectorXd all = knot_union(knots);
  std::vector<BSplineCurve> out;
  for (const BSplineCurve& c : curves) {
    // Knots of the union missing from c (multiset difference of two sorted vectors).
    std::vector<double> missing;
    std::set_difference(all.data(), all.data() + all.size(), c.knots.data(),
                        c.knots.data() + c.knots.size(), std::back_inserter(missing));
    out.push_back(refine_knots(
        c, Eigen::Map<const VectorXd>(missing.data(), static_cast<Index>(missing.size()))));
  }
  return out;
}

BSplineCurve curve_piece(const BSplineCurve& c, double a, double b) {
  const int p = c.degree;
  const double u0 = domain_begin(c), u1 = domain_end(c);
  if (!(a >= u0 && a <= u1 && b >= u0 && b <= u1) || a == b)
    throw std::invalid_argument("curve_piece: the piece's ends must be distinct and in the domain");
  if (a > b && b == u0) // up to the end of the domain: no wrap needed
    b = u1;
  const BSplineCurve r = with_breakpoints(c, {a, b});
  std::vector<Eigen::RowVectorXd> P;
  std::vector<double> K(size_t(p + 1), a);
  double end = b;
  append_piece(r, a, a < b ? b : u1, false, P, K, 0);
  if (a > b) { // through the end of a closed curve: on from its start, shifted by one period
    const double period = u1 - u0;
    K.insert(K.end(), size_t(p), u1);
    append_piece(r, u0, b, true, P, K, period);
    end = b + period;
  }
  K.insert(K.end(), size_t(p + 1), end);
  BSplineCurve out;
  out.degree = p;
  out.ctrl.resize(long(P.size()), c.ctrl.cols());
  for (size_t i = 0; i < P.size(); ++i)
    out.ctrl.row(long(i)) = P[i];
  out.knots.resize(long(K.size()));
  for (size_t i = 0; i < K.size(); ++i)
    out.knots(long(i)) = (K[i] - a) / (end - a);
  if (out.knots.size() != out.ctrl.rows() + p + 1)
    throw std::logic_error("curve_piece: inconsistent piece");
  return out;
}

} // namespace interlin
