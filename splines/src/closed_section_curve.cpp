// seed 001 §2.2 (digest 001 §2.2, T18): closed section curves from points.
#include "interlin/splines/closed_section_curve.h"

#include "interlin/splines/interpolate_curve.h"
#include "interlin/splines/parameterization.h"
#include "interlin/splines/spline_basis.h"

#include <Eigen/Dense>
#include <stdexcept>
#include <string>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

BSplineCurve seed_section_curve(const MatrixXd& P, const VectorXd& F) {
  const Index M = P.rows() - 1; // intervals
  if (M < 3)
    throw std::invalid_argument("seed section curve: need at least 4 points (3 intervals)");
  if (F.size() != P.rows())
    throw std::invalid_argument("seed section curve: one parameter per point");
  if (!P.allFinite() || !F.allFinite())
    throw std::invalid_argument("seed section curve: points and parameters must be finite");
  for (Index i = 1; i <= M; ++i)
    if (!(F(i) > F(i - 1)))
      throw std::invalid_argument("seed section curve: parameters must increase strictly");
  if (P.row(0) != P.row(M))
    throw std::invalid_argument("seed section curve: the last point must repeat the first");
  BSplineCurve c;
  c.degree = 2;
  c.knots.resize(M + 5);
  c.knots.head(2).setConstant(F(0));
  c.knots.segment(2, M + 1) = F;
  c.knots.tail(2).setConstant(F(M));
  const Index n = M + 2;
  const SplineBasis B = explicit_basis(c.knots, 2);
  MatrixXd A = MatrixXd::Zero(n, n), rhs = MatrixXd::Zero(n, P.cols());
  for (Index p = 0; p <= M; ++p) { // x_p = SSX(F_p), y_p = SSY(F_p)
    Index span;
    const MatrixXd D = basis_derivatives(B, F(p), 0, &span);
    for (int r = 0; r <= 2; ++r)
      A(p, span - 2 + r) += D(0, r);
    rhs.row(p) = P.row(p);
  }
  for (const auto& [u, sign] : {std::pair{F(0), 1.0}, std::pair{F(M), -1.0}}) {
    Index span; // tangent closure: C'(F_0) - C'(F_M) = 0
    const MatrixXd D = basis_derivatives(B, u, 1, &span);
    for (int r = 0; r <= 2; ++r)
      A(M + 1, span - 2 + r) += sign * D(1, r);
  }
  const Eigen::JacobiSVD<MatrixXd> svd(A, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const VectorXd s = svd.singularValues();
  if (!(s(n - 1) > 1e-12 * s(0)))
    throw std::runtime_error(
        "seed section curve: the system is singular: quadratic B-splines with knots at the data "
        "parameters have the alternating null vector (" +
        std::to_string(M + 1) +
        " points; digest 001 §2.2); use closed_section_curve (midpoint knots) instead");
  c.ctrl = svd.solve(rhs);
  return c;
}

SectionCurve closed_section_curve(const MatrixXd& P, const SectionCurveOptions& o) {
  if (o.degree < 1)
    throw std::invalid_argument("section curve: degree must be >= 1");
  if (o.degree >= P.rows())
    throw std::invalid_argument("section curve: degree " + std::to_string(o.degree) +
                                " needs more than " + std::to_string(o.degree) + " points, got " +
                                std::to_string(P.rows()));
  SectionCurve r;
  if (o.least_squares) {
    ApproximationOptions a;
    a.degree = o.degree;
    a.closed = true;
    a.num_ctrl = o.num_ctrl;
    a.smoothing = o.smoothing;
    a.tolerance = o.tolerance;
    a.parameter_exponent = o.parameter_exponent;
    const Approximation fit = approximate_curve(P, a);
    r.curve = fit.curve;
    r.u = fit.u;
    r.max_deviation = fit.max_deviation;
    r.met_tolerance = fit.met_tolerance;
    return r;
  }
  const VectorXd u = chord_parameters(P, true, o.parameter_exponent);
  r.curve = interpolate_closed(P, u, o.degree); // periodic_knots: midpoints for even degree
  r.u = u.head(P.rows());
  r.max_deviation = (evaluate(r.curve, r.u) - P).rowwise().norm().maxCoeff();
  return r;
}

} // namespace interlin
