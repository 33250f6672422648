// Patch signs chosen by the winding number (orient_normals.h, orient_by_winding_number).
#include "interlin/reconstruction/clouds/orient_normals.h"

#include "exterior_side.h"
#include "nearest_neighbours.h"
#include "orientation_tree.h"
#include "winding_number.h"

#include "interlin/reconstruction/clouds/noise_level.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace interlin {

using Eigen::Index;

namespace {

// Neighbours i, j join one patch when their normals agree within 30 degrees and the edge lies
// within 30 degrees of both tangent planes (plus 2 noise sigmas): one smooth sheet, oriented one
// way. Points whose kSmoothNeighbours nearest normals are not all within 30 degrees of their own
// (up to sign) sit on a sharp rim or a thin wall's edge, where the estimated normal is unreliable:
// they join no patch and take the sign change of the nearest decided patch.
const double kPatchCos = std::cos(30.0 * M_PI / 180.0), kPatchSin = 0.5;
constexpr double kPatchSigmas = 2;
constexpr int kSmoothNeighbours = 8;
// Patches end at the faces of a grid of cells kCellsPerDiagonal to the bounding box diagonal: a
// patch that leaked across a thin wall's noisy edge then spans only the cells by that edge.
constexpr double kCellsPerDiagonal = 8;
// The patches decided: the kMaxPatches largest with at least kMinPatchShare of the points and
// kMinPatchPoints points. On a sparse scan (PCL's bunny, 392 points) nearly every point is its own
// patch; free signs for single points let the descent lower the measure by scattering flips
// (bunny: 178 normals turned, fit rms 0.0030 -> 0.0126), so such patches stay as propagated.
constexpr int kMaxPatches = 256;
constexpr double kMinPatchShare = 0.002, kMinPatchPoints = 20;
// Probes per decided patch (at most), outside each probed point at kProbeSpacings point
// spacings plus kProbeSigmas noise sigmas along its normal.
constexpr int kProbesPerPatch = 40;
constexpr double kProbeSpacings = 2, kProbeSigmas = 3;
constexpr Index kCheckProbes = 4000; // outside_winding's probes
// Thin-wall sides: the neighbours searched for the other side of the wall, the offsets along the
// normal beyond which a neighbour counts as off the point's own sheet (noise sigmas), and the
// probe offsets (point spacings) of the decided patches' winding number that must agree.
constexpr int kSideNeighbours = 32;
constexpr double kSideSigmas = 4;
constexpr double kSideProbes[] = {0.25, 0.5, 1.0};
// A wall, not a narrow gap: among the kWallNeighbours nearest points, pairs with antiparallel
// normals (within 30 degrees) each more than kWallSpacings point spacings behind the other
// outnumber the pairs each in front of the other (a gap's facing sides, or a slot's).
constexpr int kWallNeighbours = 16;
constexpr double kWallSpacings = 0.5;
// The thin-wall passes: each reads the normals the previous one left, so a side whose neighbours
// were mostly wrong (a gap to the wall test) is turned once enough of them are right; a point
// turned is never turned back (its tests then both say outward). At most kMaxSidePasses.
constexpr int kMaxSidePasses = 10;

// The flood fill's votes (exterior_side.h, voxels of kVoxelSpacings point spacings: finer ones
// leak through the sampling's gaps, the UAV at 1 spacing); a patch takes the votes' sign when at
// least kVotedShare of its points vote and kVoteAgreement of the votes agree.
constexpr double kVotedShare = 0.2, kVoteAgreement = 0.9;

int find(std::vector<int>& parent, int i) {
  while (parent[size_t(i)] != i)
    i = parent[size_t(i)] = parent[size_t(parent[size_t(i)])];
  return i;
}

// Whether each point's normal agrees (up to sign) with its nearest neighbours' normals.
std::vector<bool> smooth_points(const Eigen::MatrixX3d& N, const Eigen::MatrixXi& K) {
  std::vector<bool> smooth(size_t(N.rows()), true);
  for (Index i = 0; i < N.rows(); ++i)
    for (Index c = 0; c < std::min<Index>(kSmoothNeighbours, K.cols()); ++c)
      if (std::abs(N.row(i).dot(N.row(K(i, c)))) < kPatchCos)
        smooth[size_t(i)] = false;
  return smooth;
}

// Patch label of every point (union-find over the neighbour edges that join a patch).
std::vector<int> patches(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& N,
                         const Eigen::MatrixXi& K, double sigma) {
  const std::vector<bool> smooth = smooth_points(N, K);
  const Eigen::RowVector3d lo = P.colwise().minCoeff();
  const double cell = (P.colwise().maxCoeff() - lo).norm() / kCellsPerDiagonal;
  auto cell_of = [&](Index i) {
    const Eigen::Array3i c = ((P.row(i) - lo) / cell).array().floor().cast<int>();
    return (long(c(2)) * 4096 + c(1)) * 4096 + c(0);
  };
  std::vector<int> parent(size_t(P.rows()));
  std::iota(parent.begin(), parent.end(), 0);
  for (Index i = 0; i < K.rows(); ++i)
    for (Index c = 0; c < K.cols(); ++c) {
      const Index j = K(i, c);
      const Eigen::RowVector3d e = P.row(j) - P.row(i);
      const double slack = kPatchSin * e.norm() + kPatchSigmas * sigma;
      if (!smooth[size_t(i)] || !smooth[size_t(j)] || cell_of(i) != cell_of(j) ||
          N.row(i).dot(N.row(j)) < kPatchCos || std::abs(N.row(i).dot(e)) > slack ||
          std::abs(N.row(j).dot(e)) > slack)
        continue;
      parent[size_t(find(parent, int(i)))] = find(parent, int(j));
    }
  std::vector<int> label(parent.size());
  for (size_t i = 0; i < parent.size(); ++i)
    label[i] = find(parent, int(i));
  return label;
}

// The roots of the largest patches (at most kMaxPatches, each >= kMinPatchShare of the points).
std::vector<int> largest_patches(const std::vector<int>& label) {
  std::vector<Index> size(label.size(), 0);
  for (int l : label)
    ++size[size_t(l)];
  std::vector<int> roots;
  for (size_t i = 0; i < label.size(); ++i)
    if (label[i] == int(i) &&
        double(size[i]) >= std::max(kMinPatchShare * double(label.size()), kMinPatchPoints))
      roots.push_back(int(i));
  std::sort(roots.begin(), roots.end(),
            [&](int a, int b) { return size[size_t(a)] > size[size_t(b)]; });
  if (roots.size() > size_t(kMaxPatches))
    roots.resize(size_t(kMaxPatches));
  return roots;
}

// Each decided patch's sign as the flood fill's votes give it (rows[r]: its points; the last
// entry, the undecided points, is not read): +1 or -1 where they decide it, 0 where not.
std::vector<int> voted_signs(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& N,
                             const std::vector<std::vector<Index>>& rows, double spacing) {
  const std::vector<signed char> vote =
      detail::exterior_votes(P, N, detail::kVoxelSpacings * spacing);
  std::vector<int> known(rows.size() - 1, 0);
  for (size_t r = 0; r < known.size(); ++r) {
    double plus = 0, minus = 0;
    for (Index i : rows[r]) {
      plus += vote[size_t(i)] > 0;
      minus += vote[size_t(i)] < 0;
    }
    if (plus + minus >= kVotedShare * double(rows[r].size()) &&
        std::max(plus, minus) >= kVoteAgreement * (plus + minus))
      known[r] = plus > minus ? 1 : -1;
  }
  return known;
}

// The signs s of the decided patches minimising sum over probes of min(|w|, 1) at the outside
// offset of each probed point (its own patch's sign chooses which offset that is): about 0 for
// outward normals everywhere. at_plus[r][q], at_minus[r][q]: patch r's winding number at probe
// q's two offsets. Steepest descent over single flips, the sums at the probes kept up to date;
// the patches with known[r] != 0 keep that sign.
std::vector<int> choose_signs(const std::vector<int>& probe_patch,
                              const std::vector<std::vector<double>>& at_plus,
                              const std::vector<std::vector<double>>& at_minus,
                              const std::vector<int>& known) {
  const size_t R = at_plus.size(), m = probe_patch.size();
  std::vector<int> s(R, 1);
  for (size_t r = 0; r < R; ++r)
    if (known[r] != 0)
      s[r] = known[r];
  std::vector<double> wp(m, 0), wm(m, 0);
  for (size_t r = 0; r < R; ++r)
    for (size_t q = 0; q < m; ++q) {
      wp[q] += s[r] * at_plus[r][q];
      wm[q] += s[r] * at_minus[r][q];
    }
  auto cost = [](int own_sign, double p, double n) {
    return std::min(std::abs(own_sign > 0 ? p : n), 1.0);
  };
  for (size_t steps = 0; steps < 4 * R; ++steps) {
    double best = 0;
    size_t best_r = R;
    for (size_t r = 0; r < R; ++r) {
      if (known[r] != 0)
        continue;
      double delta = 0; // energy change if patch r flips
      for (size_t q = 0; q < m; ++q) {
        const size_t own = size_t(probe_patch[q]);
        const int so = own == r ? -s[own] : s[own];
        delta += cost(so, wp[q] - 2 * s[r] * at_plus[r][q], wm[q] - 2 * s[r] * at_minus[r][q]) -
                 cost(s[own], wp[q], wm[q]);
      }
      if (delta < best - 1e-9) {
        best = delta;
        best_r = r;
      }
    }
    if (best_r == R)
      break;
    for (size_t q = 0; q < m; ++q) {
      wp[q] -= 2 * s[best_r] * at_plus[best_r][q];
      wm[q] -= 2 * s[best_r] * at_minus[best_r][q];
    }
    s[best_r] = -s[best_r];
  }
  return s;
}

// Mean of min(|w|, 1) over up to kCheckProbes points p_i + d n_i outside the cloud (every point's
// own offset as for the patches' probes), w the whole oriented cloud's winding number: the
// measure by which the repaired orientation must beat the propagated one.
double outside_winding(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& N,
                       const Eigen::VectorXd& area, double sigma) {
  const detail::WindingNumber w(P, N, area);
  const Index step = std::max<Index>(1, P.rows() / kCheckProbes);
  double e = 0;
  Index m = 0;
  for (Index i = 0; i < P.rows(); i += step, ++m) {
    const double d = kProbeSpacings * std::sqrt(area(i)) + kProbeSigmas * sigma;
    e += std::min(std::abs(w(P.row(i).transpose() + d * N.row(i).transpose())), 1.0);
  }
  return e / double(std::max<Index>(m, 1));
}

// Whether point i lies on a wall rather than by a narrow gap (kWallNeighbours): the two have the
// same unoriented geometry, a sheet close behind or in front, so the test reads the neighbours'
// current orientation, which is right for most of them (back to back: a wall's two sides).
bool on_a_wall(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& N,
               const detail::NeighbourIndex& index, Index i, double spacing) {
  std::vector<int> q;
  std::vector<double> q2;
  index.knn(P.row(i).transpose(), kWallNeighbours + 1, q, q2);
  const double tau = kWallSpacings * spacing;
  int back = 0, facing = 0;
  for (size_t a = 0; a < q.size(); ++a)
    for (size_t b = a + 1; b < q.size(); ++b) {
      if (N.row(q[a]).dot(N.row(q[b])) >= -kPatchCos)
        continue;
      const Eigen::RowVector3d e = P.row(q[b]) - P.row(q[a]);
      const double ha = e.dot(N.row(q[a])), hb = -e.dot(N.row(q[b])); // each one's offset
      back += ha < -tau && hb < -tau;
      facing += ha > tau && hb > tau;
    }
  return back > facing;
}

// Each point outside the decided patches (which[i] == R: a rim or a thin wall's edge) is turned
// when three tests say its normal points into a wall: (1) its kSideNeighbours nearest points
// that lie within 45 degrees of its normal line and farther than kSideSigmas noise sigmas along
// it (the other side of a thin wall, or the body's own curvature) lie in front of it on the
// whole (sum of their offsets along n positive); (2) the decided patches' winding number is
// larger in front of it than behind it (sum over the kSideProbes offsets); (3) on_a_wall, read
// from the normals before the pass (a narrow gap's or slot's far side also lies in front, and
// (2) is weak there). Passes repeat until one turns none (kMaxSidePasses).
void orient_thin_wall_sides(const Eigen::MatrixX3d& P, Eigen::MatrixX3d& N,
                            const detail::NeighbourIndex& index, const Eigen::VectorXd& area,
                            const std::vector<int>& which, int R, double sigma) {
  std::vector<Index> decided;
  for (Index i = 0; i < P.rows(); ++i)
    if (which[size_t(i)] < R)
      decided.push_back(i);
  if (decided.empty())
    return;
  const detail::WindingNumber w(P(decided, Eigen::all), N(decided, Eigen::all), area(decided));
  auto winding_says_inward = [&](Index i) {
    const Eigen::Vector3d p = P.row(i).transpose(), n = N.row(i).transpose();
    double contrast = 0; // behind minus in front
    for (double f : kSideProbes)
      contrast += w(p - f * std::sqrt(area(i)) * n) - w(p + f * std::sqrt(area(i)) * n);
    return contrast < 0;
  };
  std::vector<int> idx;
  std::vector<double> d2;
  for (int pass = 0; pass < kMaxSidePasses; ++pass) {
    const Eigen::MatrixX3d N_in = N;
    Index turned = 0;
    for (Index i = 0; i < P.rows(); ++i) {
      if (which[size_t(i)] < R)
        continue;
      index.knn(P.row(i).transpose(), kSideNeighbours + 1, idx, d2);
      double ahead = 0; // sum of the off-sheet neighbours' offsets along n
      for (int j : idx) {
        const Eigen::RowVector3d e = P.row(j) - P.row(i);
        const double h = e.dot(N_in.row(i));
        if (std::abs(h) > kSideSigmas * sigma && (e - h * N_in.row(i)).norm() <= std::abs(h))
          ahead += h;
      }
      if (ahead > 0 && winding_says_inward(i) && on_a_wall(P, N_in, index, i, std::sqrt(area(i)))) {
        N.row(i) *= -1;
        ++turned;
      }
    }
    if (turned == 0)
      break;
  }
}

// The decided patches take their signs s; the other points take the sign change of the nearest
// decided point along the neighbour graph (breadth first): the propagated orientation was right
// locally, wrong by whole patches.
void propagate_sign_changes(Eigen::MatrixX3d& N, const Eigen::MatrixXi& K,
                            const std::vector<int>& which, int R, const std::vector<int>& s) {
  const Index n = N.rows();
  std::vector<int> change(size_t(n), 0);
  std::vector<Index> queue;
  for (Index i = 0; i < n; ++i)
    if (which[size_t(i)] < R) {
      change[size_t(i)] = s[size_t(which[size_t(i)])];
      queue.push_back(i);
    }
  for (size_t head = 0; head < queue.size(); ++head)
    for (Index c = 0; c < K.cols(); ++c) {
      const Index j = K(queue[head], c);
      if (change[size_t(j)] == 0) {
        change[size_t(j)] = change[size_t(queue[head])];
        queue.push_back(j);
      }
    }
  for (Index i = 0; i < n; ++i)
    if (change[size_t(i)] < 0)
      N.row(i) *= -1;
}

// The decided patches take their signs s; the other points (rims, thin walls' edges) are
// oriented again from all of them at once by Hoppe's propagation (orientation_tree.h), so that a
// point by a thin wall's edge follows its own side's patch along the sheet, not the sign change
// of a patch across the wall, and any sign the first propagation got wrong there is dropped.
void orient_from_patches(const Eigen::MatrixX3d& P, Eigen::MatrixX3d& N, const Eigen::MatrixXi& K,
                         const std::vector<int>& which, int R, const std::vector<int>& s) {
  std::vector<int> seeds;
  std::vector<char> done(size_t(P.rows()), 0);
  for (Index i = 0; i < P.rows(); ++i)
    if (which[size_t(i)] < R) {
      if (s[size_t(which[size_t(i)])] < 0)
        N.row(i) *= -1;
      seeds.push_back(int(i));
      done[size_t(i)] = 1;
    }
  detail::grow_orientation(P, N, detail::neighbour_graph(K), seeds, done);
}

} // namespace

