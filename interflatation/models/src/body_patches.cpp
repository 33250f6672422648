#include "interlin/interflatation/models/body_patches.h"

#include "interlin/splines/surface_foot.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace interlin {

using Eigen::Index;
using Eigen::Vector3d;

namespace {

// Parameters of the cap's two sides around the loop: u_a(s) on side one, u_b(s) on side two
// (wrapped into [0, 1)).
struct CapMap {
  double ua, ub;
  double side_one(double s) const { return ua + s * (ub - ua); }
  double side_two(double s) const {
    const double u = ua - s * (1 - (ub - ua));
    return u < 0 ? u + 1 : u;
  }
};

// The ruled cap at v = ve as a piecewise surface of degree p x 1: on every s-span both sides are
// polynomials of degree p in s (a polynomial piece of S composed with a linear map), found by
// collocation at p + 1 interior points of the span.
PiecewiseSurface ruled_cap(const PiecewiseSurface& S, double ve, const CapMap& m) {
  const int p = S.degree_u;
  const double len1 = m.ub - m.ua, len2 = 1 - len1;
  std::vector<double> br{0, 1};
  for (Index k = 0; k < S.breaks_u.size(); ++k)
    for (double kn : {S.breaks_u(k), S.breaks_u(k) - 1}) {
      if (kn > m.ua && kn < m.ub)
        br.push_back((kn - m.ua) / len1);
      if (kn < m.ua && kn > m.ua - len2)
        br.push_back((m.ua - kn) / len2);
    }
  std::sort(br.begin(), br.end());
  std::vector<double> breaks{br[0]};
  for (double b : br)
    if (b - breaks.back() > 1e-13)
      breaks.push_back(b);
  breaks.back() = 1;
  PiecewiseSurface C;
  C.degree_u = p;
  C.degree_v = 1;
  C.closed_u = false;
  C.breaks_u = Eigen::Map<Eigen::VectorXd>(breaks.data(), static_cast<Index>(breaks.size()));
  C.breaks_v = Eigen::Vector2d(0, 1);
  const Index spans = C.breaks_u.size() - 1;
  C.coeffs.resize(spans * (p + 1) * 2, 3);
  Eigen::MatrixXd V(p + 1, p + 1);
  for (int r = 0; r <= p; ++r)
    for (int q = 0; q <= p; ++q)
      V(r, q) = std::pow((r + 0.5) / (p + 1), q);
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(V);
  for (Index a = 0; a < spans; ++a) {
    const double s0 = C.breaks_u(a), h = C.breaks_u(a + 1) - s0;
    Eigen::MatrixXd A(p + 1, 3), B(p + 1, 3);
    for (int r = 0; r <= p; ++r) {
      const double s = s0 + h * (r + 0.5) / (p + 1);
      A.row(r) = evaluate(S, m.side_one(s), ve).transpose();
      B.row(r) = evaluate(S, m.side_two(s), ve).transpose();
    }
    const Eigen::MatrixXd ca = lu.solve(A), cb = lu.solve(B);
    for (int q = 0; q <= p; ++q) {
      const double scale = std::pow(h, -q); // coefficient of (s - s0)^q
      C.coeffs.row((a * (p + 1) + q) * 2 + 0) = scale * ca.row(q);
      C.coeffs.row((a * (p + 1) + q) * 2 + 1) = scale * (cb.row(q) - ca.row(q));
    }
  }
  return C;
}

// Mean point of the loop at v and its vector area (Newell), from n samples.
void loop_frame(const PiecewiseSurface& S, double v, Vector3d& mean, Vector3d& area) {
  const int n = 256;
  mean.setZero();
  area.setZero();
  Vector3d prev = evaluate(S, 0.0, v);
  for (int i = 1; i <= n; ++i) {
    const Vector3d x = evaluate(S, i == n ? 0.0 : double(i) / n, v);
    area += 0.5 * prev.cross(x);
    mean += x / n;
    prev = x;
  }
}

// The cap parameters (s, t) of the loop point S(u, v_e): side one (t = 0) or side two (t = 1).
Eigen::Vector2d cap_parameters(const CapMap& m, double u) {
  if (u >= m.ua && u <= m.ub)
    return {(u - m.ua) / (m.ub - m.ua), 0};
  const double w = u > m.ua ? u - 1 : u; // in (u_b - 1, u_a)
  return {std::clamp((m.ua - w) / (1 - (m.ub - m.ua)), 0.0, 1.0), 1};
}

// The side's outward normal with the span chord in place of S_v: S_u x (S(u, v + w) -
// S(u, v - w)), w a tenth of the span, oriented. Where the span spline overshoots between close
// sections and returns (a fold: Rotor 37's tip, 5e-4 cm), S_v runs backwards and S_u x S_v is
// reversed; the chord keeps the normal of the unfolded sheet. `folded` tells whether S_v runs
// against the chord at (u, v).
Vector3d side_normal(const BodyPatches& b, double u, double v, bool* folded) {
  const PiecewiseSurface& S = b.patches[0];
  const Eigen::Vector4d dom = domain(S);
  const double w = 0.1 * (dom(3) - dom(2));
  const Vector3d chord =
      evaluate(S, u, std::min(dom(3), v + w)) - evaluate(S, u, std::max(dom(2), v - w));
  const SurfaceJet J = evaluate_jet(S, u, v);
  if (folded)
    *folded = J.Sv.dot(chord) < 0;
  return (b.orientation[0] * J.Su.cross(chord)).normalized();
}

// The fold of the end at v = ve (body_patches.h): scans v from the end inward over a twentieth
// of the span on 256 loop points for the turn where S_v runs against the chord. Sets the fold
// zone (twice the turning line's largest distance from the loop, 0 without a fold) and the
// parameter where the fold region ends (three times its deepest turn: the turn's neighbourhood,
// where the normal sweeps round, belongs to the edge too).
void find_fold(BodyPatches& b, int end) {
  const PiecewiseSurface& S = b.patches[0];
  const Eigen::Vector4d dom = domain(S);
  const double ve = end == 0 ? dom(2) : dom(3), inward = end == 0 ? 1 : -1;
  const double reach = 0.05 * (dom(3) - dom(2));
  double zone = 0, depth = 0;
  for (int i = 0; i < 256; ++i) {
    const double u = i / 256.0;
    const Vector3d loop = evaluate(S, u, ve);
    for (int j = 0; j <= 400; ++j) {
      const double v = ve + inward * reach * j / 400;
      bool folded = false;
      side_normal(b, u, v, &folded);
      if (!folded) {
        if (j > 0) {
          zone = std::max(zone, 2 * (evaluate(S, u, v) - loop).norm());
          depth = std::max(depth, reach * j / 400);
        }
        break;
      }
    }
  }
  b.fold_zone[static_cast<size_t>(end)] = zone;
  b.fold_v[static_cast<size_t>(end)] = zone > 0 ? ve + inward * 3 * depth : ve - inward;
}

// The foot on a ruled cap C(s, t) = A(s) + t D(s) as a problem in s alone: for each s the
// nearest point of the ruling is explicit (t = (p - A).D / D.D, clamped to [0, 1]), and
// g(s) = |C(s, t(s)) - p|^2 / 2 has g' = r.C_s and, for an interior t, the reduced curvature
// g'' = |C_s|^2 + r.C_ss - (C_s.D + r.D')^2 / D.D (Schur complement of the 2 x 2 Hessian).
// Newton on s with a halving line search; unlike Newton on (s, t) it stays quadratic where the
// rulings shrink to the cap's edge points (s = 0, 1), where the (s, t) parametrisation degenerates.
SurfaceFoot ruled_foot(const PiecewiseSurface& C, const Vector3d& p, double s, int max_iterations) {
  struct Eval {
    double s, t, f;
    Vector3d r, Cs, Css, D, Dp;
  };
  const auto eval = [&](double sv) {
    const SurfaceJet J0 = evaluate_jet(C, sv, 0.0), J1 = evaluate_jet(C, sv, 1.0);
    Eval e;
    e.s = sv;
    e.D = J1.S - J0.S;
    e.Dp = J1.Su - J0.Su;
    const double dd = e.D.squaredNorm();
    e.t = dd > 0 ? std::clamp((p - J0.S).dot(e.D) / dd, 0.0, 1.0) : 0.0;
    e.r = J0.S + e.t * e.D - p;
    e.Cs = J0.Su + e.t * e.Dp;
    e.Css = J0.Suu + e.t * (J1.Suu - J0.Suu);
    e.f = 0.5 * e.r.squaredNorm();
    return e;
  };
  Eval e = eval(std::clamp(s, 0.0, 1.0));
  const double tiny = 1e-15 * (p.cwiseAbs().maxCoeff() + 1);
  SurfaceFoot F;
  for (; F.iterations < max_iterations; ++F.iterations) {
    const double g1 = e.r.dot(e.Cs), a = e.Cs.squaredNorm(), dd = e.D.squaredNorm();
    double g2 = a + e.r.dot(e.Css);
    if (e.t > 0 && e.t < 1 && dd > 0)
      g2 -= std::pow(e.Cs.dot(e.D) + e.r.dot(e.Dp), 2) / dd;
    if (!(g2 > 0))
      g2 = a;
    double ds = g2 > 0 ? -g1 / g2 : 0;
    if ((e.s <= 0 && ds < 0) || (e.s >= 1 && ds > 0) || !std::isfinite(ds) || ds == 0)
      break;
    bool moved = false;
    for (int ls = 0; ls < 40; ++ls, ds *= 0.5) {
      const Eval n = eval(std::clamp(e.s + ds, 0.0, 1.0));
      if (n.f <= e.f + 1e-13 * e.f + 1e-300) {
        moved = (n.r - e.r).norm() > tiny;
        e = n;
        break;
      }
    }
    if (!moved)
      break;
  }
  F.u = e.s;
  F.v = e.t;
  F.jet = evaluate_jet(C, e.s, e.t);
  F.distance = e.r.norm();
  F.clamped_u = e.s <= 0 || e.s >= 1;
  F.clamped_v = e.t <= 0 || e.t >= 1;
  return F;
}

} // namespace

