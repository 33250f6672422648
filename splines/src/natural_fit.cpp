// seed 004 Ch. 1 (digest 004 §2.5, §3.2–3.6): natural curves through points and tangents.
#include "interlin/splines/natural_fit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace interlin {

using Eigen::Index;
using Eigen::Vector2d;
using Eigen::VectorXd;

namespace {

using Pieces = std::vector<PlanarNaturalCurve>;

// One shooting problem: unknowns theta -> pieces and the computed points that must hit targets.
struct Shooting {
  std::function<Pieces(const VectorXd&)> build;
  // Computed points for the unknowns theta and the pieces they build.
  std::function<std::vector<Vector2d>(const VectorXd&, const Pieces&, const QuadratureOptions&)>
      points;
  std::vector<Vector2d> targets;
  std::vector<double> weights; // Germeier lambda_i for Hooke–Jeeves (1.17)
  std::function<bool(const VectorXd&)> feasible;
  std::vector<VectorXd> starts;
};

double max_miss(const std::vector<Vector2d>& p, const std::vector<Vector2d>& t) {
  double m = 0;
  for (size_t i = 0; i < t.size(); ++i)
    m = std::max(m, (p[i] - t[i]).norm());
  return m;
}

// Trial curves that wind more than kMaxTurning radians (|k| bounded from samples times length)
// are rejected: no target needs them, and their quadrature would be arbitrarily expensive.
constexpr double kMaxTurning = 200;

bool tame(const Pieces& ps) {
  for (const PlanarNaturalCurve& c : ps) {
    double kmax = 0;
    for (int i = 0; i <= 32; ++i)
      kmax = std::max(kmax, std::abs(curvature(c.law, c.length * i / 32)));
    if (!std::isfinite(kmax) || kmax * c.length > kMaxTurning)
      return false;
  }
  return true;
}

NaturalFit solve(const Shooting& pr0, const ShootingOptions& o, const char* what) {
  if (!(o.tolerance > 0))
    throw std::invalid_argument(std::string(what) + ": tolerance must be > 0");
  Shooting pr = pr0;
  pr.feasible = [&pr0](const VectorXd& t) {
    return t.allFinite() && pr0.feasible(t) && tame(pr0.build(t));
  };
  const auto residual = [&](const VectorXd& th) {
    const std::vector<Vector2d> p = pr.points(th, pr.build(th), o.quadrature);
    VectorXd r(2 * static_cast<Index>(p.size()));
    for (size_t i = 0; i < p.size(); ++i)
      r.segment<2>(2 * static_cast<Index>(i)) = p[i] - pr.targets[i];
    return r;
  };
  NaturalFit best;
  best.miss = std::numeric_limits<double>::infinity();
  for (const VectorXd& th0 : pr.starts) {
    if (!pr.feasible(th0))
      continue;
    VectorXd th;
    if (o.solver == ShootingSolver::levenberg_marquardt) {
      LevenbergMarquardtOptions lm = o.lm;
      lm.residual_tolerance = std::min(lm.residual_tolerance, 1e-3 * o.tolerance);
      th = levenberg_marquardt(residual, th0, lm, pr.feasible).x;
    } else {
      const auto Q = [&](const VectorXd& t) {
        if (!t.allFinite() || !pr.feasible(t))
          return std::numeric_limits<double>::infinity();
        const std::vector<Vector2d> p = pr.points(t, pr.build(t), o.quadrature);
        double q = 0;
        for (size_t i = 0; i < p.size(); ++i)
          q += pr.weights[i] * (o.hj_objective == HookeJeevesObjective::germeier
                                    ? (p[i] - pr.targets[i]).norm()
                                    : (p[i] - pr.targets[i]).squaredNorm());
        return q;
      };
      // Stop once every miss is surely below the tolerance.
      const double wmin = *std::min_element(pr.weights.begin(), pr.weights.end());
      HookeJeevesOptions hj = o.hj;
      hj.target = std::max(hj.target, o.hj_objective == HookeJeevesObjective::germeier
                                          ? 0.1 * o.tolerance * wmin
                                          : 0.01 * o.tolerance * o.tolerance * wmin);
      // Restarted from its own result with the initial steps while that still helps: one run
      // often stalls on the non-smooth sum of distances (digest §2.5 [V]).
      HookeJeevesResult r = hooke_jeeves(Q, th0, hj);
      for (int restart = 0; restart < 20 && r.f > hj.target; ++restart) {
        const HookeJeevesResult again = hooke_jeeves(Q, r.x, hj);
        if (!(again.f < 0.999 * r.f))
          break;
        r = again;
      }
      th = r.x;
    }
    NaturalFit fit;
    fit.pieces = pr.build(th);
    fit.miss = max_miss(pr.points(th, fit.pieces, o.quadrature), pr.targets);
    if (fit.miss < best.miss)
      best = fit;
    if (best.miss <= o.tolerance)
      return best;
  }
  std::ostringstream msg;
  msg << what << ": no curve reaches the targets (smallest miss " << best.miss << " > tolerance "
      << o.tolerance << "); the points and tangent angles may be inconsistent";
  throw std::runtime_error(msg.str());
}

void check_pose(const CurvePose& p, const char* what) {
  if (!p.point.allFinite() || !std::isfinite(p.angle))
    throw std::invalid_argument(std::string(what) + ": points and angles must be finite");
}

double chord(const Vector2d& a, const Vector2d& b, const char* what) {
  const double c = (b - a).norm();
  if (!(c > 0))
    throw std::invalid_argument(std::string(what) + ": consecutive points coincide");
  return c;
}

PlanarNaturalCurve piece(const Vector2d& start, double phi0, const VectorXd& poly, double S) {
  PlanarNaturalCurve c;
  c.start = start;
  c.phi0 = phi0;
  c.law.poly = poly;
  c.length = S;
  return c;
}

std::vector<Vector2d> piece_ends(const VectorXd&, const Pieces& ps, const QuadratureOptions& q) {
  std::vector<Vector2d> e;
  for (const PlanarNaturalCurve& c : ps)
    e.push_back(natural_point(c, c.length, q));
  return e;
}

// The points of a one-piece curve at arc length theta(2) (the interior target) and at its end.
std::vector<Vector2d> interior_and_end(const VectorXd& t, const Pieces& ps,
                                       const QuadratureOptions& q) {
  const NaturalSamples smp =
      sample_natural_curve(ps[0], (VectorXd(2) << t(2), ps[0].length).finished(), q);
  return {smp.points.row(0).transpose(), smp.points.row(1).transpose()};
}

// Law of fit_hermite_curvature for unknowns (b, S).
VectorXd hermite_law(const VectorXd& fixed, double dphi, double b, double S) {
  const Index m = fixed.size();
  VectorXd poly(m + 2);
  poly.head(m) = fixed;
  double rest = dphi - b * std::pow(S, double(m + 1)) / double(m + 1);
  for (Index j = 0; j < m; ++j)
    rest -= fixed(j) * std::pow(S, double(j + 1)) / double(j + 1);
  poly(m) = b;
  poly(m + 1) = double(m + 2) / std::pow(S, double(m + 2)) * rest;
  return poly;
}

const auto positive_lengths = [](Index first) {
  return [first](const VectorXd& t) {
    for (Index i = first; i < t.size(); ++i)
      if (!(t(i) > 0))
        return false;
    return true;
  };
};

} // namespace

