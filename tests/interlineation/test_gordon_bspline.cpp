// Gordon surface of a B-spline curve network as one tensor-product B-spline: exact on both
// families, equal to the operator form evaluated from the same curves, C2 across the seam.
#include "interlin/interlineation/gordon_bspline.h"
#include "interlin/interlineation/gordon_surface.h"
#include "interlin/interlineation/interlinate_curves.h"
#include "interlin/splines/interpolate_curve.h"
#include "interlin/splines/knot_insertion.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace interlin;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// A closed, twisted, tapering tube: f(u, v), u in [0,1) around, v in [0,1] along.
Eigen::RowVector3d tube(double u, double v) {
  const double t = 2 * M_PI * u, a = 1.5 + 0.4 * std::sin(2 * v), b = 0.5 + 0.2 * v * v;
  const double w = 0.8 * v, x = a * std::cos(t) + 0.1 * std::cos(3 * t), y = b * std::sin(t);
  return {std::cos(w) * x - std::sin(w) * y, std::sin(w) * x + std::cos(w) * y, 2 * v};
}

// Closed section at v: periodic cubic through 24 nonuniform points, clamped at u = 0.
BSplineCurve tube_section(double v, const VectorXd& landmarks) {
  std::vector<double> s;
  for (int i = 0; i < 24; ++i)
    s.push_back((i + 0.3 * std::sin(i)) / 24.0);
  for (double l : landmarks)
    s.push_back(l);
  std::sort(s.begin(), s.end());
  s.erase(std::unique(s.begin(), s.end(), [](double a, double b) { return b - a < 1e-3; }),
          s.end());
  s[0] = 0;
  MatrixXd P(static_cast<Index>(s.size()), 3);
  VectorXd u(static_cast<Index>(s.size()) + 1);
  for (size_t i = 0; i < s.size(); ++i) {
    P.row(static_cast<Index>(i)) = tube(s[i], v);
    u(static_cast<Index>(i)) = s[i];
  }
  u(u.size() - 1) = 1;
  return periodic_to_clamped(interpolate_closed(P, u, 3), 0.0);
}

struct Network {
  std::vector<BSplineCurve> sections, guides;
  VectorXd v, u;
};

// K sections (each its own knots), L guides through the section curves' points at u_l plus
// the tube's points between sections.
Network network(Index K, const VectorXd& u, int q) {
  Network n;
  n.u = u;
  n.v = VectorXd::LinSpaced(K, 0, 1);
  n.v(1) = 0.2;
  for (Index k = 0; k < K; ++k)
    n.sections.push_back(tube_section(n.v(k), u));
  std::vector<BSplineCurve> same = make_compatible(n.sections);
  n.sections = same;
  for (Index l = 0; l < u.size(); ++l) {
    MatrixXd P(2 * K - 1, 3);
    VectorXd s(2 * K - 1);
    for (Index k = 0; k < K; ++k) {
      P.row(2 * k) = evaluate(n.sections[k], VectorXd::Constant(1, u(l)));
      s(2 * k) = n.v(k);
      if (k + 1 < K) {
        s(2 * k + 1) = 0.5 * (n.v(k) + n.v(k + 1));
        P.row(2 * k + 1) = tube(u(l), s(2 * k + 1));
      }
    }
    n.guides.push_back(interpolate_open(P, s, q));
  }
  return n;
}

// Traces of the Boolean-sum operator from the same curves: the guides on the lines x = u_l, the
// sections on the lines y = v_k.
LineTraces curve_traces(const VectorXd& u, const std::vector<BSplineCurve>& guides,
                        const VectorXd& v, const std::vector<BSplineCurve>& sections) {
  LineTraces t;
  t.x = u;
  t.y = v;
  for (const BSplineCurve& g : guides)
    t.on_x.push_back(spline_trace(g));
  for (const BSplineCurve& c : sections)
    t.on_y.push_back(spline_trace(c));
  return t;
}

// The largest |P(a, b) - O(a, b)| over na x nb samples of [0, a_max] x [0, 1].
double max_difference(const PiecewiseSurface& P, const GordonSurface& O, int na, double a_max,
                      int nb) {
  double worst = 0;
  for (double a : VectorXd::LinSpaced(na, 0, a_max))
    for (double b : VectorXd::LinSpaced(nb, 0, 1))
      worst = std::max(worst, (evaluate(P, a, b).transpose() - evaluate(O, a, b)).norm());
  return worst;
}

} // namespace

