#include "occt_loft.h"

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepOffsetAPI_ThruSections.hxx>
#include <GeomAPI_Interpolate.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Precision.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <gp_Pnt.hxx>

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

} // namespace interlin::bench
