// Spanwise parameters from the stack's geometry (stations) or from chord lengths (seed 001 §2.5).
#include "interlin/reconstruction/loft/span_parameters.h"

#include "interlin/reconstruction/loft/section_prep.h"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::Vector2d;
using Eigen::Vector3d;
using Eigen::VectorXd;

std::string to_string(SpanParameters p) {
  switch (p) {
  case SpanParameters::automatic:
    return "auto";
  case SpanParameters::station:
    return "station";
  case SpanParameters::chord:
    return "chord";
  case SpanParameters::centripetal:
    return "centripetal";
  case SpanParameters::uniform:
    return "uniform";
  }
  return "?";
}

std::string to_string(Stacking s) {
  switch (s) {
  case Stacking::none:
    return "none";
  case Stacking::parallel_planes:
    return "parallel planes";
  case Stacking::coaxial_revolution:
    return "coaxial surfaces of revolution about z";
  }
  return "?";
}

namespace {

// Smallest gap between neighbouring stations; <= 0 when they do not increase strictly.
double smallest_gap(const VectorXd& station) {
  double gap = INFINITY;
  for (Index k = 0; k + 1 < station.size(); ++k)
    gap = std::min(gap, station(k + 1) - station(k));
  return gap;
}

// Parallel planes: the common normal is the mean of the sections' unit vector areas (Newell),
// each turned to agree with the first; the station of a section is its mean point along the
// normal, its width the extent of its points along the normal.
SectionStations plane_stations(const std::vector<MatrixXd>& sections) {
  const Index K = static_cast<Index>(sections.size());
  SectionStations s;
  const Vector3d first = vector_area(sections[0]).normalized();
  Vector3d n = Vector3d::Zero();
  for (const MatrixXd& P : sections) {
    const Vector3d a = vector_area(P).normalized();
    n += a.dot(first) < 0 ? -a : a;
  }
  if (!(n.norm() > 0))
    return s;
  n.normalize();
  s.station.resize(K);
  double width = 0;
  for (Index k = 0; k < K; ++k) {
    const VectorXd h = sections[static_cast<size_t>(k)] * n;
    s.station(k) = h.mean();
    width = std::max(width, h.maxCoeff() - h.minCoeff());
  }
  if (s.station(K - 1) < s.station(0)) { // orient from the first section to the last
    n = -n;
    s.station = -s.station;
  }
  s.normal = n;
  const double gap = smallest_gap(s.station);
  s.spread = gap > 0 ? width / gap : INFINITY;
  return s;
}

// Distance from q to the polyline of the rows [a, b] of M (cyclic), in the plane.
double distance_to_arc(const MatrixXd& M, Index a, Index b, const Vector2d& q) {
  const Index n = M.rows();
  double best = INFINITY;
  for (Index i = a; i != b; i = (i + 1) % n) {
    const Vector2d p = M.row(i).transpose(), d = M.row((i + 1) % n).transpose() - p;
    const double t =
        d.squaredNorm() > 0 ? std::clamp((q - p).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    best = std::min(best, (p + t * d - q).norm());
  }
  return best;
}

// The meridional trace (z, R) of a section: #P by 2.
MatrixXd meridional_trace(const MatrixXd& P) {
  MatrixXd M(P.rows(), 2);
  M.col(0) = P.col(2);
  M.col(1) = P.leftCols(2).rowwise().norm();
  return M;
}

// Width of a closed section in the meridional plane: the trace M is cut at its two extreme
// points along its principal direction into two sides; the width is the largest distance of a
// point of one side to the polyline of the other. A section on a surface of revolution about z
// traces one meridional arc out and back: width ~ 0.
double meridional_width(const MatrixXd& M) {
  const Index n = M.rows();
  const MatrixXd C = M.rowwise() - M.colwise().mean();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(C.transpose() * C);
  const VectorXd xi = C * eig.eigenvectors().col(1); // largest eigenvalue last
  Index lo = 0, hi = 0;
  xi.minCoeff(&lo);
  xi.maxCoeff(&hi);
  double width = 0;
  for (Index i = 0; i < n; ++i) {
    const bool on_first = ((i - lo + n) % n) <= ((hi - lo + n) % n);
    const Vector2d q = M.row(i).transpose();
    width =
        std::max(width, on_first ? distance_to_arc(M, hi, lo, q) : distance_to_arc(M, lo, hi, q));
  }
  return width;
}

// Coaxial surfaces of revolution about z. The station is the meridional position of each
// section's stream surface: the traces are expressed in one frame of the meridional plane (e the
// common flow direction, the principal direction of all traces about their own centres; n across
// it), each trace's offset eta = n . (z, R) is fitted as a quadratic in xi = e . (z, R) by least
// squares, and evaluated at one reference xi* (the mean of the traces' centres). For cylinders
// this is the radius, for cones R = R0 + a z the offset R0 (scaled), for curved stream surfaces
// their distance across the flow path at mid-chord; a mean radius would shift with each
// section's own axial extent on inclined surfaces.
SectionStations revolution_stations(const std::vector<MatrixXd>& sections) {
  const Index K = static_cast<Index>(sections.size());
  std::vector<MatrixXd> traces;
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  std::vector<Eigen::RowVector2d> centre;
  double width = 0;
  for (const MatrixXd& P : sections) {
    traces.push_back(meridional_trace(P));
    centre.push_back(traces.back().colwise().mean());
    const MatrixXd C = traces.back().rowwise() - centre.back();
    scatter += C.transpose() * C;
    width = std::max(width, meridional_width(traces.back()));
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(scatter);
  const Vector2d e = eig.eigenvectors().col(1), n(-e(1), e(0));
  double xi_ref = 0;
  for (const Eigen::RowVector2d& c : centre)
    xi_ref += c.dot(e.transpose()) / static_cast<double>(K);
  SectionStations s;
  s.station.resize(K);
  for (Index k = 0; k < K; ++k) {
    const MatrixXd& M = traces[static_cast<size_t>(k)];
    const VectorXd xi = (M * e).array() - xi_ref, eta = M * n;
    MatrixXd A(M.rows(), 3);
    A << VectorXd::Ones(M.rows()), xi, xi.cwiseProduct(xi);
    s.station(k) = A.colPivHouseholderQr().solve(eta)(0); // the quadratic at xi = xi_ref
  }
  if (s.station(K - 1) < s.station(0))
    s.station = -s.station;
  const double gap = smallest_gap(s.station);
  s.spread = gap > 0 ? width / gap : INFINITY;
  return s;
}

} // namespace

SectionStations section_stations(const std::vector<MatrixXd>& sections) {
  if (sections.size() < 2)
    throw std::invalid_argument("stations need at least 2 sections");
  // Both criteria can hold (a nearly flat patch of a cone; planes z = const are surfaces of
  // revolution about z too): the stacking that locates the sections better wins, planes on a tie
  // (spreads below 1e-9 are round-off of the coordinates: equal).
  SectionStations planes = plane_stations(sections);
  SectionStations revolution = revolution_stations(sections);
  const auto level = [](double spread) { return std::max(spread, 1e-9); };
  if (planes.spread <= kStationSpread && level(planes.spread) <= level(revolution.spread)) {
    planes.stacking = Stacking::parallel_planes;
    return planes;
  }
  if (revolution.spread <= kStationSpread) {
    revolution.stacking = Stacking::coaxial_revolution;
    return revolution;
  }
  SectionStations none;
  none.spread = std::min(planes.spread, revolution.spread);
  return none;
}

VectorXd span_parameters(SpanParameters p, const VectorXd& distance, const VectorXd& station) {
  const Index K = distance.size() + 1;
  VectorXd gap(K - 1);
  switch (p) {
  case SpanParameters::station:
    if (station.size() != K)
      throw std::invalid_argument("station span parameters need the sections' stations");
    gap = station.tail(K - 1) - station.head(K - 1);
    break;
  case SpanParameters::chord:
    gap = distance;
    break;
  case SpanParameters::centripetal:
    gap = distance.cwiseSqrt();
    break;
  case SpanParameters::uniform:
    gap.setOnes();
    break;
  case SpanParameters::automatic:
    throw std::invalid_argument("span_parameters: choose the parameters first (span_model.h)");
  }
  VectorXd v(K);
  v(0) = 0;
  for (Index k = 1; k < K; ++k)
    v(k) = v(k - 1) + gap(k - 1);
  v /= v(K - 1);
  v(K - 1) = 1.0;
  return v;
}

} // namespace interlin
