#pragma once
// CAD caps of a closed loft: each end loop S(u, v0), S(u, v1) filled by the ruled surface between
// its two halves (cut at the loop's two points farthest apart: a blade's leading and trailing
// edges), whose boundary is exactly the loop, so that the lateral surface and the two caps make a
// closed shell (the solid of interlin loft --cap in STEP).

#include "interlin/reconstruction/io/step.h"
#include "interlin/splines/bspline_curve.h"
#include "interlin/splines/bspline_surface.h"

namespace interlin {

// The loop at v = v0 (at_end false) or v1 of a closed_u surface, as a clamped curve: the surface's
// first (last) row of control points with its u knots (exact: the surface is clamped in v).
BSplineCurve end_loop(const BSplineSurface& s, bool at_end);

// The cap of one end. Corners: the two loop points farthest apart (on a fine sampling), corner_u
// their parameters (increasing, in [u0, u1)). Patch: degree p x 1 (p the loop's degree) on
// [0, 1]^2, P(s, t) = (1 - t) A(s) + t B(s), A the loop from corner 0 to corner 1, B the other
// half from corner 0 to corner 1, both parametrised by their own parameter mapped to [0, 1] (the
// loft's u is a chord-length parameter: points at equal fractions of each half's length are
// joined); the sides s = 0 and s = 1 are the corners. A planar loop gives a planar cap (every
// cap point is an affine combination of loop points), a thin blade section lines across its
// thickness, which do not cross as long as the two halves run alike from edge to edge.
// Inputs: s closed_u, check_surface-valid (std::invalid_argument otherwise)
StepCap end_cap(const BSplineSurface& s, bool at_end);

} // namespace interlin
