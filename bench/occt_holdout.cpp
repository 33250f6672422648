// OpenCASCADE hold-out baseline and IGES read-back check (docs/benchmarks.md).
//
// 1. OCCT: BRepOffsetAPI_ThruSections (occt_loft.h) of the Rotor 37 sections 0, 2, ..., 12;
//    distance of every point of the withheld sections 1, 3, ..., 11 to the lofted surface by
//    GeomAPI_ProjectPointOnSurf, and of the 7 training sections (OCCT's own reproduction).
// 2. interlin: holdout_study with withheld_every(13, 2); the lofted surface written with
//    write_iges (unit mm, OCCT's default, so nothing is scaled), read back by IGESControl_Reader
//    (exactly one face on a Geom_BSplineSurface required), and the same distances computed by
//    OCCT's projector on the read-back surface, compared with interlin's own.
// Global-minimum check for every projection: the distance must not exceed the smallest distance
// to a dense grid of surface points (an upper bound of the true minimum); a sample is also
// checked with BRepExtrema_DistShapeShape. Prints Markdown tables; exit status 1 if a check fails.
//
// Usage: occt_holdout [sections.csv]   (default: data/rotor37/sections.csv)

#include "occt_loft.h"

#include "interlin/reconstruction/io/iges.h"
#include "interlin/reconstruction/io/section_csv.h"
#include "interlin/reconstruction/loft/holdout.h"
#include "interlin/splines/bspline_surface.h"

#include <Eigen/Cholesky>
#include <Eigen/LU> // determinant

#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
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
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

using namespace interlin;
using Eigen::Index;

int failures = 0;

void check(bool ok, const std::string& what) {
  if (!ok) {
    std::printf("CHECK FAILED: %s\n", what.c_str());
    ++failures;
  }
}

struct Face {
  int faces = 0;
  TopoDS_Face face;
  Handle(Geom_Surface) surface;
};

Face first_face(const TopoDS_Shape& shape) {
  Face f;
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next())
    if (f.faces++ == 0) {
      f.face = TopoDS::Face(ex.Current());
      f.surface = BRep_Tool::Surface(f.face);
    }
  return f;
}

