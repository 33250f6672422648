#pragma once
// CGAL Mesh_3 baseline of the volume-mesh benchmark: Delaunay refinement of an implicit body
// (Labeled_mesh_domain_3::create_implicit_mesh_domain, make_mesh_3). Only cgal_mesh_3.cpp sees
// CGAL's headers, so this interface is plain Eigen.

#include <Eigen/Core>
#include <functional>

namespace interlin::bench {

struct CgalMeshOptions {
  double size = 0.1; // facet_size and cell_size: target edge scale, the grid cell of interlin's run
  double facet_distance = 0.01; // surface approximation (CGAL's facet_distance)
  double facet_angle = 25;      // degrees, lower bound of the surface triangles' angles
  double radius_edge = 2;       // cell_radius_edge_ratio upper bound
  bool optimise = true;         // ODT smoothing, perturbation and exudation (CGAL's optimisers)
};

// Tetrahedral mesh of { F > 0 } inside the ball (centre, radius). F is called one point at a time
// (CGAL's domain oracle), on one thread (CGAL::Sequential_tag).
// Outputs: V #V by 3, T #T by 4 positively oriented ((p1 - p0) x (p2 - p0) . (p3 - p0) > 0),
//          B #B by 3 the boundary triangles (vertices of V)
void cgal_mesh_3(const std::function<double(double, double, double)>& F,
                 const Eigen::Vector3d& centre, double radius, const CgalMeshOptions& o,
                 Eigen::MatrixXd& V, Eigen::MatrixXi& T, Eigen::MatrixXi& B);

} // namespace interlin::bench
