#include "interlin/reconstruction/meshing/surface_mesh.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace interlin {

namespace {

// Share of the u-sample weight given to arc length, to turning angle and to plain u.
constexpr double kArcShare = 0.495, kTurnShare = 0.495, kUniformShare = 0.01;
// Rows S(., v) whose geometry drives the u distribution.
constexpr int kRows = 5;

double turning_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// nu u values distributed by arc length + turning angle of a few u-curves (see header).
Eigen::VectorXd sample_u(const PiecewiseSurface& s, int nu, const Eigen::Vector4d& dom) {
  const bool closed = s.closed_u;
  const double u0 = dom(0), u1 = dom(1);
  // Fine grid: every polynomial span of u cut into m equal pieces, at least 8 per final sample.
  const Eigen::Index spans = s.breaks_u.size() - 1; // >= 1, checked by the caller
  const Eigen::Index m = std::max<Eigen::Index>(8, (8 * nu + spans - 1) / spans);
  const Eigen::Index M = spans * m; // fine intervals
  Eigen::VectorXd uf(M + 1);
  for (Eigen::Index a = 0; a < spans; ++a) {
    const double b0 = s.breaks_u(a), b1 = s.breaks_u(a + 1);
    for (Eigen::Index q = 0; q < m; ++q)
      uf(a * m + q) = b0 + (b1 - b0) * double(q) / double(m);
  }
  uf(M) = u1;
  Eigen::VectorXd vr(kRows);
  for (int r = 0; r < kRows; ++r)
    vr(r) = dom(2) + (dom(3) - dom(2)) * double(r) / double(kRows - 1);
  const Eigen::MatrixXd P = evaluate_grid(s, uf, vr); // (M+1) * kRows by 3

  // w(j): weight of fine interval j, averaged over the rows that are not degenerate.
  Eigen::VectorXd w = Eigen::VectorXd::Zero(M);
  int used = 0;
  Eigen::VectorXd len(M), turn(M);
  for (int r = 0; r < kRows; ++r) {
    auto pt = [&](Eigen::Index j) -> Eigen::Vector3d { return P.row(j + (M + 1) * r); };
    for (Eigen::Index j = 0; j < M; ++j)
      len(j) = (pt(j + 1) - pt(j)).norm();
    const double L = len.sum();
    if (!(L > 0) || !std::isfinite(L))
      continue;
    // Turning at fine vertex j (between intervals j-1 and j), half to each neighbour; on a
    // closed curve the seam vertex joins interval M-1 and interval 0.
    turn.setZero();
    for (Eigen::Index j = closed ? 0 : 1; j < M; ++j) {
      const Eigen::Index prev = j == 0 ? M - 1 : j - 1;
      if (len(prev) == 0 || len(j) == 0)
        continue;
      const double t = turning_angle(pt(prev + 1) - pt(prev), pt(j + 1) - pt(j));
      turn(prev) += 0.5 * t;
      turn(j) += 0.5 * t;
    }
    const double T = turn.sum();
    if (T > 0)
      w += kArcShare * len / L + kTurnShare * turn / T;
    else
      w += (kArcShare + kTurnShare) * len / L;
    ++used;
  }
  if (used > 0)
    w /= double(used);
  for (Eigen::Index j = 0; j < M; ++j)
    w(j) += (used > 0 ? kUniformShare : 1.0) * (uf(j + 1) - uf(j)) / (u1 - u0);

  // Invert the cumulative weight at equally spaced levels.
  Eigen::VectorXd C(M + 1);
  C(0) = 0;
  for (Eigen::Index j = 0; j < M; ++j)
    C(j + 1) = C(j) + w(j);
  const double total = C(M);
  const int n_levels = closed ? nu : nu - 1;
  Eigen::VectorXd u(nu);
  Eigen::Index j = 0;
  for (int k = 0; k < nu; ++k) {
    const double level = total * double(k) / double(n_levels);
    while (j < M - 1 && C(j + 1) <= level)
      ++j;
    const double t = w(j) > 0 ? std::clamp((level - C(j)) / w(j), 0.0, 1.0) : 0.0;
    u(k) = uf(j) + t * (uf(j + 1) - uf(j));
  }
  u(0) = u0;
  if (!closed)
    u(nu - 1) = u1;
  return u;
}

// nv uniform values merged with the required ones (see header).
Eigen::VectorXd sample_v(int nv, const std::vector<double>& required, const Eigen::Vector4d& dom) {
  const double v0 = dom(2), v1 = dom(3), h = (v1 - v0) / double(nv - 1);
  const double tol = 1e-12 * std::max(1.0, std::abs(v1 - v0));
  std::vector<double> req;
  for (double r : required) {
    if (!std::isfinite(r) || r < v0 - tol || r > v1 + tol)
      throw std::invalid_argument("surface_mesh: required_v value " + std::to_string(r) +
                                  " outside the v domain [" + std::to_string(v0) + ", " +
                                  std::to_string(v1) + "]");
    req.push_back(std::clamp(r, v0, v1));
  }
  std::sort(req.begin(), req.end());
  req.erase(std::unique(req.begin(), req.end()), req.end());
  std::vector<double> v(req);
  for (int k = 0; k < nv; ++k) {
    const double x = k == nv - 1 ? v1 : v0 + h * double(k);
    const auto it = std::lower_bound(req.begin(), req.end(), x);
    const bool near = (it != req.end() && *it - x < 0.25 * h) ||
                      (it != req.begin() && x - *std::prev(it) < 0.25 * h);
    if (!near)
      v.push_back(x);
  }
  std::sort(v.begin(), v.end());
  return Eigen::Map<const Eigen::VectorXd>(v.data(), Eigen::Index(v.size()));
}

double signed_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, Eigen::Index rows,
                     const Eigen::RowVector3d& origin) {
  double vol = 0;
  for (Eigen::Index f = 0; f < rows; ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)) - origin, b = V.row(F(f, 1)) - origin,
                          c = V.row(F(f, 2)) - origin;
    vol += a.dot(b.cross(c));
  }
  return vol / 6.0;
}