ShootingOptions book_mode() {
  ShootingOptions o;
  o.solver = ShootingSolver::hooke_jeeves;
  o.quadrature.rule = NaturalQuadrature::trapezoid;
  o.quadrature.intervals = 2000;
  o.tolerance = 1e-4;
  return o;
}

NaturalFit fit_hermite_curvature(const CurvePose& p0, const CurvePose& p1, const VectorXd& fixed,
                                 const ShootingOptions& o) {
  const char* what = "natural curve G1 Hermite fit";
  check_pose(p0, what);
  check_pose(p1, what);
  if (!fixed.allFinite())
    throw std::invalid_argument(std::string(what) + ": prescribed coefficients must be finite");
  const double L = chord(p0.point, p1.point, what), dphi = p1.angle - p0.angle;
  Shooting pr;
  pr.build = [=](const VectorXd& t) {
    return Pieces{piece(p0.point, p0.angle, hermite_law(fixed, dphi, t(0), t(1)), t(1))};
  };
  pr.points = piece_ends;
  pr.targets = {p1.point};
  pr.weights = {1.0};
  pr.feasible = positive_lengths(1);
  // Starts: S = chord (the book's choice) and longer; b = 0 and b = mean turning rate.
  for (double f : {1.0, 1.25, 1.6, 0.9, 2.2})
    for (double b : {dphi / (f * L), 0.0})
      pr.starts.push_back((VectorXd(2) << (fixed.size() == 0 ? b : 0.0), f * L).finished());
  return solve(pr, o, what);
}

NaturalFit fit_linear_curvature(const CurvePose& p0, const CurvePose& p1,
                                const ShootingOptions& o) {
  return fit_hermite_curvature(p0, p1, VectorXd(), o);
}

