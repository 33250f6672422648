#pragma once
// Unstructured scans -> implicit function: a multi-level partition of unity of local surface
// fits on an adaptive octree (Ohtake, Belyaev, Alexa, Turk, Seidel, "Multi-level partition of
// unity implicits", ACM Trans. Graph. 22(3), SIGGRAPH 2003; docs/formulas.md "Point clouds").
//
//   F(x) = sum_i w_i(x) Q_i(x) / sum_i w_i(x),   w_i(x) = psi(|x - c_i| / R_i),
//   psi(r) = (1 - r)^4 (4 r + 1) on [0, 1) (Wendland's C2 function), R_i = support x the cell's
//   diagonal,
//
// over the leaves i of an octree: each leaf cell (centre c_i) holds a local function Q_i fitted
// by weighted least squares to the points in its ball, and a cell is split while its fit misses
// the points by more than the noise. F > 0 inside, F = 0 on the surface, F < 0 outside; F is C2
// where the Q_i are, and Q ~ signed distance near the surface (|grad Q| ~ 1).
// Local functions (Q > 0 below the sheet, i.e. inside):
//   one sheet   Q = h(u, v) - w, (u, v, w) the point in a frame whose w axis is the mean
//               outward normal, h a quadratic (a plane for cells far from the points);
//   two sheets  Q = Q1 and Q2 joined by Rvachev's R-conjunction Q1 + Q2 - sqrt(Q1^2 + Q2^2)
//               (thin walls, convex edges) or R-disjunction Q1 + Q2 + sqrt(Q1^2 + Q2^2)
//               (concave edges): the normals of the cell's points fall into two groups, e.g.
//               both sides of a blade near its leading edge (MPU's sharp-feature functions,
//               with R-functions in place of max/min so F stays smooth off the edge).

#include "interlin/interflatation/implicit_function.h"
#include "interlin/reconstruction/clouds/point_cloud.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace interlin {

// Q(x) = h(u, v) - w with (u, v, w) = frame * (x - origin),
// h(u, v) = c[0] u^2 + c[1] u v + c[2] v^2 + c[3] u + c[4] v + c[5].
//   frame  rows: two tangents and the outward normal (orthonormal)
struct HeightSheet {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
  std::array<double, 6> c{};
};

// The local function of one octree leaf.
//   centre, radius  the partition-of-unity support ball
//   level, cell     the leaf's octree address: level L, integer cell (i, j, k) in [0, 2^L)^3
//   sheets          1 or 2; conjunction: how two sheets join (else disjunction)
struct LocalFit {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0;
  int level = 0;
  Eigen::Array3i cell = Eigen::Array3i::Zero();
  int sheets = 1;
  bool conjunction = true;
  std::array<HeightSheet, 2> sheet{};
};

// The fitted model: what an .ifl file stores. Evaluate through cloud_implicit_function.
//   origin, size  the octree's root cube [origin, origin + size]^3
//   box           the region of interest (the points' box with a margin): the function's box
//   support       PU radius / cell diagonal used for every leaf (Ohtake et al.'s alpha); each
//                 fit's radius is support x its cell's diagonal
//   fits          the octree leaves; together they tile the root cube
//   spacing       the finest detail F resolves, which sets the default mesh cell (half of it:
//                 default_mesh_cell): the median point spacing of the fitted cloud, twice it
//                 when its points were smoothed (info.smoothed_points); 0: unknown (older files)
struct CloudImplicit {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double size = 1;
  Eigen::AlignedBox3d box;
  double support = 0.6;
  std::vector<LocalFit> fits;
  double spacing = 0;
};

