#pragma once
// Private to reconstruction/clouds: the local sheets of oriented points (the partition of
// unity's cell fits, cloud_implicit_fit.cpp; the smoothing's edge projection,
// smooth_scan_points.cpp): one quadric height function, or two joined at an edge or a thin wall.

#include "interlin/reconstruction/clouds/cloud_implicit.h"

#include <Eigen/Core>
#include <vector>

namespace interlin::detail {

// Oriented points: P, N #P by 3 (unit normals).
struct OrientedPoints {
  const Eigen::MatrixX3d& P;
  const Eigen::MatrixX3d& N;
};

inline constexpr int kQuadricPoints = 10; // a sheet with fewer points is a plane

// Weighted least-squares height function over the points idx (weights w) in the frame of their
// mean normal; `scale` (the ball radius) normalises the coordinates. False when degenerate.
bool fit_sheet(const OrientedPoints& pts, const std::vector<int>& idx, const std::vector<double>& w,
               double scale, bool quadric, HeightSheet& s);

// Splits the points idx into two groups by normal direction (2-means on the sphere, seeded by
// the normal farthest from the mean and the one farthest from that); a and b receive positions
// in idx.
void split_by_normal(const OrientedPoints& pts, const std::vector<int>& idx,
                     const Eigen::Vector3d& mean, std::vector<size_t>& a, std::vector<size_t>& b);

// The signed distance of x to the zero set of f, to first order: Q / |grad Q| of its sheet, or
// of the sheet that decides the join of two (the smaller of the two distances for a conjunction,
// the larger for a disjunction: the join's zero set is that of their min or max). deciding: that
// sheet's index.
double join_distance(const LocalFit& f, const Eigen::Vector3d& x, int* deciding = nullptr);

// Two sheets whose normals are more than 120 degrees apart are a thin wall's sides.
inline constexpr double kThinWallCos = -0.5;

// The distances of the points idx to the zero set of f, rms and max: for a thin wall
// |join_distance|; otherwise |F| / |grad F| of the fit (R0's join for edge sheets). R0's own
// measure overstates a point's distance where both sheets are near, by 1 / cos(theta / 2) on
// the bisector of planes theta apart (without bound toward a thin wall's rim), which split cells
// along every rim of a thin blade; at edges it is kept: there the deciding sheet's measure
// accepted coarse cells whose joined quadrics close a blob of F > 0 off the points (the blade at
// sigma 0.005 cm: 0.2 cm off, Hausdorff 0.0089 -> 0.0203 of the diagonal). docs/benchmarks.md,
// "Edge projection in the smoothing".
void misfit(const LocalFit& f, const OrientedPoints& pts, const std::vector<int>& idx, double& rms,
            double& mx);

// The sheets of the groups a and b (positions in idx) into f, joined as the points lie: each
// group inside the other's sheet is a thin wall or a convex edge (conjunction), outside a concave
// edge (disjunction). False when a sheet is degenerate.
bool fit_two_sheets(const OrientedPoints& pts, const std::vector<int>& idx,
                    const std::vector<double>& w, double R, const std::vector<size_t>& a,
                    const std::vector<size_t>& b, LocalFit& f);

// Edge sheets (Ohtake et al. 2003: a cell across a sharp feature takes a Boolean of two
// fits): points that pass the one-sheet test may still hold an edge whose faces' normals are
// within 60 degrees of their mean (a 90-degree edge: 45 each), where one quadric rounds the edge
// by up to the acceptance's 1.5 sigma rms. When their normals split into two groups whose mean
// normals differ by kEdgeAngle or more, each with kEdgeShare of the weight and kQuadricPoints
// points, the join of the groups' sheets replaces the quadric if it misses the points by
// at most kEdgeGain times the quadric's rms. Measured on 18 blade and valve scans, the clean
// models, sparse clouds and the smoothing families (docs/benchmarks.md, "Edge sheets"): at most
// 0.8 % worse, the noisy valve -7 %, the clean valve -11 %.
inline constexpr double kEdgeAngle = 20, kEdgeShare = 0.1, kEdgeGain = 0.9;

// Whether normals of total weight sw whose weighted sum is m can hold two groups as above:
// their mean resultant length |m| / sw is below that of two groups kEdgeAngle apart with
// kEdgeShare and 1 - kEdgeShare of the weight (a quick test: most cells are smooth).
bool may_hold_edge(const Eigen::Vector3d& m, double sw);

// The one-sheet fit f of the points idx (weights w, ball radius R, mean normal `mean`) replaced
// by edge sheets where they fit (see kEdgeGain).
void fit_edge_sheets(const OrientedPoints& pts, const std::vector<int>& idx,
                     const std::vector<double>& w, double R, const Eigen::Vector3d& mean,
                     LocalFit& f);

} // namespace interlin::detail
