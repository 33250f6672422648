#pragma once
// Section data shared by the loft tests: the NASA Rotor 37 blade sections (data/rotor37) with
// their edge lines, and sections sampled from bodies known in closed form.

#include "interlin/reconstruction/io/guide_csv.h"
#include "interlin/reconstruction/io/section_csv.h"

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace interlin::test {

// The 13 Rotor 37 sections, read once.
inline const std::vector<Section>& rotor37() {
  static const SectionSet set = read_sections(INTERLIN_DATA_DIR "/rotor37/sections.csv");
  return set.sections;
}

// The leading- and trailing-edge lines of the NASA table: point 0 (J = 1) and point 99
// (J = 100) of every section.
inline GuideSet rotor37_edges(const std::vector<Section>& s) {
  GuideSet g;
  g.path = "edges.csv";
  for (auto [id, row] : {std::pair{"LE", 0}, {"TE", 99}}) {
    Guide e;
    e.id = id;
    e.points.resize(static_cast<Eigen::Index>(s.size()), 3);
    for (size_t k = 0; k < s.size(); ++k) {
      e.points.row(static_cast<Eigen::Index>(k)) = s[k].points.row(row);
      e.lines.push_back(static_cast<long>(k) + 2);
    }
    g.guides.push_back(e);
  }
  return g;
}

// The closed section at height z through point(t, z) at n nonuniform angles
// t_i = 2 pi (i / n + wobble sin(2 pi i / n)) + phase, on lines 2, 3, ...
template <class Point>
Section angle_section(double z, Eigen::Index n, double phase, double wobble, Point point) {
  Section s;
  s.id = std::to_string(z);
  s.points.resize(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t =
        2 * M_PI * (double(i) / n + wobble * std::sin(2 * M_PI * double(i) / n)) + phase;
    s.points.row(i) = point(t, z).transpose();
    s.lines.push_back(i + 2);
  }
  return s;
}

// A smooth twisted, tapering elliptic body: section z has semi-axes a(z), b(z) and is turned by
// twist(z) = 0.4 z. Exactly known surface for error studies.
inline Eigen::Vector3d body(double t, double z) {
  const double a = 2.0 + 0.3 * std::sin(z), b = 0.6 + 0.1 * z * z, w = 0.4 * z;
  const double x = a * std::cos(t), y = b * std::sin(t);
  return {std::cos(w) * x - std::sin(w) * y, std::sin(w) * x + std::cos(w) * y, z};
}

// The body's section at height z through n points (angle wobble 0.03).
inline Section body_section(double z, Eigen::Index n, double phase = 0) {
  return angle_section(z, n, phase, 0.03, body);
}

} // namespace interlin::test
