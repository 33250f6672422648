#pragma once
// Topology and quality checks of a triangle mesh.

#include <Eigen/Core>

namespace interlin {

struct MeshReport {
  long vertices = 0, faces = 0;
  long boundary_edges = 0;            // edges with one incident face
  long nonmanifold_edges = 0;         // edges with more than two incident faces
  long nonmanifold_vertices = 0;      // vertices whose faces form more than one fan (linked across
                                      // edges with exactly two faces)
  long components = 0;                // connected components of the vertex-edge graph (an unused
                                      // vertex is a component of its own)
  long euler = 0;                     // V - E + F
  long genus = -1;                    // sum of component genera; -1 unless closed, manifold,
                                      // consistently oriented and every vertex used
  bool consistently_oriented = false; // every edge has two faces using it in opposite directions
                                      // (boundary edges allowed, non-manifold edges not)
  double area = 0;
  double volume = 0; // signed, by the divergence theorem (sum of tetrahedra to the bounding-box
                     // centre: origin-independent for closed meshes)
  double min_angle_deg = 0;    // smallest corner angle of the non-degenerate faces
  double max_aspect_ratio = 0; // largest sqrt(3) l_max^2 / (4 area) (1 for equilateral) of the
                               // non-degenerate faces
  long degenerate_faces = 0;   // repeated vertex index, or 2 area <= 1e-12 l_max^2
  // Closed, manifold, consistently oriented, no degenerate faces (and at least one face).
  bool watertight() const;
};

// Inputs:  V #V by 3, F #F by 3 (0-based indices; std::invalid_argument when out of range)
// Output:  the report above. O(#F log #F).
MeshReport check_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

} // namespace interlin