TEST_CASE("Gordon B-spline surface interpolates both curve families exactly", "[gordon_bspline]") {
  for (Index L : {1, 2, 3, 5}) {
    const VectorXd u = VectorXd::LinSpaced(L + 1, 0.1, 0.9).head(L);
    const Network n = network(5, u, 3);
    const BSplineSurface S = gordon_bspline(n.sections, n.v, n.guides, n.u, 3, true);
    const PiecewiseSurface P = to_piecewise(S);
    CHECK(S.closed_u);
    double sec = 0, gui = 0;
    const VectorXd s = VectorXd::LinSpaced(301, 0, 1);
    for (size_t k = 0; k < n.sections.size(); ++k) {
      const MatrixXd C = evaluate(n.sections[k], s);
      for (Index i = 0; i < s.size(); ++i)
        sec = std::max(sec, (evaluate(P, s(i), n.v(Index(k))).transpose() - C.row(i)).norm());
    }
    for (size_t l = 0; l < n.guides.size(); ++l) {
      const MatrixXd G = evaluate(n.guides[l], s);
      for (Index i = 0; i < s.size(); ++i)
        gui = std::max(gui, (evaluate(P, n.u(Index(l)), s(i)).transpose() - G.row(i)).norm());
    }
    INFO(L << " guides: sections " << sec << ", guides " << gui);
    // Coordinates O(2); knot insertion and small collocation solves: round-off.
    CHECK(sec < 1e-13);
    CHECK(gui < 1e-13);
    // C2 across the seam u = 0 = 1 (periodic sections and periodic cubic blending).
    for (int d = 0; d <= 2; ++d)
      for (double v : {0.1, 0.5, 0.93})
        CHECK((evaluate(P, 0.0, v, d, 0) - evaluate(P, 1.0, v, d, 0)).norm() <
              1e-11 * std::pow(100.0, d));
  }
}

TEST_CASE("Gordon B-spline surface equals the Boolean-sum operator on the same curves",
          "[gordon_bspline]") {
  // Independent evaluation: gordon_surface with spline traces, periodic cubic alpha over u and
  // cubic cardinal beta over v, summed term by term at each point.
  const VectorXd u = Eigen::Vector3d(0.0, 0.4, 0.7);
  const Network n = network(6, u, 3);
  const PiecewiseSurface P = to_piecewise(gordon_bspline(n.sections, n.v, n.guides, n.u, 3, true));
  GordonOptions o;
  o.periodic_x = true;
  o.period_x = 1.0;
  o.tolerance = 1e-12;
  const GordonSurface O = gordon_surface(curve_traces(n.u, n.guides, n.v, n.sections), o);
  const double worst = max_difference(P, O, 37, 0.999, 23);
  INFO("max difference " << worst);
  CHECK(worst < 1e-13);
}

TEST_CASE("Open network: quadratic cardinal blending across, elevated to the sections' degree",
          "[gordon_bspline]") {
  // Half of the tube, u in [0, 1] open; guides on both boundaries and one inside.
  const VectorXd u = Eigen::Vector3d(0.0, 0.3, 1.0), v = Eigen::Vector4d(0, 0.3, 0.6, 1);
  std::vector<BSplineCurve> sections, guides;
  const VectorXd s = (VectorXd(9) << 0, 0.1, 0.2, 0.3, 0.45, 0.6, 0.7, 0.85, 1).finished();
  for (double vk : v) {
    MatrixXd P(9, 3);
    for (Index i = 0; i < 9; ++i)
      P.row(i) = tube(0.5 * s(i), vk);
    sections.push_back(interpolate_open(P, s, 3));
  }
  sections = make_compatible(sections);
  for (double ul : u) {
    MatrixXd P(4, 3);
    for (Index k = 0; k < 4; ++k)
      P.row(k) = evaluate(sections[static_cast<size_t>(k)], VectorXd::Constant(1, ul));
    guides.push_back(interpolate_open(P, v, 3));
  }
  const BSplineSurface S = gordon_bspline(sections, v, guides, u, 3, false);
  CHECK_FALSE(S.closed_u);
  const PiecewiseSurface P = to_piecewise(S);
  GordonOptions o;
  o.degree_x = 2; // min(p, L - 1)
  o.tolerance = 1e-12;
  const GordonSurface O = gordon_surface(curve_traces(u, guides, v, sections), o);
  const double worst = max_difference(P, O, 31, 1, 17);
  INFO("max difference " << worst);
  CHECK(worst < 1e-13);
  CHECK_THROWS_WITH(gordon_bspline(sections, v, {guides[0], guides[1]}, u.head(2), 3, false),
                    Catch::Contains("both ends"));
}

TEST_CASE("Gordon B-spline surface: no guides is the section loft, mismatches are rejected",
          "[gordon_bspline]") {
  const Network n = network(4, Eigen::Vector2d(0.0, 0.5), 3);
  const BSplineSurface A = gordon_bspline(n.sections, n.v, {}, VectorXd(0), 3, true);
  const BSplineSurface B = interlinate_curves(n.sections, n.v, 3, true);
  CHECK((A.ctrl - B.ctrl).cwiseAbs().maxCoeff() < 1e-13);
  CHECK(A.knots_v == B.knots_v);
  std::vector<BSplineCurve> bad = n.guides;
  bad[1].ctrl.row(3) += Eigen::RowVector3d(0, 0, 1e-6); // moves G_1(v_k) off section k
  CHECK_THROWS_WITH(gordon_bspline(n.sections, n.v, bad, n.u, 3, true),
                    Catch::Contains("do not meet"));
  CHECK_THROWS_WITH(gordon_bspline(n.sections, n.v, n.guides, Eigen::Vector2d(0.0, 1.0), 3, true),
                    Catch::Contains("outside"));
}