// Volume of the fan from the centroid of loop (indices in traversal order) to its edges.
double fan_volume(const Eigen::MatrixXd& V, const std::vector<int>& loop,
                  const Eigen::RowVector3d& origin) {
  Eigen::RowVector3d c = Eigen::RowVector3d::Zero();
  for (int i : loop)
    c += V.row(i);
  c /= double(loop.size());
  const Eigen::Vector3d cc = c - origin;
  double vol = 0;
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const Eigen::Vector3d a = V.row(loop[k]) - origin;
    const Eigen::Vector3d b = V.row(loop[(k + 1) % loop.size()]) - origin;
    vol += cc.dot(a.cross(b));
  }
  return vol / 6.0;
}

} // namespace

void surface_mesh(const PiecewiseSurface& s, const SurfaceMeshOptions& o, Eigen::MatrixXd& V,
                  Eigen::MatrixXi& F, Eigen::VectorXd* u_samples, Eigen::VectorXd* v_samples) {
  if (o.nu < 3)
    throw std::invalid_argument("surface_mesh: nu must be >= 3, got " + std::to_string(o.nu));
  if (o.nv < 2)
    throw std::invalid_argument("surface_mesh: nv must be >= 2, got " + std::to_string(o.nv));
  if (o.cap && !s.closed_u)
    throw std::invalid_argument("surface_mesh: cap needs a closed_u surface");
  if (s.breaks_u.size() < 2 || s.breaks_v.size() < 2 ||
      s.coeffs.rows() !=
          (s.breaks_u.size() - 1) * (s.breaks_v.size() - 1) * (s.degree_u + 1) * (s.degree_v + 1) ||
      s.coeffs.cols() != 3)
    throw std::invalid_argument("surface_mesh: inconsistent PiecewiseSurface (use to_piecewise)");
  const Eigen::Vector4d dom = domain(s);
  if (!(dom(1) > dom(0)) || !(dom(3) > dom(2)))
    throw std::invalid_argument("surface_mesh: empty parameter domain");

  const Eigen::VectorXd u = sample_u(s, o.nu, dom);
  const Eigen::VectorXd v = sample_v(o.nv, o.required_v, dom);
  const int nu = o.nu, nv = int(v.size());
  V = evaluate_grid(s, u, v); // row i + nu * k = S(u(i), v(k))

  const bool closed = s.closed_u;
  const int quads_u = closed ? nu : nu - 1;
  const Eigen::Index grid_faces = Eigen::Index(2) * quads_u * (nv - 1);
  F.resize(grid_faces + (o.cap ? 2 * (nu - 2) : 0), 3);
  Eigen::Index f = 0;
  for (int k = 0; k + 1 < nv; ++k)
    for (int i = 0; i < quads_u; ++i) {
      const int i1 = (i + 1) % nu;
      const int a = i + nu * k, b = i1 + nu * k, c = i1 + nu * (k + 1), d = i + nu * (k + 1);
      // Shorter diagonal; both triangles follow S_u x S_v.
      if ((V.row(a) - V.row(c)).squaredNorm() <= (V.row(b) - V.row(d)).squaredNorm()) {
        F.row(f++) << a, b, c;
        F.row(f++) << a, c, d;
      } else {
        F.row(f++) << a, b, d;
        F.row(f++) << b, c, d;
      }
    }
  if (!closed) {
    if (u_samples)
      *u_samples = u;
    if (v_samples)
      *v_samples = v;
    return;
  }

  // Boundary loops in the direction that matches the grid faces: the grid uses the edge
  // (i -> i+1) on the row at v0 and (i+1 -> i) on the row at v1, so a cap must run the other way.
  std::vector<int> bottom(nu), top(nu);
  for (int i = 0; i < nu; ++i) {
    bottom[i] = nu - 1 - i;
    top[i] = i + nu * (nv - 1);
  }
  const Eigen::RowVector3d origin =
      0.5 * (V.colwise().minCoeff() + V.colwise().maxCoeff()); // better-conditioned volumes
  double vol = signed_volume(V, F, grid_faces, origin);
  if (o.cap) {
    for (const std::vector<int>* loop : {&bottom, &top}) {
      Eigen::MatrixXd P(nu, 3);
      for (int i = 0; i < nu; ++i)
        P.row(i) = V.row((*loop)[i]);
      const Eigen::MatrixXi T = triangulate_loop(P);
      for (Eigen::Index r = 0; r < T.rows(); ++r)
        F.row(f++) << (*loop)[T(r, 0)], (*loop)[T(r, 1)], (*loop)[T(r, 2)];
    }
    vol = signed_volume(V, F, F.rows(), origin);
  } else {
    vol += fan_volume(V, bottom, origin) + fan_volume(V, top, origin);
  }
  if (vol < 0)
    F.col(1).swap(F.col(2));
  if (u_samples)
    *u_samples = u;
  if (v_samples)
    *v_samples = v;
}

} // namespace interlin
