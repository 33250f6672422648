// Python bindings of splines/: B-spline curves and bases, seed 001 Theorem 1 (explicit B-splines)
// and Theorem 2 (minimal-jump quadratic spline), curve fitting.
#include "bindings.h"

#include "interlin/splines/approximate_curve.h"
#include "interlin/splines/bspline_curve.h"
#include "interlin/splines/closed_section_curve.h"
#include "interlin/splines/cox_de_boor.h"
#include "interlin/splines/explicit_bspline.h"
#include "interlin/splines/interpolate_curve.h"
#include "interlin/splines/knot_insertion.h"
#include "interlin/splines/knots.h"
#include "interlin/splines/min_jump_quadratic.h"
#include "interlin/splines/parameterization.h"
#include "interlin/splines/spline_basis.h"

#include <optional>
#include <vector>

namespace interlin::python {

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

// The dense (#u, #ctrl) matrix of the deriv-th derivatives of all basis functions at u.
MatrixXd basis_matrix(const SplineBasis& b, const VectorXd& u, int deriv) {
  std::vector<Index> rows, cols;
  std::vector<double> vals;
  collocation_entries(b, u, deriv, 0, rows, cols, vals);
  MatrixXd A = MatrixXd::Zero(u.size(), b.num_ctrl);
  for (size_t k = 0; k < vals.size(); ++k)
    A(rows[k], cols[k]) += vals[k];
  return A;
}

void bind_curve(py::module_& m) {
  py::class_<BSplineCurve>(m, "BSplineCurve",
                           R"(B-spline curve C(u) = sum_i N_{i,degree}(u) ctrl[i].

Attributes:
  degree    int
  knots     (#ctrl + degree + 1,) non-decreasing
  ctrl      (#ctrl, dim) control points
  periodic  the last `degree` control points repeat the first ones (closed, C^{degree-1} seam);
            evaluation wraps u into the domain)")
      .def(py::init([](int degree, VectorXd knots, MatrixXd ctrl, bool periodic) {
             check_knots(knots, degree, ctrl.rows());
             return BSplineCurve{degree, std::move(knots), std::move(ctrl), periodic};
           }),
           py::arg("degree"), py::arg("knots"), py::arg("ctrl"), py::arg("periodic") = false)
      .def_readwrite("degree", &BSplineCurve::degree)
      .def_readwrite("knots", &BSplineCurve::knots)
      .def_readwrite("ctrl", &BSplineCurve::ctrl)
      .def_readwrite("periodic", &BSplineCurve::periodic)
      .def_property_readonly(
          "domain",
          [](const BSplineCurve& c) { return py::make_tuple(domain_begin(c), domain_end(c)); },
          "(begin, end) = (knots[degree], knots[#ctrl])")
      .def(
          "evaluate",
          [](const BSplineCurve& c, const VectorXd& u, int deriv) {
            return evaluate(to_piecewise(c), u, deriv);
          },
          py::arg("u"), py::arg("deriv") = 0,
          "deriv-th derivative at the parameters u (#u,) -> (#u, dim), by the explicit per-span "
          "form (seed 001 Theorem 1 applied to the curve).")
      .def("__repr__", [](const BSplineCurve& c) {
        return "<BSplineCurve degree " + std::to_string(c.degree) + ", " +
               std::to_string(c.ctrl.rows()) + " x " + std::to_string(c.ctrl.cols()) +
               " control points" + (c.periodic ? ", periodic>" : ">");
      });

  m.def("chord_parameters", &chord_parameters, py::arg("P"), py::arg("closed") = false,
        py::arg("exponent") = 1.0,
        R"(Parameters in [0, 1] from |P_{i+1} - P_i|^exponent (1 chord length, 0.5 centripetal, 0
uniform). P (N, dim). Returns (N,) values, or (N + 1,) when closed (the last closes the loop).)");
  m.def("averaged_knots", &averaged_knots, py::arg("u"), py::arg("degree"),
        "Clamped knots for open interpolation at u (#u,) by averaging -> (#u + degree + 1,).");
  m.def("periodic_knots", &periodic_knots, py::arg("u"), py::arg("degree"),
        "Periodic knot vector for interpolation at the N sites u[:N] with closing parameter u[N] "
        "(N + 1 values) -> (N + 2 degree + 1,).");
  m.def("interpolate_open", &interpolate_open, py::arg("P"), py::arg("u"), py::arg("degree") = 3,
        "Open clamped interpolant C(u_i) = P_i. P (N, dim), u (N,) increasing in [0, 1].");
  m.def(
      "interpolate_closed",
      [](const MatrixXd& P, const VectorXd& u, int degree, const std::optional<VectorXd>& knots) {
        return knots ? interpolate_closed(P, u, degree, *knots) : interpolate_closed(P, u, degree);
      },
      py::arg("P"), py::arg("u"), py::arg("degree") = 3, py::arg("knots") = py::none(),
      R"(Periodic interpolant through a closed polygon, C^{degree-1} at the seam.
P (N, dim) distinct points (P_0 not repeated), u (N + 1,) increasing (u[N] closes the loop),
knots optional periodic knot vector (periodic_knots).)");
  m.def("refine_knots", &refine_knots, py::arg("curve"), py::arg("knots"),
        "Inserts the sorted knots into a clamped curve (the same curve on more knots).");
  m.def("periodic_to_clamped", &periodic_to_clamped, py::arg("curve"), py::arg("begin"),
        "The periodic curve on [begin, begin + period] as a clamped curve (same points).");
  m.def("make_compatible", &make_compatible, py::arg("curves"),
        "Clamped curves of one degree and domain refined to their knot union (one knot vector).");

  py::class_<Approximation>(m, "Approximation", "Result of approximate_curve.")
      .def_readonly("curve", &Approximation::curve)
      .def_readonly("u", &Approximation::u, "(#P,) parameters of the points")
      .def_readonly("max_deviation", &Approximation::max_deviation)
      .def_readonly("rms_deviation", &Approximation::rms_deviation)
      .def_readonly("worst_point", &Approximation::worst_point)
      .def_readonly("met_tolerance", &Approximation::met_tolerance);
  m.def(
      "approximate_curve",
      [](const MatrixXd& P, int degree, bool closed, int num_ctrl, double smoothing,
         double tolerance, double parameter_exponent) {
        ApproximationOptions o;
        o.degree = degree, o.closed = closed, o.num_ctrl = num_ctrl, o.smoothing = smoothing;
        o.tolerance = tolerance, o.parameter_exponent = parameter_exponent;
        return approximate_curve(P, o);
      },
      py::arg("P"), py::arg("degree") = 3, py::arg("closed") = false, py::arg("num_ctrl") = 0,
      py::arg("smoothing") = 0.0, py::arg("tolerance") = 0.0, py::arg("parameter_exponent") = 1.0,
      R"(Least-squares B-spline curve through noisy points P (N, dim) (seed 001 ch. 3):
minimises mean |C(u_i) - P_i|^2 + smoothing * int |C''|^2 / L^2. num_ctrl 0: max(degree+1, 8);
tolerance > 0 doubles num_ctrl until the max deviation is below it.)");
  m.def("bending_energy", &bending_energy, py::arg("curve"), "int |C''(u)|^2 du (degree >= 2).");

  py::class_<SectionCurve>(m, "SectionCurve", "Result of closed_section_curve.")
      .def_readonly("curve", &SectionCurve::curve)
      .def_readonly("u", &SectionCurve::u)
      .def_readonly("max_deviation", &SectionCurve::max_deviation)
      .def_readonly("met_tolerance", &SectionCurve::met_tolerance);
  m.def(
      "closed_section_curve",
      [](const MatrixXd& P, int degree, bool least_squares, int num_ctrl, double smoothing,
         double tolerance, double parameter_exponent) {
        return closed_section_curve(
            P, {degree, least_squares, num_ctrl, smoothing, tolerance, parameter_exponent});
      },
      py::arg("P"), py::arg("degree") = 2, py::arg("least_squares") = false,
      py::arg("num_ctrl") = 0, py::arg("smoothing") = 0.0, py::arg("tolerance") = 0.0,
      py::arg("parameter_exponent") = 1.0,
      "Closed section curve through (or near) P (N, dim), seed 001 §2.2 without its singular "
      "mode.");
  m.def("seed_section_curve", &seed_section_curve, py::arg("P"), py::arg("F"),
        "The seed's literal closed quadratic system (§2.2): P (M+1, dim) with P[M] = P[0], F "
        "(M+1,) parameters. RuntimeError names the alternating singular mode.");
}

void bind_basis(py::module_& m) {
  py::class_<SplineBasis>(m, "SplineBasis", R"(All B-splines of one knot vector in explicit
per-span form (seed 001 Theorem 1): coefficients computed once, then Horner.

Attributes: degree, knots, num_ctrl, coeffs ((#ctrl - degree)(degree + 1), degree + 1).)")
      .def_readonly("degree", &SplineBasis::degree)
      .def_readonly("knots", &SplineBasis::knots)
      .def_readonly("num_ctrl", &SplineBasis::num_ctrl)
      .def_readonly("coeffs", &SplineBasis::coeffs)
      .def(
          "derivatives",
          [](const SplineBasis& b, double u, int nderiv) {
            Index span = 0;
            MatrixXd D = basis_derivatives(b, u, nderiv, &span);
            return py::make_tuple(std::move(D), span);
          },
          py::arg("u"), py::arg("nderiv") = 0,
          "(D, span): D (nderiv + 1, degree + 1), row d the d-th derivatives of the basis "
          "functions N_{span-degree..span} non-zero at u.")
      .def("matrix", &basis_matrix, py::arg("u"), py::arg("deriv") = 0,
           "Dense (#u, #ctrl) matrix: entry (k, i) = N_i^(deriv)(u_k).");
  m.def("explicit_basis", &explicit_basis, py::arg("knots"), py::arg("degree"),
        "The explicit per-span basis of a knot vector (#ctrl + degree + 1,).");
  m.def(
      "cox_de_boor_derivatives",
      [](const VectorXd& knots, int p, Index num_ctrl, double u, int nderiv) {
        Index span = 0;
        MatrixXd D = cox_de_boor_derivatives(knots, p, num_ctrl, u, nderiv, &span);
        return py::make_tuple(std::move(D), span);
      },
      py::arg("knots"), py::arg("degree"), py::arg("num_ctrl"), py::arg("u"), py::arg("nderiv") = 0,
      "Reference: (D, span) by the Cox-de Boor recursion (Piegl & Tiller A2.3), same layout as "
      "SplineBasis.derivatives.");
  m.def("find_span", &find_span, py::arg("knots"), py::arg("degree"), py::arg("num_ctrl"),
        py::arg("u"), "Index k of the knot span [knots[k], knots[k+1]) holding u.");
}

void bind_theorem1(py::module_& m) {
  py::class_<ExplicitBSpline>(m, "ExplicitBSpline", R"(One B-spline N_{0,n}(x; X) in explicit
per-span form (seed 001 Theorem 1). Call it: N(x, deriv=0) on any array x.

Attributes:
  degree  n
  breaks  (s + 1,) distinct knots
  taylor  (s, n + 1): taylor[j, q] = D^q N at the left end of span j)")
      .def_readonly("degree", &ExplicitBSpline::degree)
      .def_readonly("breaks", &ExplicitBSpline::breaks)
      .def_readonly("taylor", &ExplicitBSpline::taylor)
      .def(
          "__call__",
          [](const ExplicitBSpline& N, const DoubleArray& x, int deriv) {
            return map_elements(x, [&](double t) { return evaluate(N, t, deriv); });
          },
          py::arg("x"), py::arg("deriv") = 0, "N^(deriv)(x), elementwise; 0 outside the support.");
  m.def("explicit_bspline", &explicit_bspline, py::arg("X"), py::arg("n"),
        "seed 001 Theorem 1: the B-spline of degree n on the n + 2 knots X (multiple knots "
        "allowed), y* by the stable derivative recurrence.");
  m.def("theorem1_y", &theorem1_y, py::arg("X"), py::arg("n"),
        "y_k = N^(n-1)(X_k), k = 1..n (stable derivative recurrence; simple knots).");
  m.def("theorem1_y_solve", &theorem1_y_solve, py::arg("X"), py::arg("n"),
        "The seed's own route: y_1 = 1 and a linear solve of the closure conditions (3), scaled "
        "to partition of unity. Ill-conditioned for strongly nonuniform knots.");
  m.def("theorem1_y_closed_form", &theorem1_y_closed_form, py::arg("X"), py::arg("n"),
        "digest 001 §2.1.3: y_k from the divided-difference representation.");
  m.def("closure_residual", &closure_residual, py::arg("N"), py::arg("X"),
        "max_q |D^q N(X_{n+1}-)| / max |N|: how well N closes its support (conditions (3)).");
}

void bind_theorem2(py::module_& m) {
  py::class_<MinJumpQuadratic>(m, "MinJumpQuadratic", R"(seed 001 Theorem 2 spline: interpolating
quadratic with the minimal sum of squared jumps of S''. Call it: S(t, deriv=0).

Attributes: x (N,) nodes, y (N,) values, M (N - 1,) S'' on each interval.)")
      .def_readonly("x", &MinJumpQuadratic::x)
      .def_readonly("y", &MinJumpQuadratic::y)
      .def_readonly("M", &MinJumpQuadratic::M)
      .def(
          "__call__",
          [](const MinJumpQuadratic& S, const VectorXd& t, int deriv) {
            return evaluate(S, t, deriv);
          },
          py::arg("t"), py::arg("deriv") = 0, "S^(deriv)(t) at t (#t,) -> (#t,).")
      .def_property_readonly("jump_functional", &jump_functional,
                             "J = sum (M_i - M_{i+1})^2, the functional Theorem 2 minimises.");
  m.def("min_jump_quadratic", &min_jump_quadratic, py::arg("x"), py::arg("y"),
        "seed 001 Theorem 2: M_{1,2} by the closed form, the rest by the recurrence. x (N,) "
        "strictly increasing, y (N,).");
  m.def("theorem2_m12", &theorem2_m12, py::arg("x"), py::arg("y"),
        "seed 001 Theorem 2: the optimal M_{1,2} (closed form).");
  m.def("theorem2_recurrence", &theorem2_recurrence, py::arg("x"), py::arg("y"), py::arg("m12"),
        "M (N - 1,) by the recurrence from a given M_{1,2}.");
  m.def("theorem2_explicit", &theorem2_explicit, py::arg("x"), py::arg("y"), py::arg("m12"),
        "M (N - 1,) by the explicit formula (an independent path to the recurrence).");
}

} // namespace

void bind_splines(py::module_& m) {
  bind_curve(m);
  bind_basis(m);
  bind_theorem1(m);
  bind_theorem2(m);
}

} // namespace interlin::python
