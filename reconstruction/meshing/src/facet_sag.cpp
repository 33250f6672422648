// The volume between boundary facets and F = 0 (facet_sag.h).
#include "interlin/reconstruction/meshing/facet_sag.h"

#include "parallel.h"
#include "value_and_gradient.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace interlin {

namespace {

constexpr long kFacetsPerTask = 2048;
constexpr double kMinCosine = 0.5;  // normal within 60 degrees of -grad F
constexpr int kMaxSteps = 16;       // secant / regula falsi steps after the Newton step
constexpr double kTolerance = 1e-9; // of the facet's diameter

// Quadrature points of a chunk of facets: position, unit outward normal, weight, reach.
struct Samples {
  Points3 X, N;
  Eigen::VectorXd w, reach;
};

Samples triangle_samples(const Eigen::MatrixXd& V, const Eigen::MatrixXi& B, long b0, long b1) {
  Samples s;
  const long n = 3 * (b1 - b0);
  s.X.resize(n, 3), s.N.resize(n, 3), s.w.resize(n), s.reach.resize(n);
  for (long b = b0, k = 0; b < b1; ++b) {
    const Eigen::Vector3d p[3] = {V.row(B(b, 0)), V.row(B(b, 1)), V.row(B(b, 2))};
    const Eigen::Vector3d c = (p[1] - p[0]).cross(p[2] - p[0]);
    const double area = 0.5 * c.norm();
    const double L = std::max({(p[1] - p[0]).norm(), (p[2] - p[1]).norm(), (p[0] - p[2]).norm()});
    for (int e = 0; e < 3; ++e, ++k) { // edge midpoints: exact for quadratics
      s.X.row(k) = 0.5 * (p[e] + p[(e + 1) % 3]);
      s.N.row(k) = area > 0 ? Eigen::Vector3d(c / c.norm()) : Eigen::Vector3d::Zero();
      s.w(k) = area / 3, s.reach(k) = L;
    }
  }
  return s;
}

Samples quad_samples(const Eigen::MatrixXd& V, const Eigen::MatrixXi& B, long b0, long b1) {
  constexpr double kSimpson[3] = {1.0 / 6, 4.0 / 6, 1.0 / 6}, kAt[3] = {0, 0.5, 1};
  Samples s;
  const long n = 9 * (b1 - b0);
  s.X.resize(n, 3), s.N.resize(n, 3), s.w.resize(n), s.reach.resize(n);
  for (long b = b0, k = 0; b < b1; ++b) {
    const Eigen::Vector3d p[4] = {V.row(B(b, 0)), V.row(B(b, 1)), V.row(B(b, 2)), V.row(B(b, 3))};
    const double L = std::max((p[2] - p[0]).norm(), (p[3] - p[1]).norm());
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j, ++k) {
        const double u = kAt[i], v = kAt[j];
        const Eigen::Vector3d Xu = (1 - v) * (p[1] - p[0]) + v * (p[2] - p[3]);
        const Eigen::Vector3d Xv = (1 - u) * (p[3] - p[0]) + u * (p[2] - p[1]);
        const Eigen::Vector3d c = Xu.cross(Xv);
        const double J = c.norm();
        s.X.row(k) =
            (1 - u) * (1 - v) * p[0] + u * (1 - v) * p[1] + u * v * p[2] + (1 - u) * v * p[3];
        s.N.row(k) = J > 0 ? Eigen::Vector3d(c / J) : Eigen::Vector3d::Zero();
        s.w(k) = kSimpson[i] * kSimpson[j] * J, s.reach(k) = L;
      }
  }
  return s;
}

// The root search of one sample along X + t s N, t in [0, reach], s = sign F(X): phi(t) = s F.
struct Search {
  double lo = 0, phi_lo = 0;  // phi > 0
  double hi = -1, phi_hi = 0; // phi <= 0 once bracketed (hi >= 0)
  double t = 0;               // the point to evaluate next
  int side = 0;               // regula falsi: the end kept last time (Illinois halving)
  bool done = false, skipped = false;
};

// The next point of a search from its bracket (or, unbracketed, the secant through 0 and lo).
void next_point(Search& q, double phi0, double reach) {
  if (q.hi >= 0) {
    const double t = q.lo + (q.hi - q.lo) * q.phi_lo / (q.phi_lo - q.phi_hi);
    q.t = std::isfinite(t) && t > q.lo && t < q.hi ? t : 0.5 * (q.lo + q.hi);
    return;
  }
  const double t = phi0 > q.phi_lo ? q.lo * phi0 / (phi0 - q.phi_lo) : 2 * q.lo;
  q.t = std::min(std::max(t, 1.5 * q.lo), reach);
}

