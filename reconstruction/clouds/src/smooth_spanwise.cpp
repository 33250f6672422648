#include "smooth_spanwise.h"

#include "profile_curves.h"

#include "interlin/reconstruction/meshing/parallel_for.h"
#include "interlin/splines/knots.h"
#include "interlin/splines/spline_basis.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>

namespace interlin::detail {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

constexpr int kDegree = 3;
// The sections' knot weights are averaged on this many even intervals of [0, 1].
constexpr Index kWeightGrid = 4096;
// The searches over either count stop after this many counts in a row without a lower C_p.
constexpr int kRisesToStop = 2;
// Control points around: at least as many as the section fit's fewest.
constexpr Index kMinControl = 8;
// Spanwise control points: from a single cubic up.
constexpr Index kMinSpanControl = kDegree + 1;
// Pivots of the normal equations below this share of the largest: a singular candidate.
constexpr double kPivotRatio = 1e-13;
// An isocurve may stray from its slice's points by their spacing plus this many sigma (strays),
// sampled this many times per knot span.
constexpr double kStray = 4;
constexpr Index kStraySamples = 8;
// Edges (curve_edges): samples of the whole curve and of the search window around each edge,
// whose half-width is this share of the parameter period.
constexpr Index kEdgeSamples = 512;
constexpr double kEdgeWindow = 0.02;
// Fits of each candidate net, each at the points' feet on the last (the pass of least RSS is
// kept); the winner gets one more.
constexpr int kSearchPasses = 2;

// One slice's blocks of the normal equations for the periodic basis Bu with cu control points:
// G = B^T B (cu by cu), R = B^T P (cu by dim), B the basis at the points' parameters u.
struct SliceGram {
  MatrixXd G, R;
};

SliceGram slice_gram(const SplineBasis& Bu, Index cu, const MatrixXd& P, const VectorXd& u) {
  SliceGram g{MatrixXd::Zero(cu, cu), MatrixXd::Zero(cu, P.cols())};
  for (Index i = 0; i < u.size(); ++i) {
    Index span = 0;
    const MatrixXd N = basis_derivatives(Bu, u(i), 0, &span);
    for (int r = 0; r <= kDegree; ++r) {
      const Index a = (span - kDegree + r) % cu;
      g.R.row(a) += N(0, r) * P.row(i);
      for (int q = 0; q <= kDegree; ++q)
        g.G(a, (span - kDegree + q) % cu) += N(0, r) * N(0, q);
    }
  }
  return g;
}

// The spanwise basis at one station: its kDegree + 1 values and the first one's index.
struct SpanBasis {
  Eigen::RowVectorXd N;
  Index first = 0;
};

SpanBasis span_basis(const SplineBasis& Bv, double v) {
  Index span = 0;
  const MatrixXd N = basis_derivatives(Bv, v, 0, &span);
  return {N.row(0), span - kDegree};
}

// The control net Q (row a cv + b: Q_ab) from sum_k (N_k N_k^T) (x) G_k Q = sum_k N_k (x) R_k;
// none when the system is singular (a span without points).
std::optional<MatrixXd> solve_net(const std::vector<SliceGram>& g, const std::vector<SpanBasis>& N,
                                  Index cu, Index cv) {
  std::vector<Eigen::Triplet<double>> T;
  MatrixXd rhs = MatrixXd::Zero(cu * cv, g.front().R.cols());
  for (size_t k = 0; k < g.size(); ++k) {
    const Index b0 = N[k].first;
    for (Index a = 0; a < cu; ++a) {
      for (int q = 0; q <= kDegree; ++q)
        rhs.row(a * cv + b0 + q) += N[k].N(q) * g[k].R.row(a);
      for (Index c = 0; c < cu; ++c)
        if (g[k].G(a, c) != 0)
          for (int q = 0; q <= kDegree; ++q)
            for (int r = 0; r <= kDegree; ++r)
              T.emplace_back(a * cv + b0 + q, c * cv + b0 + r,
                             N[k].N(q) * N[k].N(r) * g[k].G(a, c));
    }
  }
  Eigen::SparseMatrix<double> M(cu * cv, cu * cv);
  M.setFromTriplets(T.begin(), T.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(M);
  if (ldlt.info() != Eigen::Success ||
      !(ldlt.vectorD().minCoeff() > kPivotRatio * ldlt.vectorD().maxCoeff()))
    return std::nullopt;
  MatrixXd Q = ldlt.solve(rhs);
  if (!Q.allFinite())
    return std::nullopt;
  return Q;
}

// The isocurve at one station: control point a is sum_b N_b Q_ab (periodic: the first kDegree
// repeated).
BSplineCurve isocurve(const MatrixXd& Q, const VectorXd& ku, Index cu, Index cv,
                      const SpanBasis& N) {
  BSplineCurve c;
  c.degree = kDegree;
  c.knots = ku;
  c.periodic = true;
  c.ctrl = MatrixXd::Zero(cu + kDegree, Q.cols());
  for (Index a = 0; a < cu; ++a)
    for (int q = 0; q <= kDegree; ++q)
      c.ctrl.row(a) += N.N(q) * Q.row(a * cv + N.first + q);
  c.ctrl.bottomRows(kDegree) = c.ctrl.topRows(kDegree);
  return c;
}

// A closed curve's edges: the parameters of its extreme points along its chord (from each edge
// to the other), so that every section's parameters can start at its leading edge and put its
// trailing edge at one common parameter. Extremes along a direction, found where the tangent turns
// through it, move along the curve by about the fit's error; the scan's points chosen as edges
// (prepare_sections) move by the point spacing or by sqrt(2 r sigma) on a nose of radius r.
struct Edges {
  double le = 0, te = 0; // te in (le, le + 1)
};

// The parameter of the point of c farthest along d within w of u: the best of kEdgeSamples, then
// Newton on C'(u) . d = 0.
double extreme_along(const BSplineCurve& c, const Eigen::RowVectorXd& d, double u, double w) {
  const VectorXd t = VectorXd::LinSpaced(kEdgeSamples, u - w, u + w);
  Index best = 0;
  (evaluate(c, t) * d.transpose()).maxCoeff(&best);
  double x = t(best);
  for (int step = 0; step < 4; ++step) {
    const VectorXd at = VectorXd::Constant(1, x);
    const double g = evaluate(c, at, 1).row(0).dot(d), h = evaluate(c, at, 2).row(0).dot(d);
    if (h < 0)
      x = std::clamp(x - g / h, u - w, u + w);
  }
  return x;
}

// Edges from the start (u = 0, the leading edge) and the point farthest from it, refined twice.
Edges curve_edges(const BSplineCurve& c) {
  const VectorXd t = VectorXd::LinSpaced(kEdgeSamples, 0, 1 - 1.0 / kEdgeSamples);
  const MatrixXd C = evaluate(c, t);
  Edges e;
  Index far = 0;
  (C.rowwise() - C.row(0)).rowwise().norm().maxCoeff(&far);
  e.te = t(far);
  for (int it = 0; it < 2; ++it) {
    const Eigen::RowVectorXd L = evaluate(c, VectorXd::Constant(1, e.le)).row(0),
                             T = evaluate(c, VectorXd::Constant(1, e.te)).row(0);
    const Eigen::RowVectorXd d = (T - L).normalized();
    e.te = extreme_along(c, d, e.te, kEdgeWindow);
    e.le = extreme_along(c, -d, e.le, kEdgeWindow);
  }
  e.te = e.le + (e.te - e.le - std::floor(e.te - e.le));
  return e;
}

// Parameter x on a curve with edges e -> the common parameter (leading edge 0, trailing edge F,
// linear in between on either side), and back.
double to_common(const Edges& e, double F, double x) {
  const double y = x - e.le - std::floor(x - e.le), f = e.te - e.le;
  return y <= f ? y * F / f : F + (y - f) * (1 - F) / (1 - f);
}

double from_common(const Edges& e, double F, double y) {
  const double f = e.te - e.le;
  return e.le + (y <= F ? y * f / F : f + (y - F) * (1 - f) / (1 - F));
}

// The sections' knot weights on the common parameter: turning_weights averaged on kWeightGrid
// even intervals of [0, 1], and the points each interval holds per slice.
struct KnotWeights {
  VectorXd t, w, m;
};

KnotWeights knot_weights(const std::vector<BSplineCurve>& curves, const std::vector<Edges>& edges,
                         double F, const std::vector<VectorXd>& u) {
  KnotWeights q{VectorXd::LinSpaced(kWeightGrid + 1, 0, 1), VectorXd::Zero(kWeightGrid),
                VectorXd::Zero(kWeightGrid)};
  for (size_t k = 0; k < curves.size(); ++k) {
    const VectorXd tk = q.t.unaryExpr([&](double y) { return from_common(edges[k], F, y); });
    q.w += turning_weights(curves[k], tk);
    for (Index i = 0; i < u[k].size(); ++i)
      q.m(std::clamp<Index>(Index(u[k](i) * kWeightGrid), 0, kWeightGrid - 1)) +=
          1.0 / double(curves.size());
  }
  return q;
}

// Periodic knots for cu control points shared by all sections, spaced by the weights, capped by
// the points each interval holds (capped_knot_weights).
VectorXd common_knots(const KnotWeights& q, Index cu) {
  return periodic_quantile_knots(q.t, kDegree, cu, capped_knot_weights(q.w, q.m, q.t, cu));
}

double squared_residual(const BSplineCurve& c, const MatrixXd& P, const VectorXd& u) {
  return (evaluate(c, u) - P).squaredNorm();
}

// The problem: points, their pilot parameters (feet on the sections' own fits, on the common
// parameter), the knot weights, the scaled stations, the noise variance and the threads.
struct Inputs {
  const std::vector<MatrixXd>& P;
  std::vector<VectorXd> u0;
  KnotWeights weights;
  const VectorXd& v;
  double s2;
  int threads;
};

// A candidate net's isocurves, the points' feet on them, RSS and C_p.
struct Candidate {
  std::vector<BSplineCurve> curves;
  std::vector<VectorXd> u;
  Index cu = 0, cv = 0;
  double rss = 0, cp = std::numeric_limits<double>::infinity();
};

// Whether an isocurve strays from its slice's points (kStraySamples samples per knot span):
// a sample farther from both points whose feet enclose it than they are apart, plus kStray sigma.
// Where a slice has no points in a knot span, a net with little spanwise coupling is free to
// oscillate there, which the points' RSS cannot see.
bool strays(const Inputs& in, const Candidate& c) {
  std::vector<char> out(in.P.size(), 0);
  const double allowance = kStray * std::sqrt(in.s2);
  parallel_for(long(in.P.size()), in.threads, [&](long k, int) {
    const size_t i = size_t(k);
    const MatrixXd& P = in.P[i];
    const Index n = P.rows(), m = kStraySamples * c.cu;
    std::vector<Index> order(static_cast<size_t>(n));
    std::iota(order.begin(), order.end(), Index(0));
    std::sort(order.begin(), order.end(), [&](Index a, Index b) { return c.u[i](a) < c.u[i](b); });
    std::vector<double> feet;
    for (Index j : order)
      feet.push_back(c.u[i](j));
    const VectorXd t = VectorXd::LinSpaced(m, 0, 1 - 1.0 / double(m));
    const MatrixXd S = evaluate(c.curves[i], t);
    for (Index j = 0; j < m && !out[i]; ++j) {
      const Index hi = Index(std::upper_bound(feet.begin(), feet.end(), t(j)) - feet.begin());
      const Eigen::RowVectorXd a = P.row(order[size_t((hi + n - 1) % n)]),
                               b = P.row(order[size_t(hi % n)]);
      const double d = std::min((S.row(j) - a).norm(), (S.row(j) - b).norm());
      out[i] = d > (a - b).norm() + allowance;
    }
  });
  return std::find(out.begin(), out.end(), 1) != out.end();
}

// The net with cu by cv control points fitted `passes` times (at the parameters `start` on the
// common parameter, then at the points' feet on the last isocurves), the pass of least RSS kept;
// none when singular or straying.
std::optional<Candidate> fit_candidate(const Inputs& in, Index cu, Index cv,
                                       const std::vector<VectorXd>& start, int passes) {
  const long K = long(in.P.size());
  const VectorXd ku = common_knots(in.weights, cu);
  const SplineBasis Bu = explicit_basis(ku, kDegree);
  const SplineBasis Bv = explicit_basis(approximation_knots(in.v, kDegree, cv), kDegree);
  std::vector<SpanBasis> N;
  for (Index k = 0; k < in.v.size(); ++k)
    N.push_back(span_basis(Bv, in.v(k)));
  Candidate c{std::vector<BSplineCurve>(size_t(K)), start, cu, cv}, best;
  for (int pass = 0; pass < passes; ++pass) {
    std::vector<SliceGram> g(static_cast<size_t>(K));
    parallel_for(K, in.threads, [&](long k, int) {
      g[size_t(k)] = slice_gram(Bu, cu, in.P[size_t(k)], c.u[size_t(k)]);
    });
    const std::optional<MatrixXd> Q = solve_net(g, N, cu, cv);
    if (!Q)
      break;
    parallel_for(K, in.threads, [&](long k, int) {
      const size_t i = size_t(k);
      c.curves[i] = isocurve(*Q, ku, cu, cv, N[i]);
      c.u[i] = closest_parameters(c.curves[i], in.P[i], c.u[i]);
    });
    c.rss = 0;
    for (size_t k = 0; k < in.P.size(); ++k)
      c.rss += squared_residual(c.curves[k], in.P[k], c.u[k]);
    if (best.curves.empty() || c.rss < best.rss)
      best = c;
  }
  if (best.curves.empty())
    return std::nullopt;
  const bool stray = strays(in, best);
  best.cp = best.rss + 2 * in.s2 * double(kDofPerControl * cu * cv);
  if (stray)
    return std::nullopt;
  return best;
}

// The candidate of least C_p over the spanwise counts kMinSpanControl ... K (steps of 1/4) for cu
// control points around the profile.
std::optional<Candidate> best_span_count(const Inputs& in, Index cu) {
  std::optional<Candidate> best;
  int rises = 0;
  const Index K = in.v.size();
  for (Index cv = kMinSpanControl; cv <= K && rises < kRisesToStop;
       cv = std::max(cv + 1, cv * 5 / 4)) {
    std::optional<Candidate> c = fit_candidate(in, cu, cv, in.u0, kSearchPasses);
    const bool better = c && (!best || c->cp < best->cp);
    rises = better ? 0 : rises + 1;
    if (better)
      best = std::move(c);
  }
  return best;
}

// The search: the spanwise count at cu0 around, then more control points around (steps of 1/4,
// at most `most`) at that spanwise count, then one more pass for the winner from its feet.
std::optional<Candidate> least_cp_net(const Inputs& in, Index cu0, Index most) {
  std::optional<Candidate> best = best_span_count(in, cu0);
  if (!best)
    return best;
  int rises = 0;
  for (Index cu = std::min(most, std::max(cu0 + 1, cu0 * 5 / 4));
       cu > best->cu && rises < kRisesToStop; cu = std::min(most, std::max(cu + 1, cu * 5 / 4))) {
    std::optional<Candidate> c = fit_candidate(in, cu, best->cv, in.u0, kSearchPasses);
    const bool better = c && c->cp < best->cp;
    rises = better ? 0 : rises + 1;
    if (better)
      best = std::move(c);
  }
  std::optional<Candidate> c = fit_candidate(in, best->cu, best->cv, best->u, 1);
  if (c && c->rss < best->rss)
    best = std::move(c);
  return best;
}

// The sections as fitted, with the points' feet on them (into r). Output: their C_p,
// sum_k (RSS_k + 2 s2 kDofPerControl control_k).
double sections_alone(const std::vector<MatrixXd>& P, const std::vector<VectorXd>& u,
                      const std::vector<BSplineCurve>& curves, double s2, int threads,
                      SpanwiseSections& r) {
  const long K = long(P.size());
  r.curves = curves;
  r.u.resize(size_t(K));
  std::vector<double> rss(static_cast<size_t>(K));
  parallel_for(K, threads, [&](long k, int) {
    const size_t i = size_t(k);
    r.u[i] = closest_parameters(curves[i], P[i], u[i]);
    rss[i] = squared_residual(curves[i], P[i], r.u[i]);
  });
  double cp = 0;
  for (size_t k = 0; k < curves.size(); ++k)
    cp += rss[k] + 2 * s2 * double(kDofPerControl * (curves[k].ctrl.rows() - curves[k].degree));
  return cp;
}

} // namespace

SpanwiseSections smooth_spanwise(const std::vector<MatrixXd>& P, const std::vector<VectorXd>& u,
                                 const std::vector<BSplineCurve>& curves, const VectorXd& v,
                                 double s2, int threads) {
  const long K = long(P.size());
  SpanwiseSections r;
  const double cp_sections = sections_alone(P, u, curves, s2, threads, r);
  // the pilot parameters: each point's foot on its section's fit, on the common parameter
  std::vector<Edges> edges(static_cast<size_t>(K));
  parallel_for(K, threads, [&](long k, int) { edges[size_t(k)] = curve_edges(curves[size_t(k)]); });
  double F = 0;
  for (const Edges& e : edges)
    F += (e.te - e.le) / double(K);
  std::vector<VectorXd> u0;
  for (size_t k = 0; k < size_t(K); ++k)
    u0.push_back(r.u[k].unaryExpr([&](double x) { return to_common(edges[k], F, x); }));
  KnotWeights weights = knot_weights(curves, edges, F, u0);
  const Inputs in{P, std::move(u0), std::move(weights), v, s2, threads};
  // from the sections' median count around, at most #points / kPointsPerControl of any slice
  std::vector<Index> counts;
  Index most = std::numeric_limits<Index>::max();
  for (size_t k = 0; k < curves.size(); ++k) {
    counts.push_back(curves[k].ctrl.rows() - curves[k].degree);
    most = std::min(most, P[k].rows() / kPointsPerControl);
  }
  if (most < kMinControl)
    return r;
  std::nth_element(counts.begin(), counts.begin() + K / 2, counts.end());
  std::optional<Candidate> best = least_cp_net(in, std::min(counts[size_t(K / 2)], most), most);
  if (!best || !(best->cp < cp_sections))
    return r;
  r.span_control = best->cv;
  r.curves = std::move(best->curves);
  r.u = std::move(best->u);
  return r;
}

} // namespace interlin::detail
