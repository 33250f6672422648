// seed 001 §2.5: surface of a body from section lines; §2.2: closed section curves.
#include "interlin/reconstruction/loft/loft.h"

#include "cross_validate_span.h"
#include "section_curves.h"

#include "interlin/interlineation/interlinate_curves.h"

namespace interlin {

LoftResult loft_sections(const std::vector<Section>& sections, const LoftOptions& o) {
  detail::check_loft_inputs(sections, o);
  LoftResult r;
  r.sections = prepare_sections(sections, o.align, r.notes);
  const auto landmarks = detail::edge_landmarks(r.sections, o.align);
  const detail::SectionCurves c = detail::section_curves(r.sections, landmarks, o);
  r.span = detail::choose_span_model(r.sections, c, o);
  r.used = c.used;
  r.point_u = c.point_u;
  r.section_v = detail::model_span_parameters(r.span, c.curves, r.sections);
  r.surface = interlinate_curves(c.curves, r.section_v, r.span.used.degree, true);

  // The interlineation property, checked at every input point.
  Eigen::Vector3d lo, hi;
  detail::section_deviation(r, lo, hi);
  r.bbox_diagonal = (hi - lo).norm();
  detail::require_exact(r, "loft: surface deviates from the input points");
  return r;
}

} // namespace interlin
