// seed 001 §2.5: surface of a body from section lines; §2.2: closed section curves.
#include "interlin/reconstruction/loft/loft.h"

#include "section_curves.h"

#include "interlin/interlineation/interlinate_curves.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace interlin {

using Eigen::Index;

LoftResult loft_sections(const std::vector<Section>& sections, const LoftOptions& o) {
  const Index K = static_cast<Index>(sections.size());
  if (K < 2)
    throw std::invalid_argument("a loft needs at least 2 sections, got " + std::to_string(K));
  if (o.degree < 1 || o.span_degree < 1)
    throw std::invalid_argument("degrees must be >= 1");
  for (const Section& s : sections)
    if (s.points.rows() < std::max(4, o.degree + 1))
      throw std::invalid_argument("section " + s.id + " has " + std::to_string(s.points.rows()) +
                                  " points; degree " + std::to_string(o.degree) +
                                  " needs at least " + std::to_string(std::max(4, o.degree + 1)));
  LoftResult r;
  r.sections = prepare_sections(sections, o.align, r.notes);

  // The opposite edge is a landmark (one common parameter) when the start is an aligned edge.
  std::vector<std::vector<Index>> landmarks(static_cast<size_t>(K));
  if (o.align != StartAlign::first)
    for (Index k = 0; k < K; ++k) {
      const PreparedSection& s = r.sections[static_cast<size_t>(k)];
      landmarks[static_cast<size_t>(k)] = {o.align == StartAlign::leading_edge ? s.te : s.le};
    }
  const detail::SectionCurves c = detail::section_curves(r.sections, landmarks, o);
  r.used = c.used;
  r.point_u = c.point_u;
  r.section_v = c.section_v;
  r.surface = interlinate_curves(c.curves, r.section_v, o.span_degree, true);

  // The interlineation property, checked at every input point.
  Eigen::Vector3d lo, hi;
  detail::section_deviation(r, lo, hi);
  r.bbox_diagonal = (hi - lo).norm();
  detail::require_exact(r, "loft: surface deviates from the input points");
  return r;
}

} // namespace interlin
