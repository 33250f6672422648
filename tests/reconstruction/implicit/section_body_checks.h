#pragma once
// Helpers shared by the section-body tests and measurements: omega on a batch of points, random
// boundary points, and the capped loft mesh that serves as the independent inside test.
#include "interlin/interflatation/models/body_patches.h"
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

} // namespace interlin::test