BodyPatches body_patches(const BSplineSurface& side, const std::array<Eigen::Vector2d, 2>& edge_u) {
  check_surface(side);
  if (!side.closed_u)
    throw std::invalid_argument("body_patches: the side surface must be closed around (u)");
  BodyPatches b;
  b.edge_u = edge_u;
  b.patches[0] = to_piecewise(side);
  const PiecewiseSurface& S = b.patches[0];
  const Eigen::Vector4d dom = domain(S);
  if (dom(0) != 0 || dom(1) != 1)
    throw std::invalid_argument("body_patches: the side surface's u domain must be [0, 1]");
  for (int e = 0; e < 2; ++e) {
    const double ua = edge_u[e](0), ub = edge_u[e](1);
    if (!(0 <= ua && ua < ub && ub < 1))
      throw std::invalid_argument("body_patches: cap edges need 0 <= u_a < u_b < 1");
    b.patches[1 + e] = ruled_cap(S, e == 0 ? dom(2) : dom(3), CapMap{ua, ub});
  }
  // Orientation: a loop running counter-clockwise around the span direction has S_u x S_v
  // pointing out.
  Vector3d m0, m1, mid, a0, a1, area;
  loop_frame(S, dom(2), m0, a0);
  loop_frame(S, dom(3), m1, a1);
  loop_frame(S, 0.5 * (dom(2) + dom(3)), mid, area);
  const Vector3d span = m1 - m0;
  b.orientation[0] = area.dot(span) >= 0 ? 1 : -1;
  for (int e = 0; e < 2; ++e) {
    const Vector3d out = e == 0 ? Vector3d(m0 - mid) : Vector3d(m1 - mid);
    Vector3d n = Vector3d::Zero();
    for (int i = 1; i < 20; ++i) {
      const SurfaceJet J = evaluate_jet(b.patches[1 + e], i / 20.0, 0.5);
      n += J.Su.cross(J.Sv);
    }
    b.orientation[1 + e] = n.dot(out) >= 0 ? 1 : -1;
    b.cap_normal[e] = (b.orientation[1 + e] * n).normalized();
  }
  find_fold(b, 0);
  find_fold(b, 1);
  return b;
}