// phi at q.t: bracket update; done when the bracket or phi is within tolerance.
void take_value(Search& q, double phi, double phi0, double reach) {
  const double t = q.t;
  if (phi > 0) {
    if (q.side == +1 && q.hi >= 0)
      q.phi_hi *= 0.5; // Illinois: the other end kept twice
    q.lo = t, q.phi_lo = phi, q.side = +1;
    if (q.hi < 0 && t >= reach)
      q.done = q.skipped = true; // no zero within the facet's diameter
  } else {
    if (q.side == -1)
      q.phi_lo *= 0.5;
    q.hi = t, q.phi_hi = phi, q.side = -1;
  }
  if (q.done)
    return;
  if (std::abs(phi) <= 1e-14 * phi0 || (q.hi >= 0 && q.hi - q.lo <= kTolerance * reach)) {
    q.t = q.hi >= 0 && std::abs(phi) > 1e-14 * phi0 ? 0.5 * (q.lo + q.hi) : t;
    q.done = true;
    return;
  }
  next_point(q, phi0, reach);
}

// The signed distance of every sample (0 for skipped ones, flagged).
void distances(const ImplicitFunction& f, const Samples& s, Eigen::VectorXd& d,
               std::vector<char>& skipped) {
  const long n = s.X.rows();
  d.setZero(n);
  skipped.assign(size_t(n), 0);
  if (n == 0)
    return;
  Eigen::VectorXd F0(n);
  Points3 G(n, 3);
  detail::value_and_gradient(f, s.X, 1e-4 * s.reach.maxCoeff(), F0, G);
  std::vector<Search> q(static_cast<size_t>(n));
  std::vector<long> active;
  for (long k = 0; k < n; ++k) {
    const double phi0 = std::abs(F0(k));
    const double slope = G.row(k).dot(s.N.row(k)), g = G.row(k).norm();
    Search& sq = q[size_t(k)];
    sq.done = true;
    if (phi0 <= kTolerance * g * s.reach(k) || s.w(k) == 0)
      continue; // on F = 0 to first order (corners): distance 0
    if (!std::isfinite(F0(k)) || !(g > 0) || -slope < kMinCosine * g) {
      sq.skipped = true;
      continue;
    }
    sq.done = false;
    sq.phi_lo = phi0;
    sq.t = std::min(phi0 / -slope, s.reach(k)); // Newton
    active.push_back(k);
  }
  Points3 P;
  Eigen::VectorXd Fp;
  for (int step = 0; step <= kMaxSteps && !active.empty(); ++step) {
    P.resize(long(active.size()), 3);
    for (size_t a = 0; a < active.size(); ++a) {
      const long k = active[a];
      const double sign = F0(k) > 0 ? 1 : -1;
      P.row(long(a)) = s.X.row(k) + sign * q[size_t(k)].t * s.N.row(k);
    }
    Fp.resize(P.rows());
    f.value(P, Fp);
    std::vector<long> still;
    for (size_t a = 0; a < active.size(); ++a) {
      const long k = active[a];
      Search& sq = q[size_t(k)];
      const double sign = F0(k) > 0 ? 1 : -1;
      const double phi = sign * Fp(long(a));
      if (!std::isfinite(phi)) {
        sq.done = sq.skipped = true;
        continue;
      }
      take_value(sq, phi, std::abs(F0(k)), s.reach(k));
      if (!sq.done && step == kMaxSteps)
        sq.done = true, sq.skipped = sq.hi < 0;
      if (!sq.done)
        still.push_back(k);
    }
    active.swap(still);
  }
  for (long k = 0; k < n; ++k) {
    const Search& sq = q[size_t(k)];
    skipped[size_t(k)] = sq.skipped;
    if (!sq.skipped)
      d(k) = (F0(k) > 0 ? 1 : -1) * sq.t;
  }
}

} // namespace

FacetSag facet_sag(const ImplicitFunction& f, const Eigen::MatrixXd& V, const Eigen::MatrixXi& B,
                   int threads) {
  if (B.cols() != 3 && B.cols() != 4)
    throw std::invalid_argument("facet_sag: B must have 3 or 4 columns");
  const long tasks = detail::chunk_count(B.rows(), kFacetsPerTask);
  std::vector<FacetSag> part(static_cast<size_t>(tasks));
  detail::parallel_chunks(B.rows(), kFacetsPerTask, threads, [&](long task, long b0, long b1) {
    const Samples s = B.cols() == 3 ? triangle_samples(V, B, b0, b1) : quad_samples(V, B, b0, b1);
    Eigen::VectorXd d;
    std::vector<char> skipped;
    distances(f, s, d, skipped);
    FacetSag& p = part[size_t(task)];
    for (long k = 0; k < s.X.rows(); ++k) {
      (skipped[size_t(k)] ? p.skipped_area : p.area) += s.w(k);
      p.volume += s.w(k) * d(k);
      p.max_distance = std::max(p.max_distance, std::abs(d(k)));
    }
  });
  FacetSag r;
  for (const FacetSag& p : part) { // in task order: the same sum for any thread count
    r.volume += p.volume, r.area += p.area, r.skipped_area += p.skipped_area;
    r.max_distance = std::max(r.max_distance, p.max_distance);
  }
  return r;
}

double cell_for_sag(double h, double fraction, double target, double order) {
  const double a = std::abs(fraction);
  return a > target ? 0.9 * h * std::pow(target / a, 1 / order) : h;
}

} // namespace interlin
