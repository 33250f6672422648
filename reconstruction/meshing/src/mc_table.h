#pragma once
// Internal: the marching-cubes case table, generated once at first use from the cube geometry
// instead of typed in. Corners c = x + 2y + 4z (x, y, z in {0, 1}); edge 4a + u + 2v runs along
// axis a at coordinates (u, v) on the other two axes (in increasing axis order); face 2a + s is
// the face with coordinate a = s.
//
// A case is the 8-bit set of inside corners. A face whose inside corners are diagonal is
// ambiguous; each ambiguous face contributes one bit to a sub-case: 1 when the inside corners
// are connected across the face (asymptotic decider), 0 when they are separated. The decider
// reads only the face's four values, so the two cubes sharing a face decide alike and the
// surface has no cracks.

#include <cstdint>
#include <vector>

namespace interlin::detail {

struct McTable {
  std::uint8_t ambiguous[256];      // bit f set: face f is ambiguous in this case
  std::uint32_t first[256];         // sub-case 0 of the case; sub-case bits follow the face order
  std::vector<std::uint32_t> start; // triangles of sub-case s: edges[3*start[s] .. 3*start[s+1])
  std::vector<std::uint8_t> edges;  // cube edges, 3 per triangle, oriented outward (see .cpp)
  int face_corner[6][4];            // corners of each face in cyclic order
  int edge_corner[12][2];           // corners of each edge, the lower one first
  int max_triangles = 0;            // most triangles of any sub-case
};

const McTable& mc_table();

} // namespace interlin::detail
