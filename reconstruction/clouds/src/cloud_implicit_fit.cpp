// Ohtake et al. 2003 (multi-level partition of unity implicits): the adaptive octree of local
// fits (cloud_implicit.h).
#include "interlin/reconstruction/clouds/cloud_implicit.h"

#include "exterior_side.h"
#include "local_fit.h"
#include "morton_key.h"
#include "nearest_neighbours.h"
#include "sheet_fits.h"
#include "winding_number.h"

#include "interlin/reconstruction/clouds/noise_level.h"
#include "interlin/reconstruction/clouds/smooth_scan_points.h"
#include "interlin/reconstruction/meshing/parallel_for.h"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

namespace interlin {

using Eigen::Index;
using Eigen::Vector3d;

namespace {

// A fit is accepted when its rms distance to the cell's points is at most kAcceptRms sigma and
// the largest at most kAcceptMax sigma: the misfit is then noise, not shape (4 sigma: Gaussian
// noise exceeds it at 6e-5 of the points).
constexpr double kAcceptRms = 1.5, kAcceptMax = 4.0;
// Floor of sigma relative to the root cube: noise-free input still stops refining at round-off.
constexpr double kSigmaFloor = 1e-6;
using detail::kSheetCos; // one sheet: (nearly) all normals within 60 degrees of their mean
constexpr double kStrayWeight = 0.05; // weight fraction of normals outside the cone tolerated
// Points of the cell's min_points nearest whose normal is within 60 degrees of the nearest
// point's normal form the plane of a far cell (not the wall opposite).

using detail::fit_edge_sheets;
using detail::fit_sheet;
using detail::fit_two_sheets;
using detail::may_hold_edge;
using detail::misfit;
using detail::split_by_normal;

struct Points : detail::OrientedPoints {
  const Eigen::VectorXd& area; // surface area per point (point_areas)
  const detail::WindingNumber& winding;
};

std::vector<double> weights(const std::vector<double>& d2, double R) {
  std::vector<double> w(d2.size());
  for (size_t j = 0; j < d2.size(); ++j)
    w[j] = detail::wendland(std::sqrt(d2[j]) / R);
  return w;
}

// One or two sheets through the points idx (weights w) of a cell whose ball has radius R; edges:
// a one-sheet cell may take edge sheets (fit_edge_sheets).
bool fit_cell(const Points& pts, const std::vector<int>& idx, const std::vector<double>& w,
              double R, bool edges, LocalFit& f) {
  Vector3d m = Vector3d::Zero();
  double sw = 0;
  for (size_t j = 0; j < idx.size(); ++j) {
    m += w[j] * pts.N.row(idx[j]).transpose();
    sw += w[j];
  }
  const Vector3d sum = m;
  double stray = 0;
  if (m.norm() > 0) {
    m.normalize();
    for (size_t j = 0; j < idx.size(); ++j)
      if (pts.N.row(idx[j]).dot(m) < kSheetCos)
        stray += w[j];
  }
  if (m.norm() > 0 && stray <= kStrayWeight * sw) {
    f.sheets = 1;
    if (!fit_sheet(pts, idx, w, R, true, f.sheet[0]))
      return false;
    if (edges && may_hold_edge(sum, sw))
      fit_edge_sheets(pts, idx, w, R, m, f);
    return true;
  }
  std::vector<size_t> a, b;
  split_by_normal(pts, idx, m, a, b);
  return a.size() >= 3 && b.size() >= 3 && fit_two_sheets(pts, idx, w, R, a, b, f);
}

// The plane through the point p0 = P[i0] normal to the direction u from p0 to the cell's centre
// c: |Q(c)| is the distance to the nearest point, Q keeps one sign over any ball about c that
// holds no point, and that sign is the side the winding number puts c on (inside: w > 1/2).
// For a smooth surface u is the normal at the foot p0: the tangent plane there.
void far_plane(const Points& pts, int i0, double w, LocalFit& f) {
  const Vector3d p0 = pts.P.row(i0).transpose();
  const Vector3d u = (f.centre - p0).normalized();
  const bool inside = w > 0.5;
  f.sheets = 1;
  f.sheet[0].origin = p0;
  f.sheet[0].frame =
      detail::tangent_frame(inside ? Vector3d(-u) : u); // Q = -n . (x - p0), n outward
  f.sheet[0].c = {};
}

// A cell with fewer than min_points points in its ball takes its min_points nearest points
// (weights over a ball reaching past the farthest). Near the surface (its support ball holds a
// point) they are fitted like any cell, or, when that fails, give the plane of those facing like
// the nearest point (Hoppe's signed distance to the nearest tangent plane). Far from the surface
// the tangent plane would extend thin walls past their edges (both sides' planes say "inside"
// there: the spurious sheets of run 1 in docs/benchmarks.md); a far cell takes instead the plane
// through the nearest point p0 normal to the direction u from p0 to the cell's centre: |Q| is the
// distance to the nearest point at the centre and Q keeps one sign over the ball, the sign of the
// side the winding number puts the centre on (inside when w > 1/2).
// A cell may also lie on the surface in a gap of the sampling: random sampling leaves holes wider
// than the support ball of a small cell, where the far plane, normal to a direction along the
// surface, dented the zero set by up to 4 point spacings. A cell whose nearest point is within
// kGapReach radii takes its parent's fit (parent: null unless that fit, from at least
// 4 min_points points over a ball that holds the cell's, misses them by at most kGapMisfit
// spacings rms: smooth there, not a fit across an edge or a thin wall's rim).
bool fit_sparse(const Points& pts, const detail::NeighbourIndex& index, int k, bool edges,
                const LocalFit* parent, LocalFit& f) {
  constexpr double kGapReach = 2;
  std::vector<int> idx;
  std::vector<double> d2;
  index.knn(f.centre, k, idx, d2);
  const double r2 = f.radius * f.radius;
  if (parent && d2.front() >= r2 && d2.front() < kGapReach * kGapReach * r2) {
    f.sheets = parent->sheets;
    f.conjunction = parent->conjunction;
    f.sheet = parent->sheet;
    return false;
  }
  f.sheets = 1;
  if (d2.front() < r2) { // the support ball holds a point
    const double R = 1.5 * std::sqrt(d2.back());
    if (fit_cell(pts, idx, weights(d2, R), R, edges, f))
      return false;
    const Vector3d n0 = pts.N.row(idx[0]).transpose();
    std::vector<int> keep;
    std::vector<double> kd2;
    for (size_t j = 0; j < idx.size(); ++j)
      if (pts.N.row(idx[j]).dot(n0) >= kSheetCos) {
        keep.push_back(idx[j]);
        kd2.push_back(d2[j]);
      }
    const double Rk = 1.5 * std::sqrt(kd2.back()) + 1e-300;
    f.sheets = 1;
    if (fit_sheet(pts, keep, weights(kd2, Rk), Rk, false, f.sheet[0]))
      return true;
  }
  far_plane(pts, idx[0], pts.winding(f.centre), f);
  return true;
}

// The points of an n x n x n lattice over f's cube [centre - radius, centre + radius]^3 that lie
// in its support ball, in lattice order.
std::vector<Vector3d> ball_lattice(const LocalFit& f, int n) {
  std::vector<Vector3d> X;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const Vector3d t = Vector3d(i, j, k) * (2.0 / (n - 1)) - Vector3d::Ones(); // [-1, 1]^3
        if (t.squaredNorm() <= 1)
          X.push_back(f.centre + f.radius * t);
      }
  return X;
}

// Whether Q changes sign in f's ball and has the sign opposite to a decisive winding number (within
// kDecisive of 0 or 1) at kWindingLeast or more lattice points of the ball (kWindingLattice^3
// in its cube); side: the winding number's side there (inside when w > 1/2).
constexpr int kWindingLeast = 2;
constexpr double kDecisive = 0.05;
bool contradicts_winding(const Points& pts, const LocalFit& f, double& side) {
  constexpr int kWindingLattice = 5;
  const std::vector<Vector3d> lattice = ball_lattice(f, kWindingLattice);
  std::vector<double> q;
  for (const Vector3d& x : lattice)
    q.push_back(detail::fit_value(f, x, nullptr));
  const auto [lo, hi] = std::minmax_element(q.begin(), q.end());
  if (*lo > 0 || *hi < 0)
    return false;
  int inside = 0, outside = 0; // decisive lattice points where Q has the other sign
  for (size_t l = 0; l < lattice.size(); ++l) {
    const double w = pts.winding(lattice[l]);
    inside += w > 1 - kDecisive && q[l] < 0;
    outside += w < kDecisive && q[l] > 0;
  }
  side = inside > outside ? 1.0 : 0.0;
  return std::max(inside, outside) >= kWindingLeast;
}

// Where x lies from its nearest point: `spaced` when `spacings` point spacings (the square root
// of that point's area) or more away, `behind` when within 60 degrees of its inward normal
// (inside its surface). The slab and pocket tests' gate before the costly winding number.
struct NearestSide {
  bool spaced, behind;
};
NearestSide nearest_side(const Points& pts, const detail::NeighbourIndex& index, const Vector3d& x,
                         double spacings) {
  std::vector<int> idx;
  std::vector<double> d2;
  index.knn(x, 1, idx, d2);
  const int p = idx[0];
  return {d2[0] >= spacings * spacings * pts.area(p),
          pts.N.row(p).dot(x - pts.P.row(p).transpose()) <= -0.5 * std::sqrt(d2[0])};
}

// Whether f's two sheets, joined by conjunction, make a slab that runs on past a thin wall's edge
// where no point lies: the slab's mid-surface, sampled on a kSlabGrid^2 grid over the first
// sheet's tangent disc of the ball (x0 on the first sheet, mid = x0 - n0 t / 2 with t the
// first-order distance to the second sheet), has Q > 0, lies at least kSlabSpacings point
// spacings from the points and has a decisive outside winding number at kWindingLeast samples
// or more. Such slabs are razor-thin (0.001 to 0.02 cm past the sigma 0.02 blade's edges, where
// the lattices of contradicts_winding and the flood fill miss them) and reach up to the ball's
// radius past the edge (0.44 cm). Measured on 18 blade and valve clouds (docs/benchmarks.md,
// "Slabs past thin edges on the winding number"): 13^2 samples at 1 spacing beat 9^2 at 1.5 or
// 2 by up to 1.5 %; 17^2 left a blob off a 30,000-point blade's hub corner.
bool slab_past_edge(const Points& pts, const detail::NeighbourIndex& index, const LocalFit& f) {
  constexpr int kSlabGrid = 13;
  constexpr double kSlabSpacings = 1;
  if (f.sheets != 2 || !f.conjunction)
    return false;
  const HeightSheet& s0 = f.sheet[0];
  const Vector3d l = s0.frame * (f.centre - s0.origin);
  int outside = 0;
  for (int i = 0; i < kSlabGrid; ++i)
    for (int j = 0; j < kSlabGrid; ++j) {
      const double a = 2.0 * i / (kSlabGrid - 1) - 1, b = 2.0 * j / (kSlabGrid - 1) - 1;
      if (a * a + b * b > 1)
        continue;
      const double u = l(0) + a * f.radius, v = l(1) + b * f.radius;
      const Vector3d x0 =
          s0.origin + s0.frame.transpose() * Vector3d(u, v, detail::sheet_height(s0, u, v));
      Vector3d g;
      const double q1 = detail::sheet_value(f.sheet[1], x0, &g);
      if (!(q1 > 0) || !(g.norm() > 0))
        continue;
      const Vector3d mid = x0 - s0.frame.row(2).transpose() * (0.5 * q1 / g.norm());
      if ((mid - f.centre).squaredNorm() > f.radius * f.radius ||
          !(detail::fit_value(f, mid, nullptr) > 0))
        continue;
      // behind the nearest point: between a thick part's faces, inside (the winding number
      // there costs most of the test's time and cannot say outside: 5 to 21 % of fit + mesh
      // time on the noisy blades and valve, the same Chamfer to 1 %); past an edge the nearest
      // point lies on the edge or on a face beside it
      if (const NearestSide n = nearest_side(pts, index, mid, kSlabSpacings); !n.spaced || n.behind)
        continue;
      outside += pts.winding(mid) < kDecisive;
      if (outside >= kWindingLeast)
        return true;
    }
  return false;
}

// Whether f's fit says outside where the points say inside: Q < 0 at kWindingLeast or more
// points of a kPocketLattice^3 lattice over its ball that lie a point spacing or more behind the
// nearest point (within 60 degrees of its inward normal) and have a decisive inside winding
// number. A wall's sheet carried past a concave edge into a thin wall leaves such pockets of
// F < 0 inside the solid (the noisy valve's slot walls below the slot floors, in the 0.2 cm wall
// above the flange's underside: vertices up to 50 sigma off); the slab test looks for the
// converse. Opt-in (CloudFitOptions::split_pockets): its nearest-point searches cost up to 30 %
// of fit and mesh time (docs/benchmarks.md, "Pockets in thin walls"); a 5^3 lattice as good as
// 7^3 at less time.
bool pocket_in_wall(const Points& pts, const detail::NeighbourIndex& index, const LocalFit& f) {
  constexpr int kPocketLattice = 5;
  int inside = 0;
  for (const Vector3d& x : ball_lattice(f, kPocketLattice)) {
    if (!(detail::fit_value(f, x, nullptr) < 0))
      continue;
    if (const NearestSide n = nearest_side(pts, index, x, 1); !n.spaced || !n.behind)
      continue;
    inside += pts.winding(x) > 1 - kDecisive;
    if (inside >= kWindingLeast)
      return true;
  }
  return false;
}

// A leaf whose centre lies at least kSignSpacings point spacings (sqrt of the nearest point's
// area) from the points, and whose Q there has the sign opposite to the winding number's side,
// takes the far plane: at that distance the winding number is reliable and the fit has curved
// back or extends a wall past its edge (a two-sheet slab beyond a blade's trailing edge).
// A leaf whose ball holds no point but whose Q changes sign in it has a zero set where no point
// lies: a surface across a gap of the sampling (a blade's missing patch) or a spurious sheet past
// a thin edge (a blob 0.5 cm off the blade's tip corner, which check_exterior catches where the
// flood fill is trusted; the fill leaks through the patch). Without a trusted fill (no_fill),
// where the winding number is decisive and Q contradicts it (contradicts_winding: w 0.00 at that
// blob, 0.14 between the blade's faces at the patch's centre), it takes the far plane on the
// winding number's side. Returns true when it did either.
bool check_sign(const Points& pts, const detail::NeighbourIndex& index, bool no_fill, LocalFit& f) {
  constexpr double kSignSpacings = 2;
  std::vector<int> idx;
  std::vector<double> d2;
  index.knn(f.centre, 1, idx, d2);
  double w = 0.5;
  if (d2[0] >= kSignSpacings * kSignSpacings * pts.area(idx[0])) {
    w = pts.winding(f.centre);
    if ((detail::fit_value(f, f.centre, nullptr) > 0) != (w > 0.5)) {
      far_plane(pts, idx[0], w, f);
      return true;
    }
  }
  if (!no_fill || d2[0] < f.radius * f.radius || !contradicts_winding(pts, f, w))
    return false;
  far_plane(pts, idx[0], w, f);
  return true;
}

// Q -> -Q: each sheet's normal and height negated, and the join swapped
// (-(Q1 and Q2) = (-Q1) or (-Q2)).
void negate(LocalFit& f) {
  for (int k = 0; k < f.sheets; ++k) {
    f.sheet[size_t(k)].frame.row(2) *= -1;
    for (double& c : f.sheet[size_t(k)].c)
      c = -c;
  }
  f.conjunction = !f.conjunction;
}

// The lattice points of f's support ball (kExteriorLattice^3 in its cube) that the flood fill
// labels, by side, and those where Q's sign agrees or disagrees with the label.
// measured 5, 7, 9, 11 lattice points per axis, at least 4, 8, 16 of them, shares 0.6 to 0.9
// on the blades, the UAV, the car and the impeller (docs/benchmarks.md): 9, 8, 0.9 best
constexpr int kExteriorLattice = 9, kExteriorLeast = 8;
constexpr double kExteriorShare = 0.9;
struct ExteriorVotes {
  int agree = 0, disagree = 0, inside = 0, outside = 0;
  // Q has the wrong sign at kExteriorLeast of the points or more, and at kExteriorShare of the
  // labelled ones (check_exterior negates it) or not (contradicts_exterior)
  bool some_wrong() const { return disagree >= kExteriorLeast; }
  bool mostly_wrong() const {
    return some_wrong() && disagree >= kExteriorShare * (agree + disagree);
  }
};

ExteriorVotes exterior_votes(const detail::ExteriorGrid& g, const LocalFit& f) {
  ExteriorVotes v;
  for (const Vector3d& x : ball_lattice(f, kExteriorLattice)) {
    const int side = detail::exterior_side(g, x);
    const double q = detail::fit_value(f, x, nullptr);
    (side < 0 ? v.inside : v.outside) += side != 0;
    if (side == 0 || q == 0)
      continue;
    ((q > 0) == (side < 0) ? v.agree : v.disagree)++;
  }
  return v;
}

// A leaf whose Q disagrees in sign with the flood fill's side (exterior_side.h) at kExteriorShare
// of the lattice points of its support ball that the fill labels (at least kExteriorLeast of
// kExteriorLattice^3) is negated: its normals were wrong where the winding number cannot tell,
// e.g. a thin edge's, and its wrong sign made a spurious sheet of F off the edge.
// A leaf whose ball holds no point (its nearest point beyond its radius) and whose labelled
// lattice points all lie on one side is off the surface: where Q has the other sign at
// kExteriorLeast of them, it takes the far plane on the fill's side. Its side came from the
// winding number alone (a far leaf) or its parent's fit reached over it (a gap leaf), and near a
// thin edge both can be wrong: a blob of F > 0 up to 0.77 cm off the blade's tip corner
// (docs/benchmarks.md, "Far leaves on the flood fill's side").
bool check_exterior(const Points& pts, const detail::NeighbourIndex& index,
                    const detail::ExteriorGrid& g, LocalFit& f) {
  const ExteriorVotes v = exterior_votes(g, f);
  if ((v.inside == 0 || v.outside == 0) && v.some_wrong()) {
    std::vector<int> idx;
    std::vector<double> d2;
    index.knn(f.centre, 1, idx, d2);
    if (d2[0] >= f.radius * f.radius) {
      far_plane(pts, idx[0], v.inside > 0 ? 1.0 : 0.0, f);
      return true;
    }
  }
  if (!v.mostly_wrong())
    return false;
  negate(f);
  return true;
}

// Whether a leaf's fit contradicts the flood fill in part of its ball (at kExteriorLeast lattice
// points, fewer than check_exterior's share): a thin wall's two sheets joined into a slab that
// runs on past the wall's edge, F > 0 up to 0.65 cm off a noisy blade's tip, where the leaf holds
// too few points to be split for its misfit (docs/benchmarks.md "Slabs past thin edges").
bool contradicts_exterior(const detail::ExteriorGrid& g, const LocalFit& f) {
  const ExteriorVotes v = exterior_votes(g, f);
  return v.some_wrong() && !v.mostly_wrong();
}

// What decides a cell: the points per fit and the acceptance thresholds (kAcceptRms sigma,
// kAcceptMax sigma, both times `acceptance`); gap_misfit: the largest rms misfit of a fit passed
// to its children in gaps of the sampling (fit_sparse).
struct Rule {
  bool split_slabs = false;   // a noisy scan's slabs past thin edges are split (split_on_winding)
  bool split_pockets = false; // pockets of F < 0 in thin walls are split (split_on_winding)
  bool edge_sheets = false;   // one-sheet cells may take edge sheets (fit_edge_sheets)
  int min_points = 20;
  double sigma = 0, acceptance = 1, gap_misfit = 0;
};

// Noise-aware neighbourhood (CloudFitOptions::noise_aware): a local fit's offset error from k
// points with noise sigma is at least 0.8 sigma / sqrt(k) (Cramer-Rao for a plane's offset, mean
// absolute value), so an error e = 0.037 spacing needs k = (0.8 / 0.037)^2 rho^2 = 460 rho^2.
constexpr double kCramerRaoPoints = 460;
// acceptance_per_rho: larger thresholds let the octree stop at cells with more points; beyond 2
// they accept the misfit of wrong normals at thin edges (docs/benchmarks.md, session 9).
constexpr double kAcceptanceCap = 2;

// min_points 0 (automatic): kCleanPoints per fit on a clean cloud (rho below kCleanScanNoise:
// sampled from a model or a mesh; noise_level.h), whose leaves stop only at min_points (no fit is
// rejected as noise): smaller patches follow curvature and sharp edges (docs/benchmarks.md, session
// 12: tori, ellipsoids, cylinders -12 to -34 %, the bench's models up to -50 %); kNoisyPoints
// otherwise, where 10 points let the noise through (a torus at rho 0.005 +21 %, holes in 0.02-thick
// noisy walls).
constexpr int kCleanPoints = 10, kNoisyPoints = 20;

Rule fit_rule(const CloudFitOptions& o, double sigma, double rho, Eigen::Index points) {
  Rule r;
  r.sigma = sigma;
  r.min_points = o.min_points > 0        ? o.min_points
                 : rho < kCleanScanNoise ? kCleanPoints
                                         : kNoisyPoints;
  if (o.noise_aware) {
    const double k = std::ceil(kCramerRaoPoints * rho * rho);
    r.min_points = static_cast<int>(std::min<double>(std::max<double>(r.min_points, k), points));
  }
  r.acceptance = std::min(kAcceptanceCap, 1 + o.acceptance_per_rho * rho);
  return r;
}

// A parent's fit is passed to cells in gaps (fit_sparse) when its rms misfit is at most this many
// point spacings (0.01 left the gaps of spheres; fits across the valve's edges miss by more).
constexpr double kGapMisfit = 0.05;

struct Cell {
  int level = 0;
  Eigen::Array3i ijk = Eigen::Array3i::Zero();
  int child = -1, parent = -1; // first of 8 children; the cell split into this one
  LocalFit fit;
  // smooth: its fit, from its own points, misses them by at most rule.gap_misfit rms (passed to
  // its children in gaps of the sampling); dense: its fit ball holds enough of the sample to be
  // split on it (split_on_sample), which a child's ball, inside its parent's, can only if the
  // parent's did; sampled: it was split on the sample
  // exterior_split: split where its fit contradicted the flood fill (contradicts_exterior)
  bool far = false, split = false, smooth = false, dense = false, sampled = false,
       exterior_split = false, slab_split = false, pocket_split = false;
};

// A ball of half the radius holds about a quarter of a surface's points: children get
// min_points each only when the cell has kSplitShare times as many.
constexpr int kSplitShare = 4;

// Coarse cells hold much of the cloud in their ball and are split on every cloud that is not a
// plane (their fits took half the fit time of a 100,000-point model cloud, most of it at levels
// that no leaf reaches). Such a cell is split on the evidence of every kSampleStride-th point
// alone when at least kSamplePoints of them lie in its ball and their fit misses them by more
// than kSampleMargin times the largest rms a fit may have to be accepted or passed on to gaps
// (Rule): the fit from all the points would miss them by more than that too. A split cell's fit
// is never evaluated (only leaves are; only smooth parents pass theirs on), so the model is the
// one the full fits give; any other cell is fitted from all its points.
constexpr int kSampleStride = 16, kSamplePoints = 256;
constexpr double kSampleMargin = 4;

// Whether cell c (its fit's centre set; fit ball R) is split on the sample (the rows 0,
// kSampleStride, 2 kSampleStride, ... of the points, indexed alone); if so its fit and flags are
// set.
bool split_on_sample(Cell& c, const detail::NeighbourIndex& sample, const Points& pts, double R,
                     const Rule& rule, int max_depth) {
  if (c.level >= max_depth)
    return false;
  std::vector<int> idx;
  std::vector<double> d2;
  sample.radius(c.fit.centre, R, idx, d2);
  // the sample's points are some of the cell's: the split's point count is met
  c.dense = int(idx.size()) >= std::max(kSamplePoints, kSplitShare * rule.min_points);
  if (!c.dense)
    return false;
  for (int& i : idx)
    i *= kSampleStride;
  LocalFit f = c.fit;
  double rms = 0, mx = 0;
  if (!fit_cell(pts, idx, weights(d2, R), R, rule.edge_sheets, f))
    return false;
  misfit(f, pts, idx, rms, mx);
  const double sigma = rule.acceptance * rule.sigma;
  if (!(rms > kSampleMargin * std::max(kAcceptRms * sigma, rule.gap_misfit)))
    return false;
  c.fit = f;
  c.split = c.sampled = true;
  c.smooth = false;
  return true;
}

// Splits cell c (its fit set, not far: far planes lie off the surface) where its fit contradicts
// the flood fill (exterior: the trusted fill, else null); a split cell's fit is not passed on to
// gaps either.
void split_on_exterior(Cell& c, const detail::ExteriorGrid* exterior, int max_depth) {
  if (c.far || !exterior || c.level >= max_depth || !contradicts_exterior(*exterior, c.fit))
    return;
  c.split = c.exterior_split = true;
  c.smooth = false;
}

// Splits cell c (its fit set, not far, not split already) where its fit contradicts the winding
// number away from the points: on a noisy scan where its two sheets make a slab past a thin
// wall's edge (slab_past_edge), on any scan (opt-in) where it leaves a pocket of F < 0 in a
// thin wall (pocket_in_wall). The children's smaller balls hold the slab or the wall's sheet to a
// smaller reach, and those without a point take the far plane.
void split_on_winding(Cell& c, const Points& pts, const detail::NeighbourIndex& index,
                      const Rule& rule, int max_depth) {
  if (c.far || c.split || c.level >= max_depth)
    return;
  if (rule.split_slabs && slab_past_edge(pts, index, c.fit))
    c.slab_split = true;
  else if (rule.split_pockets && pocket_in_wall(pts, index, c.fit))
    c.pocket_split = true;
  else
    return;
  c.split = true;
  c.smooth = false;
}

// Fits cell c (parent: the fit of the cell it came from, null if none or not smooth); decides
// whether it is split: for its misfit, or (exterior: the trusted flood fill, else null) where its
// fit contradicts the fill.
void process(Cell& c, const LocalFit* parent, const Points& pts,
             const detail::NeighbourIndex& index, const detail::NeighbourIndex* sample,
             const detail::ExteriorGrid* exterior, const CloudFitOptions& o, const Vector3d& origin,
             double root, const Rule& rule) {
  const double side = root / double(1 << c.level);
  LocalFit& f = c.fit;
  f.level = c.level;
  f.cell = c.ijk;
  f.centre = origin + side * (c.ijk.cast<double>() + 0.5).matrix();
  f.radius = o.support * side * std::sqrt(3.0);
  const double R = o.fit_ball * side * std::sqrt(3.0);
  if (sample && split_on_sample(c, *sample, pts, R, rule, o.max_depth))
    return;
  std::vector<int> idx;
  std::vector<double> d2;
  index.radius(f.centre, R, idx, d2);
  if (int(idx.size()) < rule.min_points) {
    c.far = fit_sparse(pts, index, rule.min_points, rule.edge_sheets, parent, f);
    split_on_exterior(c, exterior, o.max_depth);
    split_on_winding(c, pts, index, rule, o.max_depth);
    return;
  }
  const bool ok = fit_cell(pts, idx, weights(d2, R), R, rule.edge_sheets, f);
  double rms = 0, mx = 0;
  if (ok)
    misfit(f, pts, idx, rms, mx);
  c.smooth = ok && rms <= rule.gap_misfit;
  const double sigma = rule.acceptance * rule.sigma;
  const bool accepted = ok && rms <= kAcceptRms * sigma && mx <= kAcceptMax * sigma;
  c.split = !accepted && c.level < o.max_depth && int(idx.size()) >= kSplitShare * rule.min_points;
  if (!ok && !c.split) // no usable fit and no refinement left: the nearest points' fit
    c.far = fit_sparse(pts, index, rule.min_points, rule.edge_sheets, parent, f);
  if (!c.split)
    split_on_exterior(c, exterior, o.max_depth);
  split_on_winding(c, pts, index, rule, o.max_depth);
}

// Z-order (Morton) key of a leaf's cell at the resolution of level `depth` (<= 21): leaves sorted
// by it lie near their neighbours in memory, which the evaluator's loops over nearby balls like.
std::uint64_t morton(const LocalFit& f, int depth) {
  const int shift = depth - f.level;
  return detail::morton_key({std::uint64_t(f.cell(0)) << shift, std::uint64_t(f.cell(1)) << shift,
                             std::uint64_t(f.cell(2)) << shift},
                            depth);
}

// The flood fill's grid (exterior_side.h) at kVoxelSpacings point spacings, trusted when the
// winding number agrees with its side at kTrustShare of at most kTrustProbes free voxels next to
// the shell (a hole the shell does not close lets the fill into the inside: 54 to 72 % agreement
// on the valve and the blade with a missing patch, 99.9 to 100 % on the closed scans); empty when
// not trusted.
std::optional<detail::ExteriorGrid> trusted_exterior(const Points& pts, double spacing,
                                                     int threads) {
  constexpr long kTrustProbes = 2000;
  constexpr double kTrustShare = 0.97;
  detail::ExteriorGrid grid = detail::exterior_grid(pts.P, detail::kVoxelSpacings * spacing);
  // pockets the shell closes (an impeller's passages) are outside when the winding number says so
  detail::open_pockets(
      grid, [&](const Vector3d& x) { return pts.winding(x); }, threads);
  const detail::ExteriorSamples probe = detail::shell_neighbours(grid, kTrustProbes);
  long agree = 0;
  for (Index i = 0; i < probe.X.rows(); ++i)
    agree += (pts.winding(probe.X.row(i).transpose()) > 0.5) == (probe.side[size_t(i)] < 0);
  if (probe.X.rows() == 0 || double(agree) < kTrustShare * double(probe.X.rows()))
    return std::nullopt;
  return grid;
}

// check_exterior on every leaf. Returns the leaves negated.
long negate_by_exterior(const Points& pts, const detail::NeighbourIndex& index,
                        const detail::ExteriorGrid& grid, int threads, std::vector<Cell>& cells,
                        const std::vector<size_t>& leaves) {
  std::vector<char> negated(leaves.size(), 0);
  detail::parallel_for(long(leaves.size()), detail::resolve_threads(threads), [&](long t, int) {
    negated[size_t(t)] = check_exterior(pts, index, grid, cells[leaves[size_t(t)]].fit);
  });
  return long(std::count(negated.begin(), negated.end(), 1));
}

// The octree of local fits to the cloud c (its normals oriented), scan_noise its sigma_n (given
// or estimate_scan_noise); info's fields up to acceptance.
CloudImplicit fit_octree(const PointCloud& c, const CloudFitOptions& o, double scan_noise,
                         CloudFitInfo& info) {
  const detail::NeighbourIndex index(c.points);
  const Eigen::VectorXd area =
      detail::point_areas(c.points, index.knn_all(detail::kAreaNeighbours, o.threads));
  info.flipped = detail::normals_inward(c.points, c.normals, area); // flipped before fitting
  const Eigen::MatrixX3d N = info.flipped ? Eigen::MatrixX3d(-c.normals) : c.normals;
  const detail::WindingNumber winding(c.points, N, area);
  const Points pts{{c.points, N}, area, winding};
  const Vector3d lo = c.points.colwise().minCoeff(), hi = c.points.colwise().maxCoeff();
  const double diag = (hi - lo).norm();
  CloudImplicit m;
  m.support = o.support;
  // kBoxMargin: the function's box reaches this fraction of the diagonal beyond the points, room
  // for the surface between and around the outermost points
  constexpr double kBoxMargin = 0.05;
  m.box = Eigen::AlignedBox3d(lo.array() - kBoxMargin * diag, hi.array() + kBoxMargin * diag);
  m.size = 1.25 * (hi - lo).maxCoeff() + 2 * kBoxMargin * diag;
  m.origin = 0.5 * (lo + hi) - Vector3d::Constant(0.5 * m.size);
  info.noise_estimated = !(o.noise > 0);
  info.noise = o.noise > 0 ? o.noise : estimate_noise(c.points);
  info.spacing = detail::median_spacing(area);
  m.spacing = info.spacing;
  info.scan_noise = scan_noise;
  const double sigma = std::max(info.noise, kSigmaFloor * m.size);
  // On a clean cloud estimate_noise's residual is shape, not noise (the impeller's 0.4-thick
  // blades, 2 spacings, in most quadrics' 24 points: 0.28 spacings): its fits are accepted by
  // the scan noise (docs/benchmarks.md "The impeller: clean clouds' fits held to the scan noise").
  const bool clean_scan = info.scan_noise < kCleanScanNoise * info.spacing;
  const bool clean = info.noise_estimated && clean_scan;
  const double fit_sigma = clean ? std::max(info.scan_noise, kSigmaFloor * m.size) : sigma;
  Rule rule = fit_rule(o, fit_sigma, info.scan_noise / info.spacing, c.points.rows());
  rule.gap_misfit = kGapMisfit * info.spacing;
  rule.split_slabs = o.split_slabs && !clean_scan;
  rule.split_pockets = o.split_pockets;
  rule.edge_sheets = o.edge_sheets;
  info.min_points = rule.min_points;
  info.acceptance = rule.acceptance;

  std::unique_ptr<const detail::NeighbourIndex> sample;
  if (o.sample_coarse && c.points.rows() >= Index(kSampleStride) * kSamplePoints)
    sample = std::make_unique<const detail::NeighbourIndex>(
        c.points(Eigen::seq(0, Eigen::last, kSampleStride), Eigen::all));
  const std::optional<detail::ExteriorGrid> exterior =
      o.exterior_side ? trusted_exterior(pts, info.spacing, o.threads) : std::nullopt;
  // Noisy scans' leaves are held large by the noise (Rule), and a thin wall's slab then runs on
  // past its edge; a clean cloud's small leaves do not (the impeller: +1.3 % with the split).
  const detail::ExteriorGrid* split_by = exterior && !clean_scan ? &*exterior : nullptr;
  std::vector<Cell> cells(1);
  size_t begin = 0;
  for (int level = 0; begin < cells.size(); ++level) {
    const size_t end = cells.size();
    detail::parallel_for(
        static_cast<long>(end - begin), detail::resolve_threads(o.threads), [&](long t, int) {
          Cell& c = cells[begin + static_cast<size_t>(t)];
          const Cell* p = c.parent >= 0 ? &cells[size_t(c.parent)] : nullptr;
          process(c, p && p->smooth ? &p->fit : nullptr, pts, index,
                  !p || p->dense ? sample.get() : nullptr, split_by, o, m.origin, m.size, rule);
        });
    for (size_t i = begin; i < end; ++i) {
      if (!cells[i].split)
        continue;
      cells[i].child = static_cast<int>(cells.size());
      for (int oc = 0; oc < 8; ++oc) {
        Cell ch;
        ch.level = level + 1;
        ch.parent = static_cast<int>(i);
        ch.ijk = 2 * cells[i].ijk + Eigen::Array3i(oc & 1, (oc >> 1) & 1, (oc >> 2) & 1);
        cells.push_back(ch);
      }
    }
    info.depth = level;
    if (o.progress)
      o.progress("octree level " + std::to_string(level) + ": " + std::to_string(end - begin) +
                 " cells");
    begin = end;
  }
  std::vector<size_t> leaves;
  for (size_t i = 0; i < cells.size(); ++i)
    if (cells[i].child < 0 && !cells[i].far)
      leaves.push_back(i);
  std::vector<char> fixed(leaves.size(), 0);
  detail::parallel_for(
      static_cast<long>(leaves.size()), detail::resolve_threads(o.threads), [&](long t, int) {
        fixed[size_t(t)] = check_sign(pts, index, !exterior, cells[leaves[size_t(t)]].fit);
      });
  info.sign_fixed_leaves = std::count(fixed.begin(), fixed.end(), 1);
  if (exterior) { // far leaves too: their sides came from the winding number alone
    std::vector<size_t> all;
    for (size_t i = 0; i < cells.size(); ++i)
      if (cells[i].child < 0)
        all.push_back(i);
    info.exterior_negated_leaves = negate_by_exterior(pts, index, *exterior, o.threads, cells, all);
  }
  for (const Cell& cell : cells)
    if (cell.child < 0) {
      m.fits.push_back(cell.fit);
      info.two_sheet_leaves += cell.fit.sheets == 2;
      info.far_leaves += cell.far;
    }
  {
    std::vector<std::pair<std::uint64_t, size_t>> order(m.fits.size());
    for (size_t i = 0; i < order.size(); ++i)
      order[i] = {morton(m.fits[i], info.depth), i};
    std::sort(order.begin(), order.end());
    std::vector<LocalFit> sorted;
    sorted.reserve(order.size());
    for (const auto& [key, i] : order)
      sorted.push_back(m.fits[i]);
    m.fits = std::move(sorted);
  }
  info.cells = static_cast<long>(cells.size());
  info.exterior_split_cells =
      std::count_if(cells.begin(), cells.end(), [](const Cell& c) { return c.exterior_split; });
  info.slab_split_cells =
      std::count_if(cells.begin(), cells.end(), [](const Cell& c) { return c.slab_split; });
  info.pocket_split_cells =
      std::count_if(cells.begin(), cells.end(), [](const Cell& c) { return c.pocket_split; });
  info.sampled_splits =
      std::count_if(cells.begin(), cells.end(), [](const Cell& c) { return c.sampled; });
  info.leaves = static_cast<long>(m.fits.size());
  return m;
}

// A noisy scan's points moved onto their local quadrics (smooth_scan_points) when
// o.smooth_points holds and the scan noise sigma (given, or estimate_scan_noise) is at least
// kCleanScanNoise point spacings; false (out untouched) otherwise. Each point's quadric averages
// up to kSmoothingPoints neighbours, as many as the shape allows; the octree then keeps the
// leaves the scan's noise asks for (fit_cloud_implicit), and its fits average the smoothed
// points (docs/benchmarks.md "Noisy scans smoothed point by point").
bool smooth_noisy_scan(const PointCloud& c, const CloudFitOptions& o, double sigma, PointCloud& out,
                       CloudFitInfo& info) {
  // At most kSmoothingPoints neighbours and a kSmoothingShare-th of the cloud: on small noisy
  // clouds (3,000 points) 512 neighbours cover a sixth of a torus or a thin ellipsoid, where the
  // rungs' test has too little power against their noise (bench/cloud_smoothing_family.py: +13
  // to +112 % there).
  constexpr int kSmoothingPoints = 512, kSmoothingShare = 32;
  // Lepski's threshold, measured on the bench's noisy clouds at 100,000 points: 1.5 beats 3 by
  // 3 to 10 % on the blades and the noisy valve and by up to 25 % on a thin ellipsoid; 1 stops the
  // rungs early on the sigma 0.02 blade (+43 %).
  constexpr double kLepskiKappa = 1.5;
  constexpr Index kLeastPoints = 25; // estimate_scan_noise's least
  if (!o.smooth_points || c.points.rows() < kLeastPoints)
    return false;
  if (sigma < kCleanScanNoise * median_point_spacing(c.points))
    return false;
  const int k_max = int(std::clamp<Index>(c.points.rows() / kSmoothingShare, 16, kSmoothingPoints));
  SmoothedPoints s =
      smooth_scan_points(c.points, c.normals, sigma, k_max, kLepskiKappa, o.edge_sheets, o.threads);
  out.points = std::move(s.P);
  out.normals = std::move(s.N);
  std::vector<int> k(s.k.begin(), s.k.end());
  std::nth_element(k.begin(), k.begin() + Index(k.size() / 2), k.end());
  info.smoothing_noise = sigma;
  info.smoothing_neighbours = k[k.size() / 2];
  info.smoothed_points = long((s.k.array() > 0).count());
  info.smoothed_on_edges = s.on_edges;
  return true;
}

} // namespace

