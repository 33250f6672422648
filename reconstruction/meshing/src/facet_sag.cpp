// The volume between boundary facets and F = 0 (facet_sag.h).
#include "interlin/reconstruction/meshing/facet_sag.h"

#include "interlin/reconstruction/meshing/project_to_zero.h"

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
constexpr int kScanSteps = 8;       // steps of an eighth of the facet's diameter
constexpr double kTolerance = 1e-9; // of the facet's diameter: a corner on F = 0

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

// The signed distance of every sample to F = 0 along its normal (0 for skipped ones, flagged):
// seed 003's findBorder (project_along) from the sample, steps of an eighth of the facet's
// diameter up to the diameter, then regula falsi.
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
  std::vector<long> rows;
  for (long k = 0; k < n; ++k) {
    const double g = G.row(k).norm();
    if (std::abs(F0(k)) <= kTolerance * g * s.reach(k) || s.w(k) == 0)
      continue; // on F = 0 to first order (corners): distance 0
    if (!std::isfinite(F0(k)) || !(g > 0) || -G.row(k).dot(s.N.row(k)) < kMinCosine * g)
      skipped[size_t(k)] = 1;
    else
      rows.push_back(k);
  }
  Eigen::MatrixXd P(long(rows.size()), 3), D(long(rows.size()), 3);
  Eigen::VectorXd h(long(rows.size()));
  for (size_t a = 0; a < rows.size(); ++a)
    P.row(long(a)) = s.X.row(rows[a]), D.row(long(a)) = s.N.row(rows[a]),
    h(long(a)) = s.reach(rows[a]) / kScanSteps;
  RootOptions o;
  o.threads = 1; // facet_sag's tasks are the parallel loop
  std::vector<char> moved;
  project_along(f, P, D, h, o, &moved, kScanSteps, 1);
  for (size_t a = 0; a < rows.size(); ++a) {
    const long k = rows[a];
    if (moved[a])
      d(k) = (P.row(long(a)) - s.X.row(k)).dot(s.N.row(k));
    else
      skipped[size_t(k)] = 1; // no zero within the facet's diameter
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
