#pragma once
// Making blade sections compatible before lofting: one winding, one start feature, known edges.

#include "interlin/reconstruction/io/section_csv.h"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace interlin {

enum class StartAlign { first, leading_edge, trailing_edge };

// One section after preparation.
//   points  #P by 3, closed profile, rolled so that row 0 is the start feature and wound like the
//           first section
//   lines   #P source lines of the rows (for messages)
//   source  #P row indices into the input section's points (what reversing and rolling did)
//   le, te  row indices of the detected leading / trailing edge (-1 when not detected)
//   reversed  the winding was reversed to match the previous section
struct PreparedSection {
  std::string id;
  Eigen::MatrixXd points;
  std::vector<long> lines;
  std::vector<Eigen::Index> source;
  Eigen::Index le = -1, te = -1;
  bool reversed = false;
};

// Newell's vector area of a closed polygon (#P by 3): normal times enclosed area, defined for
// non-planar polygons too; its direction gives the winding.
Eigen::Vector3d vector_area(const Eigen::MatrixXd& P);

// The two edge points (leading/trailing edge candidates) of a closed profile: the ends of its
// longest chord, each moved to the nose tip where the mean line leaves the profile (the profile
// point farthest along the bisector direction of the two flanks). Output: row indices (a, b).
std::pair<Eigen::Index, Eigen::Index> profile_edges(const Eigen::MatrixXd& P);

// Position (0..1 along the chord from edge a to edge b) of the maximum thickness of a profile.
double max_thickness_position(const Eigen::MatrixXd& P, Eigen::Index a, Eigen::Index b);

// Orients every section like the first one (reversing those whose vector area points the other
// way; the start point is kept), detects the edges and, for align = leading_edge/trailing_edge,
// rolls each section to start there. The leading edge is the edge nearer the maximum thickness,
// decided by a vote over all sections after matching edges section to section by proximity, so
// that every section labels the same physical edge. One line per changed section is appended to
// `notes` ("section S: reversed to match the winding of section T").
std::vector<PreparedSection> prepare_sections(const std::vector<Section>& sections,
                                              StartAlign align, std::vector<std::string>& notes);

} // namespace interlin
