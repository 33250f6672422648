#pragma once
// Implicit body -> closed triangle mesh: seed 002's parallel sub-box scheme (the bounding box cut
// into sub-boxes that share their boundary planes, each sampled and triangulated on its own
// thread), marching cubes with the asymptotic decider in each sub-box, an exact merge of the
// vertices on shared planes, and seed 003's projection of every vertex onto F = 0.

#include "interlin/interflatation/implicit_function.h"
#include "interlin/interflatation/limits.h"
#include "interlin/reconstruction/meshing/project_to_zero.h"
#include "interlin/reconstruction/meshing/regular_grid.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <string>

namespace interlin {

struct ImplicitMeshOptions {
  // Region to mesh; empty: the function's own box. The body is cut by this box: the mesh is
  // the boundary of {F > 0} inside it, closed along the box faces where the body reaches them.
  Eigen::AlignedBox3d box;
  int resolution = 128; // cells along the box's longest side (grid_with_resolution) ...
  double cell = 0;      // ... unless a cell size h > 0 is given (grid_with_cell)
  // Sub-boxes along x, y, z (each >= 1, at most the cells on that axis); 0 on an axis: automatic,
  // at most 64 cells per sub-box along it (16 when f.sign_on_box can skip the ones the surface
  // does not cross).
  Eigen::Array3i subboxes = Eigen::Array3i::Zero();
  int threads = 0;     // worker threads; 0: all cores
  bool project = true; // refine every vertex onto F = 0 along its grid edge (else linear)
  RootOptions root;    // tolerance of the projection (relative to the cell size)
  // Triangles allowed (limits::mesh_triangles): past it meshing stops with a LimitError, before
  // the merge (a surface that folds in every cell would otherwise fill the memory).
  long long max_triangles = limits::mesh_triangles;
  // Progress messages (stage starts and every tenth of the sub-boxes); called under a lock, from
  // worker threads too.
  std::function<void(const std::string&)> progress;
};

struct ImplicitMeshInfo {
  RegularGrid grid;
  Eigen::Array3i subboxes = Eigen::Array3i::Ones();
  long samples = 0; // function values sampled (nodes on shared planes count twice)
  long projection_evaluations = 0;
  long nonfinite = 0; // grid nodes whose value was NaN or infinite (treated as outside, +inf
                      // as inside), each once
  long clipped = 0;   // outer grid nodes where the body reaches the box (reaches_box), each once
  long skipped = 0;   // sub-boxes not sampled: f.sign_on_box gave them one sign (narrow band;
                      // within the others, blocks down to 4 cells are skipped the same way)
  double seconds_extract = 0, seconds_merge = 0, seconds_project = 0; // wall clock
};

// Meshes the body {F > 0} (within the box).
// Steps: grid over the box (cells from o.resolution or o.cell); each sub-box to which
// f.sign_on_box gives one sign is skipped (it holds no surface: a narrow band around F = 0, same
// mesh), unless it is inside and touches the box (the closing faces), and so is each block of its
// nodes, halved down to 4 cells, with a sign (its nodes take it as their value); the nodes of each
// sub-box sampled in batches of one z-slice and triangulated by marching cubes (all sub-boxes in
// parallel); the sub-box meshes merged, each vertex on a shared plane kept once (its grid edge
// identifies it, and both copies are bit-identical); every vertex moved onto F = 0 along its grid
// edge (project_edge_vertices). The function actually meshed is min(F, B) with B the signed
// distance to the box, and nodes of the grid's outer layer are never inside, so the result is
// closed. Guarantees: closed, 2-manifold, consistently oriented (normals out of the body), no
// repeated vertex in a triangle and no two vertices at one point where F = 0 at grid nodes
// (kEdgeClamp); the same mesh, up to vertex order, for any sub-box count and any thread count. Not
// guaranteed: that features thinner than a cell are seen, or good triangle shapes (marching cubes
// cuts slivers where the surface passes near a node: see smooth_on_surface and flip_edges). f must
// give the same value for the same point in any batch (nodes on shared planes are sampled by both
// sub-boxes). Inputs:
//   f  implicit function (value; gradient unused)
//   o  options; std::invalid_argument for no box, bad resolution/cell/sub-boxes, LimitError past
//      o.max_triangles
// Outputs:
//   V     #V by 3 vertices
//   F     #F by 3 triangles
//   info  optional statistics
void implicit_mesh(const ImplicitFunction& f, const ImplicitMeshOptions& o, Eigen::MatrixXd& V,
                   Eigen::MatrixXi& F, ImplicitMeshInfo* info = nullptr);

// The cell to mesh f over `box` with when the caller chooses none: f.sample_spacing /
// cells_per_spacing when f knows the spacing of the points it was fitted to (a point cloud's
// fit), with the grid kept to 32 .. 1024 cells along the box's longest side; else the longest
// side / 128 (ImplicitMeshOptions' default resolution). 2: three cells per spacing are within
// 2 % of its Chamfer on the bench's clouds at 20,000 and 100,000 points for twice the triangles
// (docs/benchmarks.md, "The mesh cell from the point spacing"). Throws std::invalid_argument for
// an empty box or cells_per_spacing <= 0.
double default_mesh_cell(const ImplicitFunction& f, const Eigen::AlignedBox3d& box,
                         double cells_per_spacing = 2);

// The function implicit_mesh meshes: min(F, B) with B the signed distance to `box` (positive
// inside); its box is `box`.
ImplicitFunction clip_to_box(const ImplicitFunction& f, const Eigen::AlignedBox3d& box);

} // namespace interlin