struct CloudFitOptions {
  double noise = 0; // sigma of the noise normal to the surface; 0: estimate_noise
  // Points per local fit (a cell with fewer grows its ball). 0 (automatic): 10 on a clean cloud
  // (scan noise below 0.002 point spacings: sampled from a model or a mesh), else 20.
  int min_points = 0;
  int max_depth = 12; // octree levels below the root cube
  // Radii per cell diagonal: the partition-of-unity support ball (> 0.5 so that the balls cover
  // the cells; 0.6: about 5 balls overlap at a point, half of Ohtake et al.'s 0.75, which doubles
  // the evaluation speed for 5 to 20 % larger errors on noisy tori) and the ball whose points a
  // cell's fit uses (Ohtake et al.'s 0.75).
  double support = 0.6, fit_ball = 0.75;
  // Noise-aware neighbourhood (docs/formulas.md "Point clouds"): with rho = sigma_n / spacing
  // (sigma_n: estimate_scan_noise, or the given noise; spacing: the median point spacing), every
  // fit averages at least 460 rho^2 points, the Cramer-Rao count (0.8 sigma_n / e)^2 for an
  // offset error e = 0.037 spacing. No change for rho < 0.21 (460 rho^2 < 20), e.g. noise-free
  // models (rho ~ 0).
  bool noise_aware = true;
  // Opt-in: both acceptance thresholds times min(2, 1 + acceptance_per_rho x rho) (8: blades
  // -9 to -41 %, but a thin ellipsoid at sigma = 0.09 spacing +14 %; docs/benchmarks.md).
  double acceptance_per_rho = 0;
  // Coarse cells split on every 16th point when that settles it (fit_cloud_implicit): the same
  // model; on 100,000 points the fit takes 6 to 24 % less time, fit + mesh 8 to 17 %; false fits
  // every cell from all its points.
  bool sample_coarse = true;
  // After fitting, leaves whose sign contradicts the flood fill's inside and outside are negated
  // (fit_cloud_implicit; info.exterior_negated_leaves), and on noisy scans cells whose fit
  // contradicts it in part are split (info.exterior_split_cells). False: the fits as they come.
  bool exterior_side = true;
  // On noisy scans, a cell whose two sheets make a slab past a thin wall's edge (its mid-surface
  // a point spacing or more from the points where the winding number says outside) is split
  // (info.slab_split_cells). False: such slabs stay (up to a leaf's radius past the edge).
  bool split_slabs = true;
  // A cell whose fit says outside (Q < 0) a point spacing or more behind the nearest point, where
  // the winding number says inside (above 0.95), at 2 or more points of a 5^3 lattice over its
  // ball is split (info.pocket_split_cells): a wall's sheet carried past a concave edge into a
  // thin wall leaves pockets of F < 0 inside the solid (the clean valve -6 %, the UAV -6 %, the
  // impeller -4 % Chamfer; docs/benchmarks.md "Pockets in thin walls"). Off by default: its
  // nearest-point searches cost up to 30 % of fit and mesh time. False: such pockets stay.
  bool split_pockets = false;
  // Noisy scans (scan noise, given or estimate_scan_noise, at least kCleanScanNoise spacings):
  // the points are first moved onto local quadrics of up to 512 neighbours, each point's number
  // chosen by Lepski's method (smooth_scan_points); the octree, its leaves accepted and sized by
  // the scan noise as without smoothing, fits the moved points. False: the points as they come.
  bool smooth_points = true;
  // Edge sheets (Ohtake et al. 2003): a cell whose quadric would round a sharp edge (its normals
  // in two groups 20 degrees or more apart, each with a tenth of the weight) takes the R-function
  // join of the groups' sheets when that misses its points by at most 0.9 times the quadric's rms;
  // a noisy scan's smoothing moves such points onto the join likewise (smooth_scan_points).
  // False: one quadric wherever the normals lie within 60 degrees of their mean, in both.
  bool edge_sheets = true;
  int threads = 0; // 0: all cores
  // Progress lines (one per octree level); called from the calling thread.
  std::function<void(const std::string&)> progress;
};

struct CloudFitInfo {
  double noise = 0;            // sigma used
  bool noise_estimated = true; // ... estimated from the points (else given)
  long cells = 0, leaves = 0, two_sheet_leaves = 0, far_leaves = 0;
  long sign_fixed_leaves = 0;       // leaves whose fit had the wrong side: given the far plane
  long exterior_negated_leaves = 0; // leaves negated to the flood fill's side (exterior_side)
  long exterior_split_cells = 0;    // cells split where their fit contradicted the flood fill
  long slab_split_cells = 0;        // cells split where their slab ran past a thin edge
  long pocket_split_cells = 0;      // cells split where their fit left a pocket in a thin wall
  long sampled_splits = 0;          // cells split on every 16th point alone (their fit far off)
  int depth = 0;                    // deepest level reached
  double rms_distance = 0;          // over the input points: |F| / |grad F| (first-order distance)
  double max_distance = 0;          // ... its maximum
  double within_3_sigma = 0;        // fraction of points with |F| / |grad F| <= 3 sigma
  bool flipped = false;             // the normals pointed inward and were flipped
  double seconds = 0;
  double spacing = 0;    // median point spacing (sqrt of the area per point)
  double scan_noise = 0; // sigma_n (estimate_scan_noise or the given noise); on a clean cloud
                         // (below 0.002 spacings) also the fits' acceptance sigma
  int min_points = 0;    // points per fit used
  double acceptance = 1; // multiple of the acceptance thresholds used
  // smooth_points: the points moved (0: not smoothed), the scan noise of the input that the
  // smoothing used (then also noise and scan_noise: the octree's sigma), the median number of
  // neighbours chosen, the points moved onto edge sheets. rms_distance .. within_3_sigma are
  // measured at the input points.
  long smoothed_points = 0, smoothed_on_edges = 0;
  double smoothing_noise = 0;
  int smoothing_neighbours = 0;
};