CloudImplicit fit_cloud_implicit(const PointCloud& c, const CloudFitOptions& o,
                                 CloudFitInfo* info_out) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!c.has_normals())
    throw std::invalid_argument("cloud implicit: the cloud needs oriented normals");
  if ((o.min_points != 0 && o.min_points < 3) || o.max_depth < 1 || o.max_depth > 20 ||
      !(o.support > 0.5) || !(o.fit_ball > 0) || !(o.noise >= 0) || !(o.acceptance_per_rho >= 0))
    throw std::invalid_argument("cloud implicit: bad options");
  const int least = o.min_points > 0 ? o.min_points : kNoisyPoints;
  if (c.points.rows() < least)
    throw std::invalid_argument("cloud implicit: need at least " + std::to_string(least) +
                                " points");
  CloudFitInfo info;
  // sigma_n once, for the smoothing's gate and the octree's rule
  const double scan_noise = o.noise > 0 ? o.noise : estimate_scan_noise(c.points);
  PointCloud smoothed;
  const bool smooth = smooth_noisy_scan(c, o, scan_noise, smoothed, info);
  CloudFitOptions fo = o;
  if (smooth) // the octree the scan's noise asks for, its leaves fitted to the smoothed points
    fo.noise = info.smoothing_noise;
  CloudImplicit m = fit_octree(smooth ? smoothed : c, fo, scan_noise, info);
  // A smoothed scan's points lie on quadrics of 16 to k_max neighbours: F shows no detail finer
  // than about twice the point spacing, and a mesh cell of the spacing loses 0 to 2.5 % of the
  // Chamfer to one of half of it at 30 to 45 % less time (docs/benchmarks.md, "The mesh cell of
  // smoothed scans").
  constexpr double kSmoothedSpacings = 2;
  if (smooth)
    m.spacing = kSmoothedSpacings * info.spacing;
  info.noise_estimated = !(o.noise > 0);
  // How far the zero set passes from the input points (first-order distance |F| / |grad F|).
  const double sigma = smooth ? info.smoothing_noise : std::max(info.noise, kSigmaFloor * m.size);
  const ImplicitFunction F = cloud_implicit_function(std::make_shared<const CloudImplicit>(m));
  Eigen::VectorXd v(c.points.rows());
  Points3 G(c.points.rows(), 3);
  F.gradient(c.points, v, G);
  const Eigen::ArrayXd d = v.array().abs() / G.rowwise().norm().array().max(1e-12);
  info.rms_distance = std::sqrt(d.square().mean());
  info.max_distance = d.maxCoeff();
  info.within_3_sigma = double((d <= 3 * sigma).count()) / double(d.size());
  info.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (info_out)
    *info_out = info;
  return m;
}

} // namespace interlin
