#pragma once
// OpenCASCADE baseline loft shared by the OCCT benchmarks and occt_holdout: each blade section
// becomes a closed periodic B-spline through its points (GeomAPI_Interpolate, periodic), an edge
// and a wire; BRepOffsetAPI_ThruSections (isSolid = false, ruled = false, default settings)
// lofts the wires. Include only from OCCT translation units (heavy headers).
//
// One setting differs from the defaults: CheckCompatibility(false). With the default (true),
// BRepFill_CompatibleWires treats closed C1 wires by its "polar method", which needs each wire to
// be planar; the Rotor 37 sections are not (they lie on stream surfaces), and OCCT 7.6 throws
// "BRepFill :: profiles are inconsistent". The sections already correspond (same point count,
// orientation and start point, one edge each), so the compatibility pass has nothing to do.

#include "interlin/reconstruction/loft/closest_point.h"
#include "interlin/splines/bspline_curve.h"

#include <Eigen/Core>

#include <Geom_BSplineCurve.hxx>
#include <Geom_Surface.hxx>
#include <TopoDS_Shape.hxx>
#include <TopoDS_Wire.hxx>

#include <vector>

namespace interlin::bench {

// The periodic interpolating cubic B-spline through the rows of P (#P by 3, closing edge implicit,
// no repeated point): GeomAPI_Interpolate, periodic, its own chord-length parameters.
// Throws std::runtime_error if OCCT's interpolation fails.
Handle(Geom_BSplineCurve) occt_section_curve(const Eigen::MatrixXd& P);

// interlin's clamped (non-periodic) B-spline curve C (3-D) as an OCCT curve, the same geometry.
Handle(Geom_BSplineCurve) occt_curve(const BSplineCurve& C);

// Distances of the rows of P (#P by 3) to C by GeomAPI_ProjectPointOnCurve (every extremum, the
// lowest kept), or the distance to a polyline of 20000 points on C where that is lower (an
// extremum the projector missed).
Eigen::VectorXd occt_curve_distances(const Handle(Geom_Curve) & C, const Eigen::MatrixXd& P);

// Closed wire of one section.
// Inputs:  P  #P by 3 profile points (closing edge implicit, no repeated point)
// Output:  a wire with one edge on occt_section_curve(P)
// Throws std::runtime_error if OCCT's interpolation or edge construction fails.
TopoDS_Wire occt_section_wire(const Eigen::MatrixXd& P);

// ThruSections of the wires, in order (isSolid = false, ruled = false, pres3d = 1e-6,
// CheckCompatibility(check_compatibility), everything else default).
// Throws std::runtime_error if the build fails, Standard_Failure if OCCT throws.
TopoDS_Shape occt_thru_sections(const std::vector<TopoDS_Wire>& wires,
                                bool check_compatibility = false);

// The surface of the first face of a shape (a ThruSections loft has one face).
// Throws std::runtime_error for a shape without faces.
Handle(Geom_Surface) occt_first_surface(const TopoDS_Shape& shape);

// Distances of the rows of P (#P by 3) to S by GeomAPI_ProjectPointOnSurf over the whole
// parameter domain (every extremum, the lowest kept); NaN where the projector finds none.
Eigen::VectorXd occt_distances(const Handle(Geom_Surface) & S, const Eigen::MatrixXd& P);

// S as a ParametricSurface (OCCT's D0 and D2; u wraps when S is u-periodic or u-closed), so that
// interlin's project_to_surface measures OCCT's surface with the same code as interlin's own.
// S is held by the returned functions.
ParametricSurface occt_parametric(const Handle(Geom_Surface) & S);

} // namespace interlin::bench