NaturalFit fit_linear_curvature_chain(const std::vector<CurvePose>& poses,
                                      const ShootingOptions& o) {
  if (poses.size() < 2)
    throw std::invalid_argument("linear-curvature chain needs at least 2 points");
  NaturalFit chain;
  for (size_t i = 0; i + 1 < poses.size(); ++i) {
    const NaturalFit link = fit_linear_curvature(poses[i], poses[i + 1], o);
    chain.pieces.push_back(link.pieces[0]);
    chain.miss = std::max(chain.miss, link.miss);
  }
  return chain;
}

VectorXd spline_tangent_angles(const Eigen::MatrixXd& P, double phi_first, double phi_last) {
  const Index n = P.rows();
  if (n < 2 || P.cols() != 2)
    throw std::invalid_argument("spline tangents: need #P >= 2 points of 2 coordinates");
  if (!P.allFinite() || !std::isfinite(phi_first) || !std::isfinite(phi_last))
    throw std::invalid_argument("spline tangents: points and angles must be finite");
  if (std::abs(phi_first) >= M_PI / 2 || std::abs(phi_last) >= M_PI / 2)
    throw std::invalid_argument("spline tangents: end angles of a y(x) spline must lie in "
                                "(-90, 90) degrees");
  for (Index i = 1; i < n; ++i)
    if (!(P(i, 0) > P(i - 1, 0)))
      throw std::invalid_argument("spline tangents: x must increase strictly (point " +
                                  std::to_string(i) + "); a y(x) spline cannot pass here");
  // Clamped cubic spline in slopes m_i: for interior i,
  //   h_i m_{i-1} + 2(h_{i-1}+h_i) m_i + h_{i-1} m_{i+1} = 3(h_i d_{i-1} + h_{i-1} d_i).
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  VectorXd rhs(n);
  A(0, 0) = 1;
  rhs(0) = std::tan(phi_first);
  A(n - 1, n - 1) = 1;
  rhs(n - 1) = std::tan(phi_last);
  for (Index i = 1; i + 1 < n; ++i) {
    const double h0 = P(i, 0) - P(i - 1, 0), h1 = P(i + 1, 0) - P(i, 0);
    const double d0 = (P(i, 1) - P(i - 1, 1)) / h0, d1 = (P(i + 1, 1) - P(i, 1)) / h1;
    A(i, i - 1) = h1;
    A(i, i) = 2 * (h0 + h1);
    A(i, i + 1) = h0;
    rhs(i) = 3 * (h1 * d0 + h0 * d1);
  }
  const VectorXd m = A.partialPivLu().solve(rhs);
  return m.array().atan().matrix();
}

NaturalFit fit_quadratic_curvature_3pt(const CurvePose& p0, const Vector2d& p1, const CurvePose& p2,
                                       const ShootingOptions& o) {
  const char* what = "quadratic-curvature 3-point fit";
  check_pose(p0, what);
  check_pose(p2, what);
  if (!p1.allFinite())
    throw std::invalid_argument(std::string(what) + ": points must be finite");
  const double L1 = chord(p0.point, p1, what), L2 = chord(p1, p2.point, what);
  const double dphi = p2.angle - p0.angle;
  Shooting pr;
  // theta = (b, c, S1, S2); a = (3/S^2)(dphi/S - b S/2 - c), S = S1 + S2 (errata §10.1).
  pr.build = [=](const VectorXd& t) {
    const double S = t(2) + t(3);
    const double a = 3 / (S * S) * (dphi / S - t(0) * S / 2 - t(1));
    return Pieces{piece(p0.point, p0.angle, (VectorXd(3) << t(1), t(0), a).finished(), S)};
  };
  pr.points = interior_and_end; // P(S1) and P(S1 + S2)
  pr.targets = {p1, p2.point};
  pr.weights = {0.5, 0.5};
  pr.feasible = positive_lengths(2);
  for (double f : {1.0, 1.3, 0.8, 1.8})
    pr.starts.push_back((VectorXd(4) << 0.0, dphi / (f * (L1 + L2)), f * L1, f * L2).finished());
  return solve(pr, o, what);
}

