// Independent check of write_step: OpenCASCADE's STEP reader (STEPControl_Reader) must turn our
// file into one face (a surface) or one valid solid (with caps), whose B-spline surfaces evaluate
// to interlin's own points, with the length unit applied as written, and whose volume
// (BRepGProp) is the enclosed volume known in closed form or measured on our meshes. Built only
// when OpenCASCADE is found.
//
// Point tolerance as in test_occt_iges.cpp: both sides evaluate the same polynomial pieces from
// the same doubles (every knot and pole is written exactly), so they differ by round-off only;
// 1e-12 x the largest coordinate is ~10 orders of magnitude below any real error.

#include "interlin/reconstruction/io/section_csv.h"
#include "interlin/reconstruction/io/step.h"
#include "interlin/reconstruction/loft/end_caps.h"
#include "interlin/reconstruction/loft/loft.h"
#include "interlin/reconstruction/meshing/mesh_check.h"
#include "interlin/reconstruction/meshing/surface_mesh.h"
#include "interlin/splines/bspline_surface.h"

#include "support/test_support.h"
#include "support/test_surfaces.h"

#include <catch2/catch.hpp>

#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <Geom_BSplineSurface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_Printer.hxx>
#include <STEPControl_Reader.hxx>
#include <TopAbs_ShapeEnum.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Pnt.hxx>

#include <cmath>
#include <random>
#include <string>
#include <vector>

using namespace interlin;

namespace {

struct OcctShape {
  TopoDS_Shape shape;
  int faces = 0, solids = 0, shells = 0;
  std::vector<Handle(Geom_BSplineSurface)> surfaces; // of the faces, in file order
};

// Reads `path` with OCCT's STEP reader, lengths converted to millimetres.
OcctShape read_step(const std::string& path) {
  for (Message_SequenceOfPrinters::Iterator it(Message::DefaultMessenger()->Printers()); it.More();
       it.Next())
    it.Value()->SetTraceLevel(Message_Fail);
  STEPControl_Reader reader;
  REQUIRE(Interface_Static::SetCVal("xstep.cascade.unit", "MM"));
  REQUIRE(reader.ReadFile(path.c_str()) == IFSelect_RetDone);
  reader.TransferRoots();
  REQUIRE(reader.NbShapes() >= 1);
  OcctShape r;
  r.shape = reader.OneShape();
  for (TopExp_Explorer ex(r.shape, TopAbs_SOLID); ex.More(); ex.Next())
    ++r.solids;
  for (TopExp_Explorer ex(r.shape, TopAbs_SHELL); ex.More(); ex.Next())
    ++r.shells;
  for (TopExp_Explorer ex(r.shape, TopAbs_FACE); ex.More(); ex.Next()) {
    ++r.faces;
    r.surfaces.push_back(
        Handle(Geom_BSplineSurface)::DownCast(BRep_Tool::Surface(TopoDS::Face(ex.Current()))));
  }
  return r;
}

// BRepGProp's adaptive integration to 1e-10 (its fixed-order default is off by 10 % on faces
// with hundreds of knot spans, measured on the Rotor 37 solid).
double volume_of(const TopoDS_Shape& shape) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(shape, props, 1e-10);
  return props.Mass();
}

// Largest |OCCT point - scale x interlin point| over a lattice of parameters (with the knots).
double max_point_difference(const BSplineSurface& s, const Handle(Geom_BSplineSurface) & occt,
                            double scale = 1) {
  const PiecewiseSurface ps = to_piecewise(s);
  const Eigen::Vector4d d = domain(ps);
  double worst = 0;
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j) {
      const double u = d(0) + (d(1) - d(0)) * i / 40.0, v = d(2) + (d(3) - d(2)) * j / 40.0;
      const gp_Pnt p = occt->Value(u, v);
      worst = std::max(worst,
                       (Eigen::Vector3d(p.X(), p.Y(), p.Z()) - scale * evaluate(ps, u, v)).norm());
    }
  return worst;
}

// Area enclosed by the planar ring: Green's theorem 1/2 closed integral of (x y' - y x'), exact by
// 4-point Gauss per span (the integrand has degree 5).
double ring_area() {
  const BSplineCurve ring = test::clamped_ring(0.3);
  const double g[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                       0.8611363115940526};
  const double w[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                       0.3478548451374538};
  double area = 0;
  for (Eigen::Index k = 3; k < ring.ctrl.rows(); ++k) {
    const double a = ring.knots(k), b = ring.knots(k + 1);
    for (int q = 0; q < 4; ++q) {
      Eigen::VectorXd u(1);
      u(0) = 0.5 * (a + b) + 0.5 * (b - a) * g[q];
      const Eigen::MatrixXd p = evaluate(ring, u), d = evaluate(ring, u, 1);
      area += 0.25 * (b - a) * w[q] * (p(0, 0) * d(0, 1) - p(0, 1) * d(0, 0));
    }
  }
  return std::abs(area);
}