Vector3d evaluate(const BodyPatches& b, const PatchSeed& at) {
  return evaluate(b.patches[static_cast<size_t>(at.patch)], at.u, at.v);
}

BodyDistance body_distance(const BodyPatches& b, const Vector3d& p, const PatchSeed* seeds,
                           int count, int max_iterations) {
  BodyDistance out;
  SurfaceFoot best;
  best.distance = INFINITY;
  int best_patch = -1;
  for (int i = 0; i < count; ++i) {
    const PiecewiseSurface& P = b.patches[static_cast<size_t>(seeds[i].patch)];
    const SurfaceFoot f = seeds[i].patch == 0
                              ? surface_foot(P, p, seeds[i].u, seeds[i].v, max_iterations)
                              : ruled_foot(P, p, seeds[i].u, max_iterations);
    // Ties (a foot on an end loop is on the side and on a cap) go to the earlier patch.
    if (f.distance < best.distance ||
        (f.distance == best.distance && seeds[i].patch < best_patch)) {
      best = f;
      best_patch = seeds[i].patch;
    }
  }
  if (best_patch < 0 || !std::isfinite(best.distance))
    return out;
  out.found = true;
  out.seed = {best_patch, best.u, best.v};
  out.foot = best.jet.S;
  // Pseudo-normal at the foot (outward). A side foot on an end loop or in a fold next to it is
  // an edge foot: the convex edge between side and cap.
  const Eigen::Vector4d dom = domain(b.patches[0]);
  int end = -1;
  double u_loop = 0;
  Vector3d n;
  if (best_patch == 0) {
    const int e = best.v < 0.5 * (dom(2) + dom(3)) ? 0 : 1;
    const double fv = b.fold_v[static_cast<size_t>(e)];
    bool edge = best.clamped_v;
    if (!edge && (e == 0 ? best.v <= fv : best.v >= fv)) { // in the fold region of end e
      bool folded = false;
      side_normal(b, best.u, best.v, &folded);
      edge = folded ||
             (best.jet.S - evaluate(b.patches[0], best.u, e == 0 ? dom(2) : dom(3))).norm() <=
                 b.fold_zone[static_cast<size_t>(e)];
    }
    if (edge) {
      end = e;
      u_loop = best.u;
    } else {
      n = (b.orientation[0] * best.jet.Su.cross(best.jet.Sv)).normalized();
    }
  } else if (best.clamped_u || best.clamped_v) {
    end = best_patch - 1;
    const CapMap m{b.edge_u[static_cast<size_t>(end)](0), b.edge_u[static_cast<size_t>(end)](1)};
    const double s = std::clamp(best.u, 0.0, 1.0);
    u_loop = best.v <= 0.5 ? m.side_one(s) : m.side_two(s);
  } else {
    n = (b.orientation[static_cast<size_t>(best_patch)] * best.jet.Su.cross(best.jet.Sv))
            .normalized();
  }
  if (end >= 0) { // side normal plus cap normal
    const CapMap m{b.edge_u[static_cast<size_t>(end)](0), b.edge_u[static_cast<size_t>(end)](1)};
    const Eigen::Vector2d st = cap_parameters(m, u_loop);
    const SurfaceJet C = evaluate_jet(b.patches[static_cast<size_t>(end) + 1], st(0), st(1));
    const Vector3d nc = C.Su.cross(C.Sv);
    n = side_normal(b, u_loop, end == 0 ? dom(2) : dom(3), nullptr) +
        (nc.norm() > 1e-9 * C.Su.squaredNorm()
             ? Vector3d(b.orientation[static_cast<size_t>(end) + 1] * nc.normalized())
             : b.cap_normal[static_cast<size_t>(end)]);
  }
  const Vector3d r = p - best.jet.S;
  const double sign = r.dot(n) > 0 ? -1.0 : 1.0; // outside -> negative
  out.distance = sign * best.distance;
  // The unit vector from the foot is the gradient; within 1e-7 of the scale of p the foot's
  // round-off would turn it at random, and the inward normal, its limit, takes over.
  out.gradient = best.distance > 1e-7 * (p.cwiseAbs().maxCoeff() + 1)
                     ? Vector3d(sign * r / best.distance)
                     : Vector3d(-n.normalized());
  return out;
}

} // namespace interlin
