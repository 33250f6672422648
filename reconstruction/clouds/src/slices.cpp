#include "interlin/reconstruction/clouds/slices.h"

#include "nearest_neighbours.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numeric>

namespace interlin {

using Eigen::Index;
using Eigen::Vector3d;

namespace {

// A slice boundary is a gap in the sorted stations at least this many times larger than every
// gap inside the slices (noise-free slices have ratios of 10^3 and more, slices 8 sigma apart
// still about 5; the largest gaps of an
// unstructured cloud's stations differ by small factors).
constexpr double kSliceGapRatio = 4;
constexpr Index kMinSlicePoints = 8; // fewer cannot be fitted by a closed cubic with smoothing
// order_profile: the ends of the chord (this fraction of it) are ordered by angle (noses).
constexpr double kNoseZone = 0.1;
// order_profile: chord bins whose offset range is below this share of the median range hold one
// side only and do not place the mean line.
constexpr double kTwoSided = 0.5;

// Density fallback (noisy slices, where tail gaps inside the slices rival the gaps between
// them): stations are split at the valleys of their kernel density estimate (Gaussian kernel of
// the noise's width) whose density is below kValley times the lower of the two peaks beside it.
// Slices 8 sigma apart have valleys at exp(-(4 sigma)^2 / (2 * 2 sigma^2)) = 2e-2 of their peaks;
// noise inside one slice has no valley at all at that bandwidth.
constexpr double kValley = 0.1;
constexpr int kBinsPerWidth = 4; // histogram bins per kernel width
// Unevenly spaced slices: the gaps between close slices can rival the gaps inside the others, and
// the gap cuts then merge the close ones into one slice of two peaks. A slice whose station spread
// exceeds this many times the median slice's is split at the valleys of its density (kValley):
// two slices 8 sigma apart merged have 4.1 times the spread of one.
constexpr double kWideSlice = 2.5;

struct Split {
  double score = 0; // slice spacing / spread (larger: thinner slices; 0: no split)
  SliceFamily family;
};

// The family whose slices are the stations s (sorted, with point rows) between the cuts
// (increasing station values), with the checks of detect_slices; score 0 when they fail.
Split family_from_cuts(const Eigen::MatrixX3d& P, const SliceFamily& candidate,
                       const std::vector<std::pair<double, Index>>& s,
                       const std::vector<double>& cuts) {
  Split out;
  SliceFamily f = candidate;
  std::vector<Index> current;
  size_t next = 0;
  for (const auto& [station, row] : s) {
    if (next < cuts.size() && station >= cuts[next]) {
      f.members.push_back(current);
      current.clear();
      while (next < cuts.size() && station >= cuts[next])
        ++next;
    }
    current.push_back(row);
  }
  f.members.push_back(current);
  if (f.members.size() < 3)
    return out;
  double sq = 0, worst_spread = 0;
  for (const auto& m : f.members) {
    if (Index(m.size()) < kMinSlicePoints)
      return out;
    double mean = 0;
    for (Index i : m)
      mean += f.station(P.row(i).transpose()) / double(m.size());
    double v = 0;
    Eigen::Vector3d lo = P.row(m[0]).transpose(), hi = lo;
    for (Index i : m) {
      v += std::pow(f.station(P.row(i).transpose()) - mean, 2);
      lo = lo.cwiseMin(P.row(i).transpose());
      hi = hi.cwiseMax(P.row(i).transpose());
    }
    const double spread = std::sqrt(v / double(m.size()));
    if ((hi - lo).norm() < 10 * spread) // a block of points, not a profile
      return out;
    worst_spread = std::max(worst_spread, spread);
    sq += v;
    f.stations.push_back(mean);
  }
  double spacing = 1e300;
  for (size_t k = 0; k + 1 < f.stations.size(); ++k)
    spacing = std::min(spacing, f.stations[k + 1] - f.stations[k]);
  if (worst_spread > 0.25 * spacing)
    return out;
  f.spread = std::sqrt(sq / double(s.size()));
  out.score = spacing / std::max(f.spread, 1e-15 * spacing);
  out.family = std::move(f);
  return out;
}

// Cuts at the gaps that stand out: the m largest gaps when the m-th is at least kSliceGapRatio
// times the (m+1)-th, for the m with the largest ratio; none when no m reaches it.
std::vector<double> gap_cuts(const std::vector<std::pair<double, Index>>& s) {
  const size_t n = s.size();
  std::vector<double> gaps(n - 1);
  for (size_t j = 0; j + 1 < n; ++j)
    gaps[j] = s[j + 1].first - s[j].first;
  std::vector<double> desc = gaps;
  std::sort(desc.begin(), desc.end(), std::greater<>());
  // m largest gaps are boundaries: m + 1 slices, at least 3, each of kMinSlicePoints on average
  size_t best_m = 0;
  double best = 0;
  // gaps below round-off of the stations (exact slices) count as that round-off
  const double eps = 1e-12 * (s.back().first - s.front().first) + 1e-300;
  for (size_t m = 2; m < desc.size() && (m + 1) * size_t(kMinSlicePoints) <= n; ++m) {
    const double r = std::max(desc[m - 1], eps) / std::max(desc[m], eps);
    if (r > best)
      best = r, best_m = m;
  }
  std::vector<double> cuts;
  if (best < kSliceGapRatio)
    return cuts;
  for (size_t j = 0; j + 1 < n; ++j)
    if (gaps[j] >= desc[best_m - 1])
      cuts.push_back(0.5 * (s[j].first + s[j + 1].first));
  return cuts;
}

// Cuts at the deep valleys of the stations' density (kValley), kernel width `width`.
std::vector<double> density_cuts(const std::vector<std::pair<double, Index>>& s, double width) {
  std::vector<double> cuts;
  const double lo = s.front().first, range = s.back().first - lo, bin = width / kBinsPerWidth;
  if (!(width > 0) || !(range / bin < 1e6)) // degenerate, or too fine to histogram
    return cuts;
  const int nb = int(range / bin) + 1 + 2 * 4 * kBinsPerWidth;
  const int pad = 4 * kBinsPerWidth; // the kernel's reach, 4 widths
  std::vector<double> h(size_t(nb), 0), d(size_t(nb), 0);
  for (const auto& [station, row] : s)
    h[size_t(pad + int((station - lo) / bin))] += 1;
  for (int i = 0; i < nb; ++i)
    for (int j = std::max(0, i - pad); j <= std::min(nb - 1, i + pad); ++j)
      d[size_t(i)] += h[size_t(j)] * std::exp(-0.5 * std::pow(double(i - j) / kBinsPerWidth, 2));
  std::vector<int> peaks;
  for (int i = 1; i + 1 < nb; ++i)
    if (d[size_t(i)] > d[size_t(i - 1)] && d[size_t(i)] >= d[size_t(i + 1)])
      peaks.push_back(i);
  auto valley = [&](int a, int b) {
    return int(std::min_element(d.begin() + a, d.begin() + b + 1) - d.begin());
  };
  // merge peaks across shallow valleys (keep the higher) until every valley is deep
  for (bool merged = true; merged && peaks.size() > 1;) {
    merged = false;
    for (size_t k = 0; k + 1 < peaks.size(); ++k) {
      const double top = std::min(d[size_t(peaks[k])], d[size_t(peaks[k + 1])]);
      if (d[size_t(valley(peaks[k], peaks[k + 1]))] >= kValley * top) {
        peaks.erase(peaks.begin() +
                    long(k + (d[size_t(peaks[k])] < d[size_t(peaks[k + 1])] ? 0 : 1)));
        merged = true;
        break;
      }
    }
  }
  for (size_t k = 0; k + 1 < peaks.size(); ++k)
    cuts.push_back(lo + (valley(peaks[k], peaks[k + 1]) - pad + 0.5) * bin);
  // a few stray points beyond a valley are a slice's tail, not a slice: drop the cut next to
  // a part with fewer than kMinSlicePoints points (the one on the part's emptier side)
  for (bool dropped = true; dropped && !cuts.empty();) {
    dropped = false;
    std::vector<Index> count(cuts.size() + 1, 0);
    for (const auto& [station, row] : s)
      ++count[size_t(std::upper_bound(cuts.begin(), cuts.end(), station) - cuts.begin())];
    for (size_t k = 0; k < count.size() && !dropped; ++k)
      if (count[k] < kMinSlicePoints) {
        const size_t c = k == 0             ? 0
                         : k == cuts.size() ? k - 1
                                            : (count[k - 1] < count[k + 1] ? k - 1 : k);
        cuts.erase(cuts.begin() + long(c));
        dropped = true;
      }
  }
  return cuts;
}

// Where each part between the cuts begins in s (sorted): cuts.size() + 2 indices, the last
// s.size(); a station on a cut belongs to the part above it, as in family_from_cuts.
std::vector<size_t> part_starts(const std::vector<std::pair<double, Index>>& s,
                                const std::vector<double>& cuts) {
  std::vector<size_t> b{0};
  for (double cut : cuts)
    b.push_back(size_t(std::lower_bound(s.begin(), s.end(), cut,
                                        [](const auto& e, double x) { return e.first < x; }) -
                       s.begin()));
  b.push_back(s.size());
  return b;
}

// The parts (part_starts b) whose station spread exceeds kWideSlice times the median part's (at
// least 1e-9 of the stations' range); none when there are fewer than 3 parts.
std::vector<size_t> wide_parts(const std::vector<std::pair<double, Index>>& s,
                               const std::vector<size_t>& b) {
  std::vector<size_t> wide;
  const size_t parts = b.size() - 1;
  if (parts < 3)
    return wide;
  std::vector<double> spread(parts, 0);
  for (size_t k = 0; k < parts; ++k) {
    const double n = double(b[k + 1] - b[k]);
    double mean = 0, sq = 0;
    for (size_t i = b[k]; i < b[k + 1]; ++i)
      mean += s[i].first / n;
    for (size_t i = b[k]; i < b[k + 1]; ++i)
      sq += std::pow(s[i].first - mean, 2);
    spread[k] = n > 0 ? std::sqrt(sq / n) : 0;
  }
  std::vector<double> sorted = spread;
  std::nth_element(sorted.begin(), sorted.begin() + long(parts / 2), sorted.end());
  // spreads of round-off (exact slices) count as 1e-9 of the stations' range
  const double floor = 1e-9 * (s.back().first - s.front().first);
  for (size_t k = 0; k < parts; ++k)
    if (spread[k] > kWideSlice * std::max(sorted[parts / 2], floor))
      wide.push_back(k);
  return wide;
}

// The cuts with the wide parts (of part_starts b) split at the valleys of their own density
// (density_cuts, kernel width `width`).
std::vector<double> split_parts(const std::vector<std::pair<double, Index>>& s,
                                std::vector<double> cuts, const std::vector<size_t>& b,
                                const std::vector<size_t>& wide, double width) {
  for (size_t k : wide)
    if (b[k + 1] - b[k] >= 2 * size_t(kMinSlicePoints)) {
      const std::vector<double> inner = density_cuts(
          std::vector<std::pair<double, Index>>(s.begin() + long(b[k]), s.begin() + long(b[k + 1])),
          width);
      cuts.insert(cuts.end(), inner.begin(), inner.end());
    }
  std::sort(cuts.begin(), cuts.end());
  return cuts;
}

// The noise of the stations along the candidate's axis: for each of up to kWidthSamples points,
// the median |s_i - s_j| over its nearest neighbours j (in 3D: the same slice when the slices are
// farther apart than the points along them), the median of that over the points, divided by
// 0.6745 sqrt(2) (the median of |s_i - s_j| for two independent normal stations). Neighbours
// chosen in 3D favour close stations, so this underestimates the noise a little: the kernel is
// then a little narrow, which deepens the valleys between slices.
double station_noise(const Eigen::MatrixX3d& P, const SliceFamily& c, const Eigen::MatrixXi& knn) {
  constexpr Index kWidthSamples = 4000;
  const Index n = P.rows(), step = std::max<Index>(1, n / kWidthSamples);
  std::vector<double> med, d(size_t(knn.cols()));
  for (Index i = 0; i < n; i += step) {
    const double si = c.station(P.row(i).transpose());
    for (Index j = 0; j < knn.cols(); ++j)
      d[size_t(j)] = std::abs(c.station(P.row(knn(i, j)).transpose()) - si);
    std::nth_element(d.begin(), d.begin() + long(d.size() / 2), d.end());
    med.push_back(d[d.size() / 2]);
  }
  std::nth_element(med.begin(), med.begin() + long(med.size() / 2), med.end());
  return med[med.size() / 2] / (0.6745 * std::sqrt(2.0));
}

// Splits the stations into slices (see detect_slices): at the gaps that stand out, else at the
// valleys of their density with the kernel width `width` (the noise along the axis).
// The k nearest neighbours of every point, found on first use (only the density fallback needs
// them).
struct LazyNeighbours {
  static constexpr int kNeighbours = 10;
  const Eigen::MatrixX3d& P;
  Eigen::MatrixXi knn;
  const Eigen::MatrixXi& get() {
    if (knn.size() == 0)
      knn = detail::NeighbourIndex(P).knn_all(kNeighbours);
    return knn;
  }
};

Split split_stations(const Eigen::MatrixX3d& P, const SliceFamily& candidate,
                     LazyNeighbours& neighbours) {
  const Index n = P.rows();
  if (n < 3 * kMinSlicePoints)
    return {};
  std::vector<std::pair<double, Index>> s(static_cast<size_t>(n));
  for (Index i = 0; i < n; ++i)
    s[size_t(i)] = {candidate.station(P.row(i).transpose()), i};
  std::sort(s.begin(), s.end());
  double noise = -1; // station_noise, found on first use
  auto width = [&] {
    if (noise < 0)
      noise = station_noise(P, candidate, neighbours.get());
    return noise;
  };
  std::vector<double> cuts = gap_cuts(s);
  const std::vector<size_t> b = part_starts(s, cuts);
  if (const std::vector<size_t> wide = wide_parts(s, b); !wide.empty())
    cuts = split_parts(s, cuts, b, wide, width());
  Split out = family_from_cuts(P, candidate, s, cuts);
  if (out.score == 0)
    out = family_from_cuts(P, candidate, s, density_cuts(s, width()));
  return out;
}

std::vector<Vector3d> candidate_axes(const Eigen::MatrixX3d& P, bool principal) {
  std::vector<Vector3d> axes{Vector3d::UnitX(), Vector3d::UnitY(), Vector3d::UnitZ()};
  if (principal) {
    const Eigen::MatrixX3d C = P.rowwise() - P.colwise().mean();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(C.transpose() * C);
    for (int k = 0; k < 3; ++k)
      axes.push_back(es.eigenvectors().col(k).normalized());
  }
  return axes;
}

// The normal n minimising sum_k sum_{i in slice k} (n . (p_i - mean_k))^2: the eigenvector of the
// pooled within-slice scatter with the smallest eigenvalue.
SliceFamily refined_normal(const Eigen::MatrixX3d& P, const SliceFamily& f) {
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  for (const auto& m : f.members) {
    const Eigen::MatrixX3d Q = P(m, Eigen::all);
    const Eigen::MatrixX3d C = Q.rowwise() - Q.colwise().mean();
    S += C.transpose() * C;
  }
  SliceFamily r;
  r.kind = f.kind;
  r.axis = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(S).eigenvectors().col(0).normalized();
  if (r.axis.dot(f.axis) < 0)
    r.axis = -r.axis;
  return r;
}

} // namespace

double SliceFamily::station(const Vector3d& p) const {
  if (kind == SliceKind::radial)
    return (p - axis.dot(p) * axis).norm();
  return axis.dot(p);
}

SliceFamily detect_slices(const Eigen::MatrixX3d& P, SliceKind kind) {
  Split best;
  LazyNeighbours neighbours{P, {}};
  for (SliceKind k : {SliceKind::planar, SliceKind::radial}) {
    if (kind != SliceKind::automatic && kind != k)
      continue;
    for (const Vector3d& a : candidate_axes(P, k == SliceKind::planar)) {
      SliceFamily c;
      c.kind = k;
      c.axis = a;
      Split s = split_stations(P, c, neighbours);
      if (s.score > best.score)
        best = std::move(s);
    }
  }
  if (best.family.kind == SliceKind::planar) { // the common normal that fits the slices best
    Split refined = split_stations(P, refined_normal(P, best.family), neighbours);
    if (refined.score > 0)
      best = std::move(refined);
  }
  return best.family; // kind none when nothing passed
}

std::vector<Index> order_profile(const Eigen::MatrixX2d& P) {
  const Index n = P.rows();
  const Eigen::RowVector2d c = P.colwise().mean();
  Index a = 0, b = 0;
  (P.rowwise() - c).rowwise().squaredNorm().maxCoeff(&a);
  (P.rowwise() - P.row(a)).rowwise().squaredNorm().maxCoeff(&b);
  const Eigen::RowVector2d t = (P.row(b) - P.row(a)).normalized();
  const double L = (P.row(b) - P.row(a)).norm();
  Eigen::VectorXd s(n), w(n);
  for (Index i = 0; i < n; ++i) {
    const Eigen::RowVector2d d = P.row(i) - P.row(a);
    s(i) = std::clamp(d.dot(t) / L, 0.0, 1.0);
    w(i) = t(0) * d(1) - t(1) * d(0);
  }
  // mean line: midpoint of the extreme offsets per bin (about 16 points per bin, 4 to 64 bins)
  const int bins = int(std::clamp<Index>(n / 16, 4, 64));
  std::vector<double> lo(size_t(bins), 1e300), hi(size_t(bins), -1e300);
  auto bin = [&](double x) { return std::min(bins - 1, int(x * bins)); };
  for (Index i = 0; i < n; ++i) {
    lo[size_t(bin(s(i)))] = std::min(lo[size_t(bin(s(i)))], w(i));
    hi[size_t(bin(s(i)))] = std::max(hi[size_t(bin(s(i)))], w(i));
  }
  // Only bins that hold both sides: randomly placed points leave some bins with points of one
  // side alone, whose midpoint would cut that side (their offset range is the side's slope over
  // the bin, well under the profile's thickness; kept: at least kTwoSided of the median range).
  std::vector<double> range;
  for (int k = 0; k < bins; ++k)
    if (lo[size_t(k)] <= hi[size_t(k)])
      range.push_back(hi[size_t(k)] - lo[size_t(k)]);
  std::nth_element(range.begin(), range.begin() + Index(range.size() / 2), range.end());
  const double least = kTwoSided * range[range.size() / 2];
  std::vector<double> xs, mid;
  for (int k = 0; k < bins; ++k)
    if (lo[size_t(k)] <= hi[size_t(k)] && hi[size_t(k)] - lo[size_t(k)] >= least) {
      xs.push_back((k + 0.5) / bins);
      mid.push_back(0.5 * (lo[size_t(k)] + hi[size_t(k)]));
    }
  auto mean_line = [&](double x) {
    const size_t j = size_t(std::upper_bound(xs.begin(), xs.end(), x) - xs.begin());
    if (j == 0)
      return mid.front();
    if (j == xs.size())
      return mid.back();
    const double f = (x - xs[j - 1]) / (xs[j] - xs[j - 1]);
    return (1 - f) * mid[j - 1] + f * mid[j];
  };
  // Middle: each side by chord position. Within kNoseZone of either end: by the angle about the
  // mean line's point at the zone's inner edge (a nose is star-shaped from there, where the sides
  // are no longer graphs over the chord at the scale of the noise).
  std::vector<std::pair<double, Index>> lead, upper, trail, lower;
  const Eigen::Vector2d ca(kNoseZone * L, mean_line(kNoseZone)),
      cb((1 - kNoseZone) * L, mean_line(1 - kNoseZone));
  for (Index i = 0; i < n; ++i) {
    const Eigen::Vector2d q(s(i) * L, w(i));
    if (s(i) < kNoseZone) // from the lower side round to the upper one
      lead.push_back({std::atan2(q(1) - ca(1), ca(0) - q(0)), i});
    else if (s(i) > 1 - kNoseZone) // from the upper side round to the lower one
      trail.push_back({-std::atan2(q(1) - cb(1), q(0) - cb(0)), i});
    else if (w(i) >= mean_line(s(i)))
      upper.push_back({s(i), i});
    else
      lower.push_back({-s(i), i});
  }
  std::vector<Index> order;
  for (auto* part : {&lead, &upper, &trail, &lower}) {
    std::sort(part->begin(), part->end());
    for (const auto& [key, i] : *part)
      order.push_back(i);
  }
  return order;
}

} // namespace interlin
