#pragma once
// Helpers shared by the section-body tests and measurements: omega on a batch of points, random
// boundary points, and the capped loft mesh that serves as the independent inside test.
#include "interlin/interflatation/models/body_patches.h"
#include "interlin/reconstruction/implicit/body_projection.h"
#include "interlin/reconstruction/implicit/section_body_build.h"
#include "interlin/reconstruction/meshing/surface_mesh.h"

#include <Eigen/Core>
#include <random>

namespace interlin::test {

// omega at the rows of P (#P by 3) -> #P values.
inline Eigen::VectorXd omega(const ImplicitFunction& f, const Eigen::MatrixXd& P) {
  Eigen::VectorXd w(P.rows());
  f.value(Points3(P), w);
  return w;
}

// n random points of the boundary: side 60 % (u, v uniform), each cap 20 % (s, t uniform).
inline Eigen::MatrixXd boundary_points(const BodyPatches& B, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0, 1);
  Eigen::MatrixXd P(n, 3);
  for (int i = 0; i < n; ++i)
    P.row(i) = evaluate(B, PatchSeed{i % 5 == 0   ? 1
                                     : i % 5 == 1 ? 2
                                                  : 0,
                                     U(rng), U(rng)})
                   .transpose();
  return P;
}

// The capped loft mesh (V #V by 3, F #F by 3) of `interlin loft --cap`, 800 x 200 samples with
// every section as a mesh row: the independent body for ray parity and thickness.
inline void capped_mesh(const SectionBodyBuild& b, Eigen::MatrixXd& V, Eigen::MatrixXi& F) {
  SurfaceMeshOptions mo;
  mo.nu = 800;
  mo.nv = 200;
  mo.cap = true;
  mo.required_v.assign(b.report.loft.section_v.data(),
                       b.report.loft.section_v.data() + b.report.loft.section_v.size());
  surface_mesh(to_piecewise(b.model.side), mo, V, F);
}

// omega's ratio to the distance at the inside normal offsets P = foot - delta n (P #P by 3, delta
// #P): the reference is delta where the offset's foot is its nearest boundary point (the exact
// distance by BodyProjection equals delta), else the exact distance itself (an offset past the
// local medial surface, e.g. along the chord near an edge, where delta overstates the distance).
// `by_exact` counts the offsets of the second kind.
struct InsideOffsetRatios {
  Eigen::VectorXd ratio;
  int by_exact = 0;
};
inline InsideOffsetRatios inside_offset_ratios(const ImplicitFunction& f,
                                               const BodyProjection& proj, const Eigen::MatrixXd& P,
                                               const Eigen::VectorXd& delta) {
  const Eigen::VectorXd w = omega(f, P);
  const std::vector<BodyDistance> d = proj.distances(P);
  InsideOffsetRatios r{Eigen::VectorXd(P.rows()), 0};
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const double di = d[static_cast<size_t>(i)].distance;
    const bool foot_nearest = di >= (1 - 1e-6) * delta(i); // Newton's foot to ~1e-10 relative
    r.by_exact += !foot_nearest;
    r.ratio(i) = w(i) / (foot_nearest ? delta(i) : di);
  }
  return r;
}

} // namespace interlin::test
