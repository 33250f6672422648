#pragma once
// Untangling of hexahedral meshes, shared by the mesher (pillows) and the refinement (children of
// nearly flat parents, new boundary nodes).

#include "interlin/interflatation/implicit_function.h"
#include "interlin/reconstruction/meshing/volume_smoothing.h"

#include <Eigen/Core>

#include <vector>

namespace interlin::detail {

// Rounds of functional (15) with a sharp exponent (local max-min untangling) over the free nodes
// (not in `fixed`) of the inverted hexahedra and their neighbours, until none is inverted or the
// rounds stop helping (volume_mesh.cpp, untangle_rounds). Returns the elements still inverted.
// Inputs:  C #C by 8 hexahedra, fixed #V flags, threads (0: all cores)
// In/out:  V
long untangle_hexahedra(const Eigen::MatrixXi& C, const std::vector<char>& fixed, int threads,
                        Eigen::MatrixXd& V);

// The same rounds with the nodes flagged in `slides` (of the fixed ones) sliding on the surface
// (the pillows' untangling, volume_mesh.cpp untangle_pillows).
long untangle_hexahedra(const Eigen::MatrixXi& C, const std::vector<char>& fixed,
                        const SlidingSurface& surface, const std::vector<char>& slides, int threads,
                        Eigen::MatrixXd& V);

// The elements with a node flagged in `at` (#V), renumbered: C's rows over the sub-mesh's nodes,
// node[k] the mesh node of its node k (in increasing order).
struct SubMesh {
  Eigen::MatrixXi C;
  std::vector<long> node;
};
SubMesh elements_at(const Eigen::MatrixXi& C, const std::vector<char>& at);

// Nodes flagged movable of folded elements (a corner or, hexahedra, the centre) go back to where
// they were in `before` (a valid mesh), until none is folded: surface smoothing may slide a node
// of a cut grid's small element across its opposite face, interior smoothing one beside a held
// layer element across it. Returns the nodes put back.
long restore_folded(const Eigen::MatrixXd& before, const std::vector<char>& movable,
                    const Eigen::MatrixXi& C, int threads, Eigen::MatrixXd& V);

// F = 0 as a surface to slide boundary nodes on: outward normals and the seed's gradient walk
// (steps of h / 4) back onto it, on `threads` threads.
SlidingSurface implicit_surface(const ImplicitFunction& f, double h, int threads);

} // namespace interlin::detail
