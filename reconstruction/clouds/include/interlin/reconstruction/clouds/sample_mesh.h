#pragma once
// Simulated scans: points uniform by area on a triangle mesh (a loft's capped mesh, a model's
// marching-cubes mesh), for benchmarks, studies and tests whose truth is the mesh.

#include "interlin/reconstruction/clouds/point_cloud.h"

#include <Eigen/Core>

namespace interlin {

// n points uniform by area on the triangles of a mesh, each with its triangle's unit normal.
// Inputs:  V #V by 3 vertices, F #F by 3 triangles (their orientation gives the normals' side),
//          n >= 0 points, seed of the random draws (deterministic for a seed)
// Output:  PointCloud with n points and n normals; std::invalid_argument for an empty F, an
//          index out of range, a mesh of zero area or n < 0.
// See also: prepare_cloud (noise, outliers, normals estimated again as a scanner would).
PointCloud sample_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int n, unsigned seed);

} // namespace interlin
