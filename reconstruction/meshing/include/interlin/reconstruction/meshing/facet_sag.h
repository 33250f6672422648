#pragma once
// How far a mesh's boundary facets lie from the surface F = 0 they span, and the volume between
// them: facets are chords of a curved surface (corners on F = 0, the rest inside a convex part
// and outside a concave one), so a mesh of a surface that bends within a few cells is smaller or
// larger than its body by this volume (a rod 3 cells across: 4-11 %), while every node is on F = 0.

#include "interlin/interflatation/implicit_function.h"

#include <Eigen/Core>

namespace interlin {

struct FacetSag {
  // The integral over the facets of the signed distance d from the facet to F = 0 along its
  // outward normal (d > 0 where the body reaches beyond the facet): the body's volume is about
  // the mesh's plus this.
  double volume = 0;
  double max_distance = 0; // largest |d| at a sample
  double area = 0;         // facet area measured
  // Facet area not measured: samples whose outward normal lies more than 60 degrees from -grad F
  // (a facet across a sharp edge or a thin wall, where the chord is no height field over F = 0)
  // or with no zero within the facet's diameter.
  double skipped_area = 0;
};

// The facets' sag by quadrature of the distance along each sample's normal: a triangle's three
// edge midpoints with weights A / 3 (exact for a quadratic surface over a planar facet whose
// corners are on it); a bilinear quadrilateral's 3 x 3 Simpson points (corners, edge midpoints and
// centre, weights (1, 4, 1) x (1, 4, 1) / 36 times its area element). The distance is the root of
// F along the normal by seed 003's findBorder (project_along: steps of an eighth of the facet's
// diameter up to the diameter, then roots_on_segments' regula falsi).
// Inputs:  f (value; gradient when available, else central differences), V #V by 3, B #B by 3
//          triangles or #B by 4 quadrilaterals (counter-clockwise from outside), threads (0: all
//          cores; the result does not depend on it)
// Output:  the sag volume, the largest distance and the areas measured and skipped
// See also: volume_mesh, implicit_mesh, uncovered_volume
FacetSag facet_sag(const ImplicitFunction& f, const Eigen::MatrixXd& V, const Eigen::MatrixXi& B,
                   int threads = 0);

// The cell at which the sag of a mesh at cell h would be `target` of the body's volume, from the
// measured fraction, the sag shrinking as h^order (2 on a smooth surface and at a chamfered edge
// alike), 10 % smaller for the constant's variation; h when the fraction is within target.
double cell_for_sag(double h, double fraction, double target, double order = 2);

} // namespace interlin
