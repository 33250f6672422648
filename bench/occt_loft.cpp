#include "occt_loft.h"

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepOffsetAPI_ThruSections.hxx>
#include <BRep_Tool.hxx>
#include <GeomAPI_Interpolate.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Precision.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>

#include <limits>
#include <memory>
#include <stdexcept>

namespace interlin::bench {

TopoDS_Wire occt_section_wire(const Eigen::MatrixXd& P) {
  const int n = static_cast<int>(P.rows());
  Handle(TColgp_HArray1OfPnt) pts = new TColgp_HArray1OfPnt(1, n);
  for (int i = 0; i < n; ++i)
    pts->SetValue(i + 1, gp_Pnt(P(i, 0), P(i, 1), P(i, 2)));
  GeomAPI_Interpolate interp(pts, /*PeriodicFlag=*/Standard_True, Precision::Confusion());
  interp.Perform();
  if (!interp.IsDone())
    throw std::runtime_error("GeomAPI_Interpolate failed");
  BRepBuilderAPI_MakeEdge edge(interp.Curve());
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