NaturalFit fit_quadratic_curvature_g3(const CurvePose& p1, const CurvePose& p2, const CurvePose& p3,
                                      const ShootingOptions& o) {
  const char* what = "two-piece quadratic-curvature G3 fit";
  check_pose(p1, what);
  check_pose(p2, what);
  check_pose(p3, what);
  const double L1 = chord(p1.point, p2.point, what), L2 = chord(p2.point, p3.point, what);
  const double dphi1 = p2.angle - p1.angle, dphi2 = p3.angle - p2.angle;
  Shooting pr;
  // theta = (b1, c1, S1, S2).
  pr.build = [=](const VectorXd& t) {
    const double b1 = t(0), c1 = t(1), S1 = t(2), S2 = t(3);
    const double a1 = 3 / (S1 * S1) * (dphi1 / S1 - b1 * S1 / 2 - c1); // (1.24)
    const double c2 = a1 * S1 * S1 + b1 * S1 + c1;                     // G2 (1.19)
    const double b2 = 2 * a1 * S1 + b1;                                // G3 (1.20)
    const double a2 = 3 / (S2 * S2) * (dphi2 / S2 - b2 * S2 / 2 - c2); // (1.25)
    Pieces ps{piece(p1.point, p1.angle, (VectorXd(3) << c1, b1, a1).finished(), S1),
              piece(Vector2d::Zero(), p2.angle, (VectorXd(3) << c2, b2, a2).finished(), S2)};
    return ps;
  };
  // Piece 2 starts at the computed end of piece 1 (digest §13).
  pr.points = [](const VectorXd&, const Pieces& ps, const QuadratureOptions& q) {
    const Vector2d e1 = natural_point(ps[0], ps[0].length, q);
    PlanarNaturalCurve second = ps[1];
    second.start = e1;
    return std::vector<Vector2d>{e1, natural_point(second, second.length, q)};
  };
  pr.targets = {p2.point, p3.point};
  pr.weights = {0.5, 0.5};
  pr.feasible = positive_lengths(2);
  for (double f : {1.0, 1.3, 0.8, 1.8})
    pr.starts.push_back((VectorXd(4) << 0.0, dphi1 / (f * L1), f * L1, f * L2).finished());
  NaturalFit fit = solve(pr, o, what);
  fit.pieces[1].start = natural_point(fit.pieces[0], fit.pieces[0].length, o.quadrature);
  return fit;
}

Eigen::Vector2d cubic_curvature_ab(double dphi1, double dphi2, double S1, double S2, double c,
                                   double d) {
  if (!(S1 > 0 && S2 > S1))
    throw std::invalid_argument("cubic curvature law: need 0 < S1 < S2");
  const double F1 = 4 * dphi1 / std::pow(S1, 4), F2 = 4 * dphi2 / std::pow(S2, 4);
  const double P = S1 * S2, s2 = S1 * S1 * S2 * S2;
  const double a = (F2 * S2 - F1 * S1) / (S2 - S1) + 2 * c / P + 4 * d * (S1 + S2) / s2;
  const double b = 3 * P * (F2 - F1) / (4 * (S1 - S2)) - 3 * c * (S1 + S2) / (2 * P) -
                   3 * d * (S1 * S1 + P + S2 * S2) / s2;
  return {a, b};
}

NaturalFit fit_cubic_curvature_3pt(const CurvePose& p0, const CurvePose& p1, const CurvePose& p2,
                                   const ShootingOptions& o) {
  const char* what = "cubic-curvature 3-point fit";
  check_pose(p0, what);
  check_pose(p1, what);
  check_pose(p2, what);
  const double L1 = chord(p0.point, p1.point, what), L2 = chord(p1.point, p2.point, what);
  const double dphi1 = p1.angle - p0.angle, dphi2 = p2.angle - p0.angle;
  Shooting pr;
  // theta = (c, d, S1, S2) with S2 the total length (s measured from P0).
  pr.build = [=](const VectorXd& t) {
    const Eigen::Vector2d ab = cubic_curvature_ab(dphi1, dphi2, t(2), t(3), t(0), t(1));
    return Pieces{
        piece(p0.point, p0.angle, (VectorXd(4) << t(1), t(0), ab(1), ab(0)).finished(), t(3))};
  };
  pr.points = interior_and_end; // P(S1) and P(S2)
  pr.targets = {p1.point, p2.point};
  pr.weights = {0.8, 0.2}; // the book's lambda (§1.9): the interior point is harder to hit
  pr.feasible = [](const VectorXd& t) { return t(2) > 0 && t(3) > t(2); };
  for (double f : {1.0, 1.3, 0.8, 1.8})
    pr.starts.push_back(
        (VectorXd(4) << 0.0, dphi2 / (f * (L1 + L2)), f * L1, f * (L1 + L2)).finished());
  return solve(pr, o, what);
}

} // namespace interlin