Index orient_by_winding_number(const Eigen::MatrixX3d& P, Eigen::MatrixX3d& N, int k,
                               bool thin_walls) {
  const Index n = P.rows();
  if (n < 2 * detail::kAreaNeighbours)
    return 0;
  const Eigen::MatrixX3d N0 = N;
  const detail::NeighbourIndex index(P);
  const Eigen::MatrixXi K = index.knn_all(std::max(k, detail::kAreaNeighbours));
  const Eigen::VectorXd area = detail::point_areas(P, K.leftCols(detail::kAreaNeighbours));
  const double sigma = n > 24 ? estimate_noise(P) : 0;
  const std::vector<int> label = patches(P, N, K, sigma);
  const std::vector<int> roots = largest_patches(label);
  // patch index of each point: 0..R-1 decided, R the rest (oriented last)
  const int R = int(roots.size());
  std::vector<int> which(size_t(n), R);
  std::vector<std::vector<Index>> rows(size_t(R) + 1);
  for (Index i = 0; i < n; ++i) {
    const auto r = std::find(roots.begin(), roots.end(), label[size_t(i)]);
    which[size_t(i)] = int(r - roots.begin());
    rows[size_t(which[size_t(i)])].push_back(i);
  }
  auto offset = [&](Index i) { return kProbeSpacings * std::sqrt(area(i)) + kProbeSigmas * sigma; };
  // probes: up to kProbesPerPatch points of each decided patch, offset both ways
  std::vector<Index> probe_of;
  std::vector<int> probe_patch;
  for (int r = 0; r < R; ++r) {
    const size_t step = std::max<size_t>(1, rows[size_t(r)].size() / kProbesPerPatch);
    for (size_t t = 0; t < rows[size_t(r)].size(); t += step) {
      probe_of.push_back(rows[size_t(r)][t]);
      probe_patch.push_back(r);
    }
  }
  // each decided patch's field at every probe (the winding number is linear in the dipoles)
  std::vector<std::vector<double>> at_plus(static_cast<size_t>(R)),
      at_minus(static_cast<size_t>(R));
  for (int r = 0; r < R; ++r) {
    const auto& m = rows[size_t(r)];
    const detail::WindingNumber w(P(m, Eigen::all), N(m, Eigen::all), area(m));
    for (Index i : probe_of) {
      at_plus[size_t(r)].push_back(w(P.row(i).transpose() + offset(i) * N.row(i).transpose()));
      at_minus[size_t(r)].push_back(w(P.row(i).transpose() - offset(i) * N.row(i).transpose()));
    }
  }
  const std::vector<int> known = voted_signs(P, N, rows, detail::median_spacing(area));
  const std::vector<int> s = choose_signs(probe_patch, at_plus, at_minus, known);
  if (thin_walls)
    orient_from_patches(P, N, K, which, R, s);
  else
    propagate_sign_changes(N, K, which, R, s);
  if (detail::normals_inward(P, N, area)) // the global sign, by the divergence theorem
    N *= -1;
  const bool voted_flip = std::count(known.begin(), known.end(), -1) > 0; // positions decided
  if (!voted_flip && outside_winding(P, N, area, sigma) >= outside_winding(P, N0, area, sigma))
    N = N0; // no better than the propagated orientation by the whole cloud's measure
  if (thin_walls)
    orient_thin_wall_sides(P, N, index, area, which, R, sigma);
  return ((N.array() * N0.array()).rowwise().sum() < 0).count();
}

} // namespace interlin