// Independent exact distance, for the global-minimum check: Newton's method on
// f(u,v) = |S(u,v) - p|^2 / 2 with OCCT's second derivatives (Gauss-Newton step where the Hessian
// is not positive definite; v clamped to its bounds; u continued across the seam of a closed
// surface, clamped otherwise), started from each of the `starts` grid samples (of nu x nv)
// nearest to p; the smallest distance reached. Several starts because at the thin leading and
// trailing edges the nearest sample can lie on the other side of the blade.
Eigen::VectorXd grid_newton_distances(const Handle(Geom_Surface) & S, const Eigen::MatrixXd& P,
                                      int nu, int nv, int starts) {
  double u0, u1, v0, v1;
  S->Bounds(u0, u1, v0, v1);
  const bool wrap = S->IsUPeriodic() || S->IsUClosed(); // closed: continue across the seam
  Eigen::Matrix3Xd G(3, static_cast<Index>(nu) * nv);
  Eigen::Matrix2Xd UV(2, G.cols());
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const Index c = i + static_cast<Index>(nu) * j;
      UV.col(c) = Eigen::Vector2d(u0 + (u1 - u0) * i / (nu - 1), v0 + (v1 - v0) * j / (nv - 1));
      const gp_Pnt q = S->Value(UV(0, c), UV(1, c));
      G.col(c) = Eigen::Vector3d(q.X(), q.Y(), q.Z());
    }
  auto vec = [](const gp_Vec& a) { return Eigen::Vector3d(a.X(), a.Y(), a.Z()); };
  // Newton from (u, v); returns the distance at the point it converges to.
  auto newton = [&](const Eigen::Vector3d& p, double u, double v) {
    for (int it = 0; it < 50; ++it) {
      gp_Pnt q;
      gp_Vec su, sv, suu, svv, suv;
      S->D2(u, v, q, su, sv, suu, svv, suv);
      const Eigen::Vector3d r = Eigen::Vector3d(q.X(), q.Y(), q.Z()) - p;
      const Eigen::Vector3d Su = vec(su), Sv = vec(sv);
      const Eigen::Vector2d g(Su.dot(r), Sv.dot(r));
      Eigen::Matrix2d H; // Hessian of f
      H(0, 0) = Su.dot(Su) + vec(suu).dot(r);
      H(0, 1) = H(1, 0) = Su.dot(Sv) + vec(suv).dot(r);
      H(1, 1) = Sv.dot(Sv) + vec(svv).dot(r);
      if (!(H(0, 0) > 0 && H.determinant() > 0)) { // not positive definite: Gauss-Newton
        H(0, 0) = Su.dot(Su);
        H(0, 1) = H(1, 0) = Su.dot(Sv);
        H(1, 1) = Sv.dot(Sv);
      }
      const Eigen::Vector2d step = -H.ldlt().solve(g);
      u += step(0);
      v = std::clamp(v + step(1), v0, v1);
      u = wrap ? u0 + std::fmod(std::fmod(u - u0, u1 - u0) + (u1 - u0), u1 - u0)
               : std::clamp(u, u0, u1);
      if (std::abs(step(0)) <= 1e-15 * (u1 - u0) && std::abs(step(1)) <= 1e-15 * (v1 - v0))
        break;
    }
    const gp_Pnt q = S->Value(u, v);
    return (Eigen::Vector3d(q.X(), q.Y(), q.Z()) - p).norm();
  };
  Eigen::VectorXd d(P.rows());
  std::vector<Index> order(static_cast<size_t>(G.cols()));
  for (Index k = 0; k < P.rows(); ++k) {
    const Eigen::Vector3d p = P.row(k).transpose();
    const Eigen::VectorXd d2 = (G.colwise() - p).colwise().squaredNorm().transpose();
    for (Index c = 0; c < G.cols(); ++c)
      order[static_cast<size_t>(c)] = c;
    std::partial_sort(order.begin(), order.begin() + starts, order.end(),
                      [&](Index a, Index b) { return d2(a) < d2(b); });
    d(k) = std::sqrt(d2(order[0]));
    for (int s = 0; s < starts; ++s) {
      const Index c = order[static_cast<size_t>(s)];
      d(k) = std::min(d(k), newton(p, UV(0, c), UV(1, c)));
    }
  }
  return d;
}

// BRepExtrema_DistShapeShape between a vertex at p and the face.
double brep_distance(const TopoDS_Face& face, const Eigen::RowVector3d& p) {
  BRepExtrema_DistShapeShape dss(BRepBuilderAPI_MakeVertex(gp_Pnt(p(0), p(1), p(2))).Vertex(),
                                 face);
  return dss.IsDone() ? dss.Value() : std::numeric_limits<double>::quiet_NaN();
}

Eigen::MatrixXd stack(const std::vector<Section>& all, const std::vector<size_t>& which) {
  Index rows = 0;
  for (size_t i : which)
    rows += all[i].points.rows();
  Eigen::MatrixXd P(rows, 3);
  Index r = 0;
  for (size_t i : which) {
    P.middleRows(r, all[i].points.rows()) = all[i].points;
    r += all[i].points.rows();
  }
  return P;
}

double rms(const Eigen::VectorXd& d) {
  return std::sqrt(d.squaredNorm() / static_cast<double>(d.size()));
}

struct Measured {
  Eigen::VectorXd test, train, newton;
  double brep_max_diff = 0;
  int brep_samples = 0;
};

// Every distance and check for one surface (test = withheld points, train = lofted points).
Measured measure(const std::string& name, const Face& f, const Eigen::MatrixXd& test,
                 const Eigen::MatrixXd& train) {
  Measured m;
  m.test = bench::occt_distances(f.surface, test);
  m.train = bench::occt_distances(f.surface, train);
  check(m.test.allFinite() && m.train.allFinite(), name + ": the projector found every point");
  m.newton = grid_newton_distances(f.surface, test, 2000, 100, 16);
  // Global minimum: the independent search must not find a closer point (1e-12 cm: round-off of
  // distances of ~1e-2 cm computed from coordinates of ~20 cm).
  const double excess = (m.test - m.newton).maxCoeff();
  check(excess <= 1e-12, name + ": the grid + Newton search finds points closer by " +
                             std::to_string(excess) + " cm (projector: local, not global minimum)");
  for (Index i = 0; i < test.rows(); i += 11, ++m.brep_samples)
    m.brep_max_diff =
        std::max(m.brep_max_diff, std::abs(brep_distance(f.face, test.row(i)) - m.test(i)));
  // 1e-9 cm: both are exact extrema on the same face, so they differ by round-off unless one
  // of them is a different (non-global) extremum, which here would be >= 1e-6 cm away.
  check(m.brep_max_diff <= 1e-9,
        name + ": BRepExtrema_DistShapeShape disagrees with the projector");
  return m;
}

