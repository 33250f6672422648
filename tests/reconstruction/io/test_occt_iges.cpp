// Independent check of write_iges: OpenCASCADE's IGES reader (IGESControl_Reader) must turn our
// file into exactly one face on a Geom_BSplineSurface with our degrees, whose points agree with
// interlin's own evaluation, and whose distances (GeomAPI_ProjectPointOnSurf) match values known
// by construction. Built only when OpenCASCADE is found.
//
// Tolerance for point comparisons: both sides evaluate the same polynomial pieces from the same
// doubles (the file holds every knot and control point exactly), OCCT with de Boor-type
// recurrences on the B-spline form and interlin with Horner on the per-patch power form. Their
// difference is round-off only: a few hundred ulps of the coordinate magnitude at most for these
// degrees and knot spacings, so 1e-12 x (largest |coordinate|) is a safe bound that is still
// ~10 orders of magnitude below any real error (a wrong knot, index order or unit scale changes
// the points by O(size)).

#include "interlin/reconstruction/io/iges.h"
#include "interlin/reconstruction/io/section_csv.h"
#include "interlin/reconstruction/loft/holdout.h"
#include "interlin/splines/bspline_curve.h"
#include "interlin/splines/bspline_surface.h"
#include "interlin/splines/knot_insertion.h"

#include "support/test_support.h"
#include "support/test_surfaces.h"

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <BRep_Tool.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_Surface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Reader.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_Printer.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TopAbs_ShapeEnum.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Pnt.hxx>

#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

using namespace interlin;
namespace fs = std::filesystem;

namespace {

struct OcctResult {
  int faces = 0;
  Handle(Geom_BSplineSurface) surface; // of the first face (null if not a B-spline)
};

// Reads `path` with OCCT, converting lengths to `cascade_unit` ("MM", "M", "INCH", ...).
OcctResult read_with_occt(const std::string& path, const char* cascade_unit) {
  // Keep OCCT's progress messages ("Total number of loaded entities") out of the test log.
  for (Message_SequenceOfPrinters::Iterator it(Message::DefaultMessenger()->Printers()); it.More();
       it.Next())
    it.Value()->SetTraceLevel(Message_Fail);
  IGESControl_Reader reader; // initialises the IGES controller and its static parameters
  REQUIRE(Interface_Static::SetCVal("xstep.cascade.unit", cascade_unit));
  REQUIRE(reader.ReadFile(path.c_str()) == IFSelect_RetDone);
  reader.TransferRoots();
  REQUIRE(reader.NbShapes() >= 1);
  const TopoDS_Shape shape = reader.OneShape();
  OcctResult r;
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
    if (r.faces++ == 0)
      r.surface =
          Handle(Geom_BSplineSurface)::DownCast(BRep_Tool::Surface(TopoDS::Face(ex.Current())));
  }
  return r;
}

// ~1000 parameter pairs: the domain corners, every knot pair on a coarse lattice, and random
// pairs.
std::vector<std::pair<double, double>> sample_parameters(const BSplineSurface& s) {
  const Eigen::Vector4d d = domain(to_piecewise(s));
  std::vector<std::pair<double, double>> uv = {
      {d(0), d(2)}, {d(1), d(2)}, {d(0), d(3)}, {d(1), d(3)}};
  for (Eigen::Index i = s.degree_u; i <= s.num_u; ++i)
    for (Eigen::Index j = s.degree_v; j <= s.num_v; ++j)
      uv.emplace_back(s.knots_u(i), s.knots_v(j));
  std::mt19937 rng(12345u);
  std::uniform_real_distribution<double> u(d(0), d(1)), v(d(2), d(3));
  while (uv.size() < 1000)
    uv.emplace_back(u(rng), v(rng));
  return uv;
}

// Largest distance between OCCT's and interlin's points, `scale` x ours (unit conversion).
double max_point_difference(const BSplineSurface& s, const Handle(Geom_BSplineSurface) & occt,
                            double scale = 1.0) {
  const PiecewiseSurface ps = to_piecewise(s);
  double worst = 0.0;
  for (const auto& [u, v] : sample_parameters(s)) {
    const gp_Pnt p = occt->Value(u, v);
    const Eigen::Vector3d q = scale * evaluate(ps, u, v);
    worst = std::max(worst, (Eigen::Vector3d(p.X(), p.Y(), p.Z()) - q).norm());
  }
  return worst;
}

void check_same_parametrisation(const BSplineSurface& s, const Handle(Geom_BSplineSurface) & b) {
  double u0, u1, v0, v1;
  b->Bounds(u0, u1, v0, v1);
  CHECK(u0 == s.knots_u(s.degree_u));
  CHECK(u1 == s.knots_u(s.num_u));
  CHECK(v0 == s.knots_v(s.degree_v));
  CHECK(v1 == s.knots_v(s.num_v));
}

} // namespace