std::array<StepCap, 2> caps_of(const BSplineSurface& s) {
  return {end_cap(s, false), end_cap(s, true)};
}

// Signed volume of triangles T into V about `o` (sum of (a-o).(b-o)x(c-o) / 6).
double signed_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, const Eigen::Vector3d& o) {
  double vol = 0;
  for (Eigen::Index f = 0; f < T.rows(); ++f) {
    const Eigen::Vector3d a = V.row(T(f, 0)).transpose() - o, b = V.row(T(f, 1)).transpose() - o,
                          c = V.row(T(f, 2)).transpose() - o;
    vol += a.dot(b.cross(c)) / 6;
  }
  return vol;
}

Eigen::Vector3d area_vector(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  for (Eigen::Index f = 0; f < T.rows(); ++f) {
    const Eigen::Vector3d p = (V.row(T(f, 1)) - V.row(T(f, 0))).transpose(),
                          q = (V.row(T(f, 2)) - V.row(T(f, 0))).transpose();
    a += p.cross(q);
  }
  return a;
}

struct SolidVolumes {
  double flat = 0;  // lateral mesh + the flat fills of surface_mesh(cap) (the CLI's --cap mesh)
  double ruled = 0; // lateral mesh + each ruled StepCap sampled n x n/4 (the STEP solid's faces)
};

// Volumes of the capped loft meshed with nu = n, nv = n / 4: with surface_mesh's flat caps, and
// with the open lateral mesh closed by triangulations of the ruled caps (oriented like the flat
// cap on the same loop; their edge points lie on the same loop, so the two meshes close it alike
// up to chords).
SolidVolumes mesh_volumes(const BSplineSurface& s, const std::array<StepCap, 2>& caps, int n) {
  SurfaceMeshOptions mo;
  mo.nu = n;
  mo.nv = n / 4;
  Eigen::MatrixXd V, Vo;
  Eigen::MatrixXi F, Fo;
  surface_mesh(to_piecewise(s), mo, Vo, Fo);
  mo.cap = true;
  surface_mesh(to_piecewise(s), mo, V, F);
  const Eigen::Vector3d o = (0.5 * (V.colwise().minCoeff() + V.colwise().maxCoeff())).transpose();
  SolidVolumes out;
  out.flat = signed_volume(V, F, o);
  const double lateral = signed_volume(Vo, Fo, o);
  REQUIRE(F.rows() == Fo.rows() + 2 * (n - 2)); // the caps follow the lateral faces
  out.ruled = lateral;
  for (int k = 0; k < 2; ++k) {
    const Eigen::MatrixXi flat = F.middleRows(Fo.rows() + k * (n - 2), n - 2);
    const int m = n / 2;
    const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(m + 1, 0, 1);
    const Eigen::MatrixXd P = evaluate_grid(to_piecewise(caps[size_t(k)].patch), t, t);
    Eigen::MatrixXi T(2 * m * m, 3);
    for (int j = 0, f = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const int a = i + (m + 1) * j, b = a + 1, c = a + m + 1, d = c + 1;
        T.row(f++) << a, b, d;
        T.row(f++) << a, d, c;
      }
    if (area_vector(P, T).dot(area_vector(V, flat)) < 0)
      T.col(1).swap(T.col(2));
    out.ruled += signed_volume(P, T, o);
  }
  return out;
}

} // namespace

TEST_CASE("OpenCASCADE reads our STEP surface as one B-spline face with the same geometry",
          "[occt][step]") {
  test::TempDir tmp("occt-step");
  const double size = 100;
  const BSplineSurface s = test::random_bicubic(8, 6, size, 4242u, 2.0);
  const std::string path = tmp.file("bicubic.step");
  write_step(path, s);
  const OcctShape r = read_step(path);
  REQUIRE(r.faces == 1);
  CHECK(r.solids == 0);
  REQUIRE(!r.surfaces[0].IsNull());
  CHECK(r.surfaces[0]->UDegree() == 3);
  CHECK(r.surfaces[0]->VDegree() == 3);
  CHECK(r.surfaces[0]->NbUPoles() == s.num_u);
  CHECK(r.surfaces[0]->NbVPoles() == s.num_v);
  CHECK_FALSE(r.surfaces[0]->IsURational()); // polynomial: written without weights
  CHECK_FALSE(r.surfaces[0]->IsVRational());
  const double diff = max_point_difference(s, r.surfaces[0]);
  INFO("max |OCCT - interlin| = " << diff);
  CHECK(diff <= 1e-12 * size);
}

