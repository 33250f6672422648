#include "occt_loft.h"

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepOffsetAPI_ThruSections.hxx>
#include <BRep_Tool.hxx>
#include <GeomAPI_Interpolate.hxx>
#include <GeomAPI_ProjectPointOnCurve.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Precision.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>

#include <algorithm>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

namespace interlin::bench {

Handle(Geom_BSplineCurve) occt_section_curve(const Eigen::MatrixXd& P) {
  const int n = static_cast<int>(P.rows());
  Handle(TColgp_HArray1OfPnt) pts = new TColgp_HArray1OfPnt(1, n);
  for (int i = 0; i < n; ++i)
    pts->SetValue(i + 1, gp_Pnt(P(i, 0), P(i, 1), P(i, 2)));
  GeomAPI_Interpolate interp(pts, /*PeriodicFlag=*/Standard_True, Precision::Confusion());
  interp.Perform();
  if (!interp.IsDone())
    throw std::runtime_error("GeomAPI_Interpolate failed");
  return interp.Curve();
}

Handle(Geom_BSplineCurve) occt_curve(const BSplineCurve& C) {
  const int n = static_cast<int>(C.ctrl.rows());
  TColgp_Array1OfPnt poles(1, n);
  for (int i = 0; i < n; ++i)
    poles.SetValue(i + 1, gp_Pnt(C.ctrl(i, 0), C.ctrl(i, 1), C.ctrl(i, 2)));
  std::vector<double> knots;
  std::vector<int> mults;
  for (Eigen::Index i = 0; i < C.knots.size(); ++i)
    if (!knots.empty() && C.knots(i) == knots.back())
      ++mults.back();
    else {
      knots.push_back(C.knots(i));
      mults.push_back(1);
    }
  TColStd_Array1OfReal k(1, static_cast<int>(knots.size()));
  TColStd_Array1OfInteger m(1, static_cast<int>(knots.size()));
  for (size_t i = 0; i < knots.size(); ++i) {
    k.SetValue(static_cast<int>(i) + 1, knots[i]);
    m.SetValue(static_cast<int>(i) + 1, mults[i]);
  }
  return new Geom_BSplineCurve(poles, k, m, C.degree);
}

Eigen::VectorXd occt_curve_distances(const Handle(Geom_Curve) & C, const Eigen::MatrixXd& P) {
  // A dense polyline of the curve bounds every distance from above (to its spacing): it guards
  // against an extremum the projector misses.
  constexpr int kSamples = 20000;
  const double a = C->FirstParameter(), b = C->LastParameter();
  Eigen::MatrixXd X(kSamples + 1, 3);
  for (int j = 0; j <= kSamples; ++j) {
    const gp_Pnt q = C->Value(a + (b - a) * j / kSamples);
    X.row(j) << q.X(), q.Y(), q.Z();
  }
  GeomAPI_ProjectPointOnCurve proj;
  proj.Init(C, a, b);
  Eigen::VectorXd d(P.rows());
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    proj.Perform(gp_Pnt(P(i, 0), P(i, 1), P(i, 2)));
    const double sampled = (X.rowwise() - P.row(i)).rowwise().norm().minCoeff();
    d(i) = proj.NbPoints() > 0 ? std::min(proj.LowerDistance(), sampled) : sampled;
  }
  return d;
}

TopoDS_Wire occt_section_wire(const Eigen::MatrixXd& P) {
  BRepBuilderAPI_MakeEdge edge(occt_section_curve(P));
  if (!edge.IsDone())
    throw std::runtime_error("BRepBuilderAPI_MakeEdge failed");
  BRepBuilderAPI_MakeWire wire(edge.Edge());
  if (!wire.IsDone())
    throw std::runtime_error("BRepBuilderAPI_MakeWire failed");
  return wire.Wire();
}

TopoDS_Shape occt_thru_sections(const std::vector<TopoDS_Wire>& wires, bool check_compatibility) {
  BRepOffsetAPI_ThruSections loft(/*isSolid=*/Standard_False, /*ruled=*/Standard_False);
  loft.CheckCompatibility(check_compatibility);
  for (const TopoDS_Wire& w : wires)
    loft.AddWire(w);
  loft.Build();
  if (!loft.IsDone())
    throw std::runtime_error("BRepOffsetAPI_ThruSections failed");
  return loft.Shape();
}

Handle(Geom_Surface) occt_first_surface(const TopoDS_Shape& shape) {
  TopExp_Explorer ex(shape, TopAbs_FACE);
  if (!ex.More())
    throw std::runtime_error("OCCT shape without a face");
  return BRep_Tool::Surface(TopoDS::Face(ex.Current()));
}

Eigen::VectorXd occt_distances(const Handle(Geom_Surface) & S, const Eigen::MatrixXd& P) {
  double u0, u1, v0, v1;
  S->Bounds(u0, u1, v0, v1);
  GeomAPI_ProjectPointOnSurf proj;
  proj.Init(S, u0, u1, v0, v1);
  Eigen::VectorXd d(P.rows());
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    proj.Perform(gp_Pnt(P(i, 0), P(i, 1), P(i, 2)));
    d(i) = proj.IsDone() && proj.NbPoints() > 0 ? proj.LowerDistance()
                                                : std::numeric_limits<double>::quiet_NaN();
  }
  return d;
}

ParametricSurface occt_parametric(const Handle(Geom_Surface) & S) {
  ParametricSurface p;
  S->Bounds(p.domain(0), p.domain(1), p.domain(2), p.domain(3));
  p.closed_u = S->IsUPeriodic() || S->IsUClosed();
  const auto vec = [](const gp_XYZ& a) { return Eigen::Vector3d(a.X(), a.Y(), a.Z()); };
  // The adaptor caches the polynomial of the last span evaluated (BSplSLib_Cache): grid and
  // Newton evaluations mostly stay in one span.
  const auto A = std::make_shared<GeomAdaptor_Surface>(S);
  p.point = [A, vec](double u, double v) { return vec(A->Value(u, v).XYZ()); };
  p.derivatives = [A, vec](double u, double v) {
    gp_Pnt q;
    gp_Vec su, sv, suu, svv, suv;
    A->D2(u, v, q, su, sv, suu, svv, suv);
    return SurfaceJet{vec(q.XYZ()),   vec(su.XYZ()),  vec(sv.XYZ()),
                      vec(suu.XYZ()), vec(suv.XYZ()), vec(svv.XYZ())};
  };
  return p;
}

} // namespace interlin::bench