void print_surface(const char* name, const Face& f) {
  Handle(Geom_BSplineSurface) b = Handle(Geom_BSplineSurface)::DownCast(f.surface);
  if (b.IsNull()) {
    std::printf("%s: %d face(s), surface %s\n", name, f.faces, f.surface->DynamicType()->Name());
    return;
  }
  std::printf("%s: %d face(s), Geom_BSplineSurface degree %d x %d, poles %d x %d, "
              "knots %d x %d, u periodic %d, rational %d\n",
              name, f.faces, b->UDegree(), b->VDegree(), b->NbUPoles(), b->NbVPoles(),
              b->NbUKnots(), b->NbVKnots(), b->IsUPeriodic() ? 1 : 0,
              (b->IsURational() || b->IsVRational()) ? 1 : 0);
}

int run(const std::string& path) {
  for (Message_SequenceOfPrinters::Iterator it(Message::DefaultMessenger()->Printers()); it.More();
       it.Next())
    it.Value()->SetTraceLevel(Message_Fail);

  const std::vector<Section> all = read_sections(path).sections;
  const std::vector<size_t> withheld = withheld_every(all.size(), 2);
  std::vector<size_t> train;
  for (size_t i = 0; i < all.size(); ++i)
    if (std::find(withheld.begin(), withheld.end(), i) == withheld.end())
      train.push_back(i);
  const Eigen::MatrixXd Ptest = stack(all, withheld), Ptrain = stack(all, train);
  std::printf("%s: %zu sections; lofted %zu, withheld %zu (%ld points)\n\n", path.c_str(),
              all.size(), train.size(), withheld.size(), static_cast<long>(Ptest.rows()));

  // 1. OCCT ThruSections.
  std::vector<TopoDS_Wire> wires;
  for (size_t i : train)
    wires.push_back(bench::occt_section_wire(all[i].points));
  try {
    bench::occt_thru_sections(wires, /*check_compatibility=*/true);
    std::printf("OCCT ThruSections with the default CheckCompatibility(true): built\n");
  } catch (const Standard_Failure& e) {
    std::printf("OCCT ThruSections with the default CheckCompatibility(true) fails: %s; "
                "using CheckCompatibility(false)\n",
                e.GetMessageString());
  }
  const Face occt = first_face(bench::occt_thru_sections(wires));
  print_surface("OCCT ThruSections", occt);
  check(occt.faces == 1, "OCCT ThruSections: one face");
  const Measured mo = measure("OCCT ThruSections", occt, Ptest, Ptrain);

  // 2. interlin, and its IGES read back by OCCT.
  const HoldoutResult h = holdout_study(all, withheld);
  for (const std::string& note : h.loft.notes)
    std::printf("interlin loft note: %s\n", note.c_str());
  const std::string iges = (std::filesystem::temp_directory_path() /
                            ("interlin_occt_holdout_" + std::to_string(::getpid()) + ".igs"))
                               .string();
  write_iges(iges, h.loft.surface); // unit mm: OCCT's default xstep.cascade.unit, no scaling
  IGESControl_Reader reader;
  check(Interface_Static::SetCVal("xstep.cascade.unit", "MM"), "xstep.cascade.unit = MM");
  const bool read_ok = reader.ReadFile(iges.c_str()) == IFSelect_RetDone;
  std::filesystem::remove(iges);
  check(read_ok, "IGESControl_Reader reads our file");
  reader.TransferRoots();
  const Face ours = first_face(reader.OneShape());
  print_surface("interlin via IGES", ours);
  Handle(Geom_BSplineSurface) b = Handle(Geom_BSplineSurface)::DownCast(ours.surface);
  check(ours.faces == 1 && !b.IsNull(),
        "IGES read-back: exactly one face on a Geom_BSplineSurface");
  if (failures)
    return 1;
  // Same surface, same parameters: OCCT's evaluation of the read-back surface against interlin's
  // on a 400 x 40 grid of our parameter domain (round-off only if knots, control points, index
  // order and parameter range survived the trip; OCCT may re-express a closed surface as
  // u-periodic, which changes the representation but not the map (u, v) -> point).
  const PiecewiseSurface PS = to_piecewise(h.loft.surface);
  const Eigen::Vector4d dom = domain(PS);
  double eval_diff = 0;
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 400; ++i) {
      const double u = dom(0) + (dom(1) - dom(0)) * i / 399.0,
                   v = dom(2) + (dom(3) - dom(2)) * j / 39.0;
      const gp_Pnt q = b->Value(u, v);
      eval_diff =
          std::max(eval_diff, (Eigen::Vector3d(q.X(), q.Y(), q.Z()) - evaluate(PS, u, v)).norm());
    }
  double ou0, ou1, ov0, ov1;
  b->Bounds(ou0, ou1, ov0, ov1);
  std::printf("IGES read-back: OCCT domain [%.17g, %.17g] x [%.17g, %.17g], interlin [%.17g, "
              "%.17g] x [%.17g, %.17g]; max |S_occt(u,v) - S_interlin(u,v)| on a 400 x 40 grid = "
              "%.3g cm\n\n",
              ou0, ou1, ov0, ov1, dom(0), dom(1), dom(2), dom(3), eval_diff);
  // 1e-12 x 30 cm (coordinates are below 30 cm): both sides evaluate the same polynomials from the
  // same doubles, by different algorithms (de Boor vs Horner); any real error is O(1 cm).
  check(eval_diff <= 1e-12 * 30, "IGES read-back evaluates like interlin's surface");
  const Measured mi = measure("interlin via IGES", ours, Ptest, Ptrain);

  Eigen::VectorXd own(Ptest.rows());
  for (size_t t = 0, r = 0; t < h.distance.size(); r += h.distance[t].size(), ++t)
    own.segment(static_cast<Index>(r), h.distance[t].size()) = h.distance[t];
  const double agree = (own - mi.test).cwiseAbs().maxCoeff();
  check(agree <= 1e-9, "interlin's own distances match OCCT on the IGES surface to 1e-9");
  check(std::abs(own.maxCoeff() - h.max) <= 1e-15 && std::abs(rms(own) - h.rms) <= 1e-15,
        "holdout_study max/rms");

  std::printf("| surface | withheld max [cm] | withheld rms [cm] | training max [cm] | "
              "max abs(grid+Newton - projector) [cm] | max abs(BRepExtrema - projector) [cm] |\n");
  std::printf("|---|---|---|---|---|---|\n");
  auto row = [](const char* name, const Measured& m) {
    std::printf("| %s | %.5g | %.5g | %.2g | %.2g | %.2g (%d points) |\n", name, m.test.maxCoeff(),
                rms(m.test), m.train.maxCoeff(), (m.newton - m.test).cwiseAbs().maxCoeff(),
                m.brep_max_diff, m.brep_samples);
  };
  row("OCCT ThruSections (7 sections)", mo);
  row("interlin loft, read back from IGES, OCCT projector", mi);
  std::printf("| interlin loft, interlin project_to_surface (holdout_study) | %.5g | %.5g | %.2g "
              "| | |\n\n",
              h.max, h.rms, h.loft.max_deviation);
  std::printf("max |interlin distance - OCCT distance on the IGES surface| = %.3g cm over %ld "
              "withheld points\n",
              agree, static_cast<long>(own.size()));
  std::printf("%s\n", failures ? "SOME CHECKS FAILED" : "all checks passed");
  return failures ? 1 : 0;
}

} // namespace

int main(int argc, char** argv) {
  try {
    return run(argc > 1 ? argv[1] : INTERLIN_DATA_DIR "/rotor37/sections.csv");
  } catch (const Standard_Failure& e) {
    std::fprintf(stderr, "occt_holdout: OpenCASCADE: %s\n", e.GetMessageString());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "occt_holdout: %s\n", e.what());
  }
  return 1;
}