TEST_CASE("OpenCASCADE applies the STEP length unit as written", "[occt][step]") {
  test::TempDir tmp("occt-step-units");
  const BSplineSurface s = test::random_bicubic(8, 6, 2, 99u, 2.0);
  const struct {
    LengthUnit unit;
    double mm;
  } units[] = {
      {LengthUnit::mm, 1}, {LengthUnit::cm, 10}, {LengthUnit::m, 1000}, {LengthUnit::inch, 25.4}};
  for (const auto& u : units) {
    const std::string path = tmp.file("unit.step");
    StepOptions o;
    o.unit = u.unit;
    write_step(path, s, nullptr, o);
    const OcctShape r = read_step(path); // the reader converts to millimetres
    INFO("unit factor " << u.mm);
    REQUIRE(r.faces == 1);
    REQUIRE(!r.surfaces[0].IsNull());
    CHECK(max_point_difference(s, r.surfaces[0], u.mm) <= 1e-12 * 2 * u.mm);
  }
}

TEST_CASE("A capped closed tube is one valid solid of the closed-form volume", "[occt][step]") {
  test::TempDir tmp("occt-step-tube");
  const double exact = 10 * ring_area() * (1 + 0.05 - 0.02 / 3);
  for (int pv : {1, 3}) {
    const BSplineSurface s = test::swept_tube(pv);
    const std::array<StepCap, 2> caps = caps_of(s);
    for (const bool capped : {false, true}) {
      const std::string path = tmp.file("tube.step");
      write_step(path, s, capped ? &caps : nullptr);
      const OcctShape r = read_step(path);
      INFO("degree_v " << pv << (capped ? ", capped" : ""));
      REQUIRE(r.faces == (capped ? 3 : 1));
      CHECK(r.solids == (capped ? 1 : 0));
      REQUIRE(!r.surfaces[0].IsNull());
      CHECK(max_point_difference(s, r.surfaces[0]) <= 1e-12 * 10);
      if (!capped)
        continue;
      CHECK(BRepCheck_Analyzer(r.shape).IsValid());
      const double v = volume_of(r.shape);
      INFO("OCCT volume " << v << ", exact " << exact);
      CHECK(v == Approx(exact).epsilon(1e-9));
    }
  }
}

TEST_CASE("Rotor 37 capped loft: one valid solid whose volume is the capped mesh's",
          "[occt][step]") {
  const SectionSet set = read_sections(INTERLIN_DATA_DIR "/rotor37/sections.csv");
  const LoftResult loft = loft_sections(set.sections);
  const BSplineSurface& s = loft.surface;
  const std::array<StepCap, 2> caps = caps_of(s);
  test::TempDir tmp("occt-step-rotor37");
  const std::string path = tmp.file("rotor37.step");
  write_step(path, s, &caps);
  const OcctShape r = read_step(path);
  REQUIRE(r.faces == 3);
  REQUIRE(r.solids == 1);
  CHECK(BRepCheck_Analyzer(r.shape).IsValid());
  REQUIRE(!r.surfaces[0].IsNull());
  const double size = s.ctrl.cwiseAbs().maxCoeff();
  CHECK(max_point_difference(s, r.surfaces[0]) <= 1e-12 * size);
  const double v = volume_of(r.shape);
  // The CLI's --cap mesh (flat constrained-Delaunay fills of the end loops) and the lateral mesh
  // closed by the two ruled caps themselves, at nu = n, nv = n / 4 for three n.
  std::vector<double> h, flat_err, ruled_err;
  std::vector<SolidVolumes> m;
  for (int n : {200, 400, 800}) {
    m.push_back(mesh_volumes(s, caps, n));
    h.push_back(1.0 / n);
    flat_err.push_back(std::abs(m.back().flat - v) / v);
    ruled_err.push_back(std::abs(m.back().ruled - v) / v);
    WARN("n " << n << ": OCCT solid " << v << ", mesh with flat caps " << m.back().flat
              << " (rel diff " << (m.back().flat - v) / v << "), with the ruled caps "
              << m.back().ruled << " (rel diff " << (m.back().ruled - v) / v << ")");
  }
  // The same solid (lateral face + ruled caps): flat triangles through points of smooth surfaces
  // make an O(h^2) volume error (chords), so the mesh converges to OCCT's volume at order 2 and
  // the Richardson extrapolation (4 V(h/2) - V(h)) / 3 removes that term: measured 1.9e-6 of the
  // volume (OCCT integrates to 1e-10); 1e-5 leaves room for the next order.
  CHECK(test::fitted_order(h, ruled_err) > 1.7);
  const double flat = (4 * m[2].flat - m[1].flat) / 3, ruled = (4 * m[2].ruled - m[1].ruled) / 3;
  INFO("extrapolated: flat caps " << flat << ", ruled caps " << ruled << ", OCCT " << v);
  CHECK(std::abs(ruled - v) < 1e-5 * v);
  // The --cap mesh: its flat fills and the ruled caps are different surfaces on the same
  // non-planar end loop (hub and casing are surfaces of revolution); the lens between them is
  // what remains after extrapolation, measured -2.0e-5 of the volume (-3.1e-5 at n = 800 before
  // extrapolation). Tolerance 5e-5: the capped mesh's volume equals the STEP solid's to 0.005 %.
  CHECK(std::abs(flat - v) < 5e-5 * v);
  CHECK(flat_err.back() < 5e-5);
}