TEST_CASE("OpenCASCADE reads our IGES as one B-spline face with the same geometry", "[occt]") {
  test::TempDir tmp("occt-bicubic");
  const double size = 100.0;
  const BSplineSurface s = test::random_bicubic(9, 7, size, 777u);
  const std::string path = tmp.file("bicubic.igs");
  write_iges(path, s, {LengthUnit::mm, "interlin test", "OCCT cross-check"});

  const OcctResult r = read_with_occt(path, "MM"); // file unit = reader unit: no scaling
  REQUIRE(r.faces == 1);
  REQUIRE(!r.surface.IsNull());
  CHECK(r.surface->UDegree() == 3);
  CHECK(r.surface->VDegree() == 3);
  CHECK(r.surface->NbUPoles() == s.num_u);
  CHECK(r.surface->NbVPoles() == s.num_v);
  CHECK_FALSE(r.surface->IsURational());
  check_same_parametrisation(s, r.surface);
  // OCCT parses the decimals correctly rounded too: its poles and flat knot sequences are ours,
  // bit for bit (the surface has simple interior knots, nothing for OCCT to merge or remove).
  bool same_poles = true;
  for (Eigen::Index j = 0; j < s.num_v; ++j)
    for (Eigen::Index i = 0; i < s.num_u; ++i) {
      const gp_Pnt p = r.surface->Pole(static_cast<int>(i + 1), static_cast<int>(j + 1));
      const auto row = s.ctrl.row(i + s.num_u * j);
      same_poles = same_poles && p.X() == row(0) && p.Y() == row(1) && p.Z() == row(2);
    }
  CHECK(same_poles);
  TColStd_Array1OfReal ku(1, r.surface->NbUPoles() + 4), kv(1, r.surface->NbVPoles() + 4);
  r.surface->UKnotSequence(ku);
  r.surface->VKnotSequence(kv);
  for (Eigen::Index k = 0; k < s.knots_u.size(); ++k)
    CHECK(ku(static_cast<int>(k + 1)) == s.knots_u(k));
  for (Eigen::Index k = 0; k < s.knots_v.size(); ++k)
    CHECK(kv(static_cast<int>(k + 1)) == s.knots_v(k));
  const double diff = max_point_difference(s, r.surface);
  INFO("max |OCCT - interlin| = " << diff);
  CHECK(diff <= 1e-12 * size);
}

TEST_CASE("OpenCASCADE applies the IGES unit flag as documented", "[occt]") {
  test::TempDir tmp("occt-units");
  const double size = 2.0;
  const BSplineSurface s = test::random_bicubic(5, 6, size, 31u);
  const std::string path = tmp.file("metres.igs");
  write_iges(path, s, {LengthUnit::m, "", ""});
  // Reader in metres: coordinates as written.
  const OcctResult same = read_with_occt(path, "M");
  REQUIRE(same.faces == 1);
  REQUIRE(!same.surface.IsNull());
  CHECK(max_point_difference(s, same.surface) <= 1e-12 * size);
  // Reader in millimetres: everything scaled by 1000 (the flag labels metres, not a default).
  const OcctResult mm = read_with_occt(path, "MM");
  REQUIRE(mm.faces == 1);
  REQUIRE(!mm.surface.IsNull());
  CHECK(max_point_difference(s, mm.surface, 1000.0) <= 1e-12 * 1000.0 * size);
  // Inches: 25.4 mm each.
  write_iges(path, s, {LengthUnit::inch, "", ""});
  const OcctResult in = read_with_occt(path, "MM");
  REQUIRE(in.faces == 1);
  REQUIRE(!in.surface.IsNull());
  CHECK(max_point_difference(s, in.surface, 25.4) <= 1e-12 * 25.4 * size);
  Interface_Static::SetCVal("xstep.cascade.unit", "MM"); // restore the default
}

TEST_CASE("OpenCASCADE reads a closed_u tube as one closed face", "[occt]") {
  test::TempDir tmp("occt-tube");
  for (int pv : {1, 3}) {
    const BSplineSurface s = test::swept_tube(pv);
    const std::string path = tmp.file("tube.igs");
    write_iges(path, s);
    const OcctResult r = read_with_occt(path, "MM");
    INFO("degree_v = " << pv);
    REQUIRE(r.faces == 1);
    REQUIRE(!r.surface.IsNull());
    CHECK(r.surface->UDegree() == 3);
    CHECK(r.surface->VDegree() == pv);
    CHECK(r.surface->IsUClosed()); // OCCT's own check: first and last pole rows coincide
    CHECK_FALSE(r.surface->IsVClosed());
    check_same_parametrisation(s, r.surface);
    CHECK(max_point_difference(s, r.surface) <= 1e-12 * 3.0); // |coordinates| <= 10
  }
}

