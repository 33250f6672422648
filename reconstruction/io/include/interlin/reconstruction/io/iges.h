#pragma once
// IGES 5.3 output of a B-spline surface: one Rational B-Spline Surface entity (type 128), and a
// reader for the first such entity of an IGES file (round-trip checks, CAD input).

#include "interlin/splines/bspline_surface.h"

#include <string>
#include <string_view>

namespace interlin {

// Length unit written to the Global section (unit flag / unit name): mm 2 "MM", cm 10 "CM",
// m 6 "M", inch 1 "IN". Coordinates are never scaled: the flag only labels them.
enum class LengthUnit { mm, cm, m, inch };

struct IgesOptions {
  LengthUnit unit = LengthUnit::mm;
  std::string author = "interlin"; // Global parameter 21 (printable ASCII, at most 64 chars kept)
  std::string description;         // Start section text (free ASCII, wrapped at 72 columns)
};

// Writes `s` as an IGES 5.3 file (fixed 80-column ASCII form, sections S/G/D/P/T) with exactly
// one entity: type 128 form 0, PROP1 = s.closed_u, PROP2 = 0, PROP3 = 1 (polynomial, all weights
// 1), PROP4 = PROP5 = 0 (not periodic), untrimmed (readers such as OpenCASCADE and FreeCAD make
// one face with natural bounds). Knots, control points (row i + num_u*j, first index fastest as
// IGES requires) and the parameter range [knots_u(p), knots_u(num_u)] x [...] are written as
// the shortest decimal that reads back to the same double (at most 17 significant digits), so a
// round trip through read_iges_surface is bit-exact. The Global section dates the file with the
// current UTC time, or with SOURCE_DATE_EPOCH when that environment variable is set
// (reproducible output).
// Inputs:
//   path  output file, written atomically (a failure leaves no file behind)
//   s     a valid surface (check_surface; std::invalid_argument otherwise)
//   opt   unit label, author, Start-section description
// Throws std::runtime_error("cannot write PATH: ...") when the file cannot be written.
void write_iges(const std::string& path, const BSplineSurface& s, const IgesOptions& opt = {});

// Reads the first entity of type 128 of an IGES file in fixed (80-column ASCII) form: our own
// files and other well-formed ones (any parameter/record delimiters, D or E exponents, CRLF).
// A transformation matrix (entity 124, chained) referenced by the entity is applied to the
// control points. Coordinates are returned as written (the file's unit flag is not applied).
// Output: the surface with closed_u = PROP1; the knot vectors must be clamped (end knots of
// multiplicity degree+1) and the weights all equal (a polynomial surface), otherwise the file
// is rejected.
// Throws InputError("PATH:LINE: message") for unreadable, truncated or malformed files,
// unsupported surfaces, or a missing entity 128.
BSplineSurface read_iges_surface(const std::string& path);

// Same as read_iges_surface, from the file's content `text`; `path` names it in messages.
BSplineSurface parse_iges_surface(std::string_view text, const std::string& path);

} // namespace interlin