// Fits the implicit function to a cloud with consistently oriented normals (orient_normals).
// A noisy scan's points are first moved onto local quadrics (smooth_points, smooth_scan_points.h)
// and the octree below fits the moved points with the scan noise's thresholds.
// A cell of side s has the support ball R = support * s * sqrt(3) around its centre; the points
// in the ball of radius fit_ball * s * sqrt(3) (weights psi(|p - c| / that radius)) are fitted
// by one or two sheets; the cell is a leaf when the fit's
// rms distance to its points is at most 1.5 sigma and the largest at most 4 sigma (both floored
// at 1e-6 of the root cube), when its children would hold fewer than min_points points each
// (it holds fewer than 4 min_points: a ball of half the radius holds about a quarter of a
// surface's points; min_points automatic or given, raised by noise_aware on noisy scans), or at
// max_depth. A cell whose fit ball holds at least 256 of every 16th point is split on them alone
// when their fit misses them by more than 4 times the acceptance rms and the gap rule's 0.05
// spacings (info.sampled_splits): the full fit would be rejected too, and a split cell's fit is
// not part of the function. A cell with fewer than min_points points in its fit ball takes its
// min_points nearest points: fitted like any cell when its support ball holds one of them; in a gap
// of the sampling (no point in the support ball, one within twice its radius) the parent's fit if
// it misses its points by at most 0.05 point spacings rms; else (a far cell) the plane through the
// nearest point normal to the direction from it to the cell's centre, on the side the generalized
// winding number of the cloud (Barill et al. 2018) puts the centre: Q is about minus the distance
// to the points outside, plus the distance inside, and never changes sign within the ball (the
// tangent planes of a thin wall's two sides both say "inside" past its edge, which made spurious
// sheets). After fitting, every leaf whose centre is at least 2 point spacings from the points and
// whose Q there contradicts the winding number takes that plane too, and so does (where the flood
// fill below is not trusted) a leaf whose ball holds no point but whose Q changes sign in it and
// contradicts a decisive winding number (below 0.05 or above 0.95) at 2 or more points of a 5^3
// lattice over the ball: a sheet of F where no point lies, off a thin corner
// (info.sign_fixed_leaves).
// Then (options.exterior_side) a voxel flood fill of the points' shell (1.5 point spacings) reads
// the outside and the inside from the positions alone; when the winding number agrees with it at
// 97 % of the free voxels next to the shell (the shell closes the cloud), a leaf whose Q has the
// wrong sign at 90 % (and at least 8) of the labelled points of a 9^3 lattice over its support
// ball is negated (info.exterior_negated_leaves): its normals were wrong where neither the
// orientation nor the winding number can tell, as at a blade's thin edges. The grid is built
// before the octree, and on a noisy scan a cell whose fit has the wrong sign at 8 (and fewer
// than 90 %) of those lattice points is split (info.exterior_split_cells; cells too sparse for a
// fit of their own too): a thin wall's two sheets joined into a slab that runs on past the
// wall's edge. Slabs too thin for that lattice are found on their mid-surface
// (options.split_slabs): on a noisy scan, a cell whose two sheets' slab has Q > 0, a point
// spacing or more from the points, where the winding number is below 0.05 at 2 or more of 13^2
// samples over its ball is split (info.slab_split_cells). Opt-in (options.split_pockets),
// a cell whose Q < 0 a point spacing or more behind the nearest point, where the winding number
// is above 0.95, at 2 or more points of a 5^3 lattice over its ball is split
// (info.pocket_split_cells): a wall's sheet carried into a thin wall past a concave edge.
// Before fitting, the normals' orientation is checked by the divergence theorem (sum of a_i n_i .
// (p_i - centroid) = 3 x volume > 0 for outward normals, a_i the area per point): inward normals
// are flipped and info.flipped is set. Throws std::invalid_argument for a cloud without normals,
// fewer than min_points (automatic: 20) points or bad options (min_points 1 or 2, or negative).
CloudImplicit fit_cloud_implicit(const PointCloud& c, const CloudFitOptions& options = {},
                                 CloudFitInfo* info = nullptr);

// The model as an ImplicitFunction (value and exact gradient, box = model.box). Builds the
// evaluation structure once (a lookup octree whose leaves list the support balls meeting them),
// so that a point costs one descent and a short loop. Outside the root cube,
// F(x) = F(x') - |x - x'| with x' the nearest point of the cube (continuous, negative far away).
// Safe for concurrent calls; a point's value does not depend on the batch it comes in.
// Throws std::invalid_argument when the fits do not tile the root cube or a ball does not cover
// its cell (a model read from a file).
ImplicitFunction cloud_implicit_function(std::shared_ptr<const CloudImplicit> model);

// The value of one local function and its gradient (exposed for tests and the .ifl reader's
// checks).
double local_fit_value(const LocalFit& f, const Eigen::Vector3d& x, Eigen::Vector3d* gradient);

} // namespace interlin
