#pragma once
// Guide-line files: spanwise polylines on the surface (leading edge, trailing edge, any user
// line) that the guided loft interpolates together with the sections. CSV with a header naming
// the columns guide, x, y, z (index optional); the format and every error are described in
// docs/formats.md ("Guide files").

#include <Eigen/Core>
#include <iosfwd>
#include <string>
#include <vector>

namespace interlin {

// One open polyline.
//   id      the `guide` value as written
//   points  #P by 3, #P >= 2, no point equal to its predecessor
//   lines   #P source line numbers (1-based)
struct Guide {
  std::string id;
  Eigen::MatrixXd points;
  std::vector<long> lines;
};

// The guides of one file in order of first appearance; path is used in messages.
struct GuideSet {
  std::string path;
  std::vector<Guide> guides;
};

// Reads a guide file. Throws InputError "FILE:LINE: message" (or "FILE: message").
GuideSet read_guides(const std::string& path);

// Same, from a stream.
GuideSet parse_guides(std::istream& in, const std::string& path_for_messages);

} // namespace interlin