TEST_CASE("OpenCASCADE projections give the distances known by construction", "[occt]") {
  // A gentle height field over [0, L]^2: control points on a grid with heights in
  // [-0.02 L, 0.02 L]. Its principal curvature radii exceed ~0.25 L, so the point
  // q = S(u, v) + d n(u, v) with |d| <= 0.05 L and (u, v) inside the domain has S(u, v) as its
  // closest surface point and distance exactly |d|.
  test::TempDir tmp("occt-project");
  const double L = 50.0;
  const Eigen::Index n = 8;
  std::mt19937 rng(2024u);
  std::uniform_real_distribution<double> height(-0.02 * L, 0.02 * L), unit(0.0, 1.0);
  BSplineSurface s;
  s.num_u = s.num_v = n;
  s.knots_u.resize(n + 4);
  s.knots_u << 0, 0, 0, 0, 0.2, 0.4, 0.6, 0.8, 1, 1, 1, 1;
  s.knots_v = s.knots_u;
  s.ctrl.resize(n * n, 3);
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = 0; i < n; ++i)
      s.ctrl.row(i + n * j) << L * static_cast<double>(i) / (n - 1),
          L * static_cast<double>(j) / (n - 1), height(rng);
  const std::string path = tmp.file("field.igs");
  write_iges(path, s);
  const OcctResult r = read_with_occt(path, "MM");
  REQUIRE(r.faces == 1);
  REQUIRE(!r.surface.IsNull());

  const PiecewiseSurface ps = to_piecewise(s);
  double worst = 0.0;
  for (int k = 0; k < 50; ++k) {
    const double u = 0.15 + 0.7 * unit(rng), v = 0.15 + 0.7 * unit(rng);
    const double d = (2.0 * unit(rng) - 1.0) * 0.05 * L;
    const Eigen::Vector3d nrm =
        evaluate(ps, u, v, 1, 0).cross(evaluate(ps, u, v, 0, 1)).normalized();
    const Eigen::Vector3d q = evaluate(ps, u, v) + d * nrm;
    GeomAPI_ProjectPointOnSurf proj(gp_Pnt(q.x(), q.y(), q.z()), r.surface);
    REQUIRE(proj.NbPoints() >= 1);
    worst = std::max(worst, std::abs(proj.LowerDistance() - std::abs(d)));
  }
  INFO("max |OCCT distance - |d|| = " << worst);
  // The distance is stationary at the foot point, so OCCT's parametric convergence tolerance
  // (~1e-9) enters only quadratically; 1e-9 L leaves room for the round-off of q itself.
  CHECK(worst <= 1e-9 * L);
}

TEST_CASE("Rotor 37 hold-out: OpenCASCADE on our IGES gives interlin's distances", "[occt]") {
  // The acceptance check: the IGES of the 7-section loft reads back into OCCT as one
  // B-spline face, and OCCT's own projector finds the same distances for the 6 x 198 withheld
  // points. Both are exact minimisations on the same surface; 1e-9 cm is far below the 1e-2 cm
  // being measured and far above round-off.
  const SectionSet set = read_sections(INTERLIN_DATA_DIR "/rotor37/sections.csv");
  const HoldoutResult h = holdout_study(set.sections, withheld_every(set.sections.size(), 2));
  test::TempDir tmp("occt-rotor37");
  const std::string path = tmp.file("rotor37_7.igs");
  write_iges(path, h.loft.surface); // unit mm: read back unscaled
  const OcctResult r = read_with_occt(path, "MM");
  REQUIRE(r.faces == 1);
  REQUIRE(!r.surface.IsNull());
  double worst = 0, occt_max = 0;
  for (size_t t = 0; t < h.test.size(); ++t) {
    const Eigen::MatrixXd& P = set.sections[h.test[t]].points;
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      GeomAPI_ProjectPointOnSurf proj(gp_Pnt(P(i, 0), P(i, 1), P(i, 2)), r.surface);
      REQUIRE(proj.NbPoints() > 0);
      worst = std::max(worst, std::abs(proj.LowerDistance() - h.distance[t](i)));
      occt_max = std::max(occt_max, proj.LowerDistance());
    }
  }
  INFO("max |d_occt - d_interlin| = " << worst << ", OCCT max distance " << occt_max);
  CHECK(worst < 1e-9);
  CHECK(occt_max == Approx(h.max).epsilon(0).margin(1e-9));
}
