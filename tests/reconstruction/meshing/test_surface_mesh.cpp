#include "interlin/reconstruction/io/mesh_io.h"
#include "interlin/reconstruction/meshing/mesh_check.h"
#include "interlin/reconstruction/meshing/surface_mesh.h"
#include "interlin/splines/bspline_curve.h"
#include "interlin/splines/bspline_surface.h"
#include "interlin/splines/knot_insertion.h"

#include "support/test_support.h"
#include <Eigen/Geometry>
#include <algorithm>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <string>
#include <tuple>
#include <unistd.h>
#include <vector>

using namespace interlin;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::MatrixXi;
using Eigen::Vector3d;
using Eigen::VectorXd;

namespace {

// Closed clamped cubic from the uniform periodic cubic B-spline whose distinct control points
// are the rows of Q (m by 2): knots 0..m+6, control points Q_0..Q_{m-1}, Q_0, Q_1, Q_2, then
// clamped over one period [3, m+3] (closed and C^2 at the seam by construction).
BSplineCurve closed_section(const MatrixXd& Q) {
  const Index m = Q.rows();
  BSplineCurve c;
  c.degree = 3;
  c.periodic = true;
  c.ctrl.resize(m + 3, 2);
  for (Index i = 0; i < m + 3; ++i)
    c.ctrl.row(i) = Q.row(i % m);
  c.knots = VectorXd::LinSpaced(m + 7, 0.0, double(m + 6));
  return periodic_to_clamped(c, 3.0);
}

MatrixXd ellipse_polygon(int m, double a, double b) {
  MatrixXd Q(m, 2);
  for (int j = 0; j < m; ++j) {
    const double t = 2 * M_PI * j / m;
    Q.row(j) << a * std::cos(t), b * std::sin(t);
  }
  return Q;
}

// Control polygon of a thin, strongly cambered blade profile (chord 1, 6% thick, 15% camber):
// counter-clockwise from the trailing edge over the suction side to the leading edge and back
// over the concave pressure side. Cosine spacing crowds the points at both edges.
MatrixXd blade_polygon(int half) {
  MatrixXd Q(2 * half, 2);
  for (int k = 0; k < 2 * half; ++k) {
    const double beta = M_PI * k / half;
    const double x = 0.5 * (1 + std::cos(beta));
    const double camber = 0.15 * 4 * x * (1 - x), thick = 0.06 * 4 * x * (1 - x) + 0.004;
    Q.row(k) << x, camber + (std::sin(beta) >= 0 ? 0.5 : -0.5) * thick;
  }
  return Q;
}

// Sweep of the closed section C along z: S(u, v) = s(v) R(phi(v)) C(u) + H v e_z, with the
// cubic v-direction taken over nvc control rows (uniform clamped knots on [0, 1]); row j is
// the section scaled by 1 + taper g_j and turned by twist g_j (g_j Greville abscissae, so that
// z(v) = H v exactly by linear precision). frame(v) = sum_j M_j(v) s_j (cos phi_j, sin phi_j):
// the section at v is the scaled rotation frame(v) applied to C, its area |frame(v)|^2 area(C).
struct Sweep {
  BSplineSurface surface;
  BSplineCurve section, frame;
  double height = 1;
};

Sweep make_sweep(const BSplineCurve& C, int nvc, double height, double twist, double taper) {
  Sweep w;
  w.section = C;
  w.height = height;
  VectorXd kv(nvc + 4);
  kv.head(4).setZero();
  kv.tail(4).setOnes();
  for (int i = 1; i <= nvc - 4; ++i)
    kv(3 + i) = double(i) / double(nvc - 3);
  w.frame.degree = 3;
  w.frame.knots = kv;
  w.frame.ctrl.resize(nvc, 2);
  BSplineSurface& s = w.surface;
  s.degree_u = s.degree_v = 3;
  s.knots_u = C.knots;
  s.knots_v = kv;
  s.num_u = C.ctrl.rows();
  s.num_v = nvc;
  s.closed_u = true;
  s.ctrl.resize(s.num_u * s.num_v, 3);
  for (int j = 0; j < nvc; ++j) {
    const double g = (kv(j + 1) + kv(j + 2) + kv(j + 3)) / 3.0;
    const double sc = 1 + taper * g, phi = twist * g;
    w.frame.ctrl.row(j) << sc * std::cos(phi), sc * std::sin(phi);
    for (Index i = 0; i < s.num_u; ++i) {
      const double x = C.ctrl(i, 0), y = C.ctrl(i, 1);
      s.ctrl.row(i + s.num_u * j) << sc * (std::cos(phi) * x - std::sin(phi) * y),
          sc * (std::sin(phi) * x + std::cos(phi) * y), height * g;
    }
  }
  return w;
}

// Gauss–Legendre rule on [a, b] with n = 3 or 4 points (exact for degree 2n - 1).
template <class Fn>
double gauss(double a, double b, int n, Fn f) {
  static const double x3[] = {-0.7745966692414834, 0.0, 0.7745966692414834};
  static const double w3[] = {0.5555555555555556, 0.8888888888888888, 0.5555555555555556};
  static const double x4[] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                              0.8611363115940526};
  static const double w4[] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                              0.3478548451374538};
  const double* x = n == 3 ? x3 : x4;
  const double* w = n == 3 ? w3 : w4;
  double sum = 0;
  for (int k = 0; k < n; ++k)
    sum += w[k] * f(0.5 * (a + b) + 0.5 * (b - a) * x[k]);
  return 0.5 * (b - a) * sum;
}

// Exact volume of the capped sweep: H * area(C) * int_0^1 |frame(v)|^2 dv. The integrands are
// polynomials on each knot span (degree 5 in u, 6 in v), so 3- and 4-point Gauss are exact.
double exact_volume(const Sweep& w) {
  double area = 0;
  const VectorXd& ku = w.section.knots;
  for (Index k = 0; k + 1 < ku.size(); ++k)
    if (ku(k) < ku(k + 1))
      area += gauss(ku(k), ku(k + 1), 3, [&](double u) {
        VectorXd uu(1);
        uu << u;
        const MatrixXd p = evaluate(w.section, uu), d = evaluate(w.section, uu, 1);
        return 0.5 * (p(0, 0) * d(0, 1) - p(0, 1) * d(0, 0));
      });
  double growth = 0;
  const VectorXd& kv = w.frame.knots;
  for (Index k = 0; k + 1 < kv.size(); ++k)
    if (kv(k) < kv(k + 1))
      growth += gauss(kv(k), kv(k + 1), 4, [&](double v) {
        VectorXd vv(1);
        vv << v;
        return evaluate(w.frame, vv).row(0).squaredNorm();
      });
  return w.height * area * growth;
}

Sweep twisted_ellipse_tube() {
  return make_sweep(closed_section(ellipse_polygon(12, 1.0, 0.6)), 7, 2.0, 0.8, 0.3);
}

Sweep twisted_blade() {
  return make_sweep(closed_section(blade_polygon(24)), 6, 0.8, 0.6, -0.2);
}

// Number of closed boundary loops: connected components of the boundary-edge graph.
long boundary_loops(const MatrixXi& F, Index nv) {
  std::vector<std::pair<long, long>> e;
  for (Index f = 0; f < F.rows(); ++f)
    for (int j = 0; j < 3; ++j) {
      const long a = F(f, j), b = F(f, (j + 1) % 3);
      e.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(e.begin(), e.end());
  std::vector<long> parent(static_cast<std::size_t>(nv));
  std::iota(parent.begin(), parent.end(), 0L);
  auto find = [&](long x) {
    while (parent[std::size_t(x)] != x)
      x = parent[std::size_t(x)];
    return x;
  };
  std::vector<char> on_boundary(static_cast<std::size_t>(nv), 0);
  for (std::size_t i = 0; i < e.size();) {
    std::size_t j = i;
    while (j < e.size() && e[j] == e[i])
      ++j;
    if (j - i == 1) {
      on_boundary[std::size_t(e[i].first)] = on_boundary[std::size_t(e[i].second)] = 1;
      parent[std::size_t(find(e[i].first))] = find(e[i].second);
    }
    i = j;
  }
  long loops = 0;
  for (long v = 0; v < nv; ++v)
    loops += on_boundary[std::size_t(v)] && find(v) == v;
  return loops;
}

// Exterior angle at each vertex of the closed polygon P (rows).
VectorXd turning_angles(const MatrixXd& P) {
  const Index n = P.rows();
  VectorXd t(n);
  for (Index i = 0; i < n; ++i) {
    const Vector3d a = P.row(i) - P.row((i + n - 1) % n), b = P.row((i + 1) % n) - P.row(i);
    t(i) = std::atan2(a.cross(b).norm(), a.dot(b));
  }
  return t;
}

} // namespace

TEST_CASE("check_mesh on meshes with known topology and geometry", "[mesh]") {
  MatrixXd V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  MatrixXi F(4, 3);
  F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3; // outward
  SECTION("tetrahedron") {
    const MeshReport r = check_mesh(V, F);
    CHECK(r.vertices == 4);
    CHECK(r.faces == 4);
    CHECK(r.boundary_edges == 0);
    CHECK(r.nonmanifold_edges == 0);
    CHECK(r.nonmanifold_vertices == 0);
    CHECK(r.components == 1);
    CHECK(r.euler == 2);
    CHECK(r.genus == 0);
    CHECK(r.consistently_oriented);
    CHECK(r.watertight());
    // Closed forms: volume 1/6; area 3 * 1/2 + sqrt(3)/2; right isosceles faces have the
    // smallest angle 45 deg and aspect sqrt(3) l^2 / (4 A) = sqrt(3) (l = sqrt 2, A = 1/2).
    // Tolerance: a few rounding errors of O(1) sums.
    CHECK(r.volume == Approx(1.0 / 6.0).epsilon(1e-14));
    CHECK(r.area == Approx(1.5 + std::sqrt(3.0) / 2).epsilon(1e-14));
    CHECK(r.min_angle_deg == Approx(45.0).epsilon(1e-12));
    CHECK(r.max_aspect_ratio == Approx(std::sqrt(3.0)).epsilon(1e-12));
    CHECK(r.degenerate_faces == 0);
  }
  SECTION("flipped face breaks the orientation") {
    F.row(3) << 1, 3, 2;
    const MeshReport r = check_mesh(V, F);
    CHECK(r.boundary_edges == 0);
    CHECK_FALSE(r.consistently_oriented);
    CHECK_FALSE(r.watertight());
    CHECK(r.genus == -1);
  }
  SECTION("open, two components, bow tie, fin, degenerate face") {
    // One face removed: 3 boundary edges.
    MeshReport r = check_mesh(V, F.topRows(3));
    CHECK(r.boundary_edges == 3);
    CHECK(r.consistently_oriented);
    CHECK(r.genus == -1);
    CHECK(r.euler == 1); // a disk
    // Two disjoint tetrahedra: genus 0 + 0, Euler characteristic 2 + 2.
    MatrixXd V2(8, 3);
    V2 << V, V.rowwise() + Eigen::RowVector3d(5, 0, 0);
    MatrixXi F2(8, 3);
    F2 << F, F.array() + 4;
    r = check_mesh(V2, F2);
    CHECK(r.components == 2);
    CHECK(r.euler == 4);
    CHECK(r.genus == 0);
    CHECK(r.volume == Approx(2.0 / 6.0).epsilon(1e-14));
    // Two tetrahedra glued at one vertex: that vertex has two fans.
    MatrixXd V3(7, 3);
    V3 << V, -V.bottomRows(3);
    MatrixXi F3(8, 3);
    F3 << F, 0, 5, 4, 0, 4, 6, 0, 6, 5, 4, 5, 6;
    r = check_mesh(V3, F3);
    CHECK(r.nonmanifold_vertices == 1);
    CHECK(r.nonmanifold_edges == 0);
    CHECK_FALSE(r.watertight());
    CHECK(r.genus == -1);
    // A fin: a third face on edge (0, 1).
    MatrixXd V4(5, 3);
    V4 << V, 0.5, -1, 0.5;
    MatrixXi F4(5, 3);
    F4 << F, 0, 1, 4;
    r = check_mesh(V4, F4);
    CHECK(r.nonmanifold_edges == 1);
    CHECK_FALSE(r.consistently_oriented);
    // A face with three collinear points.
    MatrixXd V5(3, 3);
    V5 << 0, 0, 0, 1, 1, 1, 2, 2, 2;
    r = check_mesh(V5, MatrixXi(MatrixXi::Map(std::vector<int>{0, 1, 2}.data(), 1, 3)));
    CHECK(r.degenerate_faces == 1);
    CHECK_THROWS_AS(check_mesh(V5, MatrixXi::Constant(1, 3, 3)), std::invalid_argument);
  }
  SECTION("torus grid has genus 1") {
    const int n = 12, m = 8;
    MatrixXd T(n * m, 3);
    MatrixXi FT(2 * n * m, 3);
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < n; ++i) {
        const double a = 2 * M_PI * i / n, b = 2 * M_PI * j / m;
        T.row(i + n * j) << (2 + std::cos(b)) * std::cos(a), (2 + std::cos(b)) * std::sin(a),
            std::sin(b);
        const int p = i + n * j, q = (i + 1) % n + n * j, r2 = (i + 1) % n + n * ((j + 1) % m),
                  s = i + n * ((j + 1) % m);
        FT.row(2 * p) << p, q, r2;
        FT.row(2 * p + 1) << p, r2, s;
      }
    const MeshReport r = check_mesh(T, FT);
    CHECK(r.euler == 0);
    CHECK(r.genus == 1);
    CHECK(r.watertight());
  }
}

TEST_CASE("surface_mesh of an uncapped closed tube", "[mesh]") {
  const Sweep w = twisted_ellipse_tube();
  const PiecewiseSurface s = to_piecewise(w.surface);
  SurfaceMeshOptions o;
  o.nu = 60;
  o.nv = 15;
  MatrixXd V;
  MatrixXi F;
  VectorXd us, vs;
  surface_mesh(s, o, V, F, &us, &vs);
  REQUIRE(us.size() == 60);
  REQUIRE(vs.size() == 15);
  CHECK(V.rows() == 60 * 15);
  CHECK(F.rows() == 2 * 60 * 14);
  // u samples: increasing in [u0, u1) for the closed direction, starting at the seam.
  const Eigen::Vector4d dom = domain(s);
  CHECK(us(0) == dom(0));
  CHECK(us(59) < dom(1));
  for (Index i = 1; i < us.size(); ++i)
    CHECK(us(i) > us(i - 1));
  // No seam duplicates: all vertex positions distinct (rows sorted lexicographically).
  std::vector<Index> order(std::size_t(V.rows()));
  std::iota(order.begin(), order.end(), Index(0));
  std::sort(order.begin(), order.end(), [&](Index a, Index b) {
    return std::tie(V(a, 0), V(a, 1), V(a, 2)) < std::tie(V(b, 0), V(b, 1), V(b, 2));
  });
  double closest = INFINITY;
  for (std::size_t k = 1; k < order.size(); ++k)
    closest = std::min(closest, (V.row(order[k]) - V.row(order[k - 1])).norm());
  CHECK(closest > 1e-6);

  const MeshReport r = check_mesh(V, F);
  CHECK(r.boundary_edges == 2 * 60);
  CHECK(boundary_loops(F, V.rows()) == 2);
  CHECK(r.nonmanifold_edges == 0);
  CHECK(r.nonmanifold_vertices == 0);
  CHECK(r.consistently_oriented);
  CHECK(r.components == 1);
  CHECK(r.euler == 0); // an annulus
  CHECK(r.degenerate_faces == 0);
  // Outward: every face normal points away from the z axis (each section is star-shaped about it).
  long inward = 0;
  for (Index f = 0; f < F.rows(); ++f) {
    const Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Vector3d n = (b - a).cross(c - a), centre = (a + b + c) / 3;
    inward += n.x() * centre.x() + n.y() * centre.y() <= 0;
  }
  CHECK(inward == 0);
}

TEST_CASE("surface_mesh rows at required_v are evaluated exactly there", "[mesh]") {
  const Sweep w = twisted_ellipse_tube();
  const PiecewiseSurface s = to_piecewise(w.surface);
  SurfaceMeshOptions o;
  o.nu = 40;
  o.nv = 11; // spacing 0.1, quarter spacing 0.025
  o.required_v = {0.61, 0.137, 0.5, 0.999, 0.5};
  MatrixXd V;
  MatrixXi F;
  VectorXd us, vs;
  surface_mesh(s, o, V, F, &us, &vs);
  // 0.61 replaces 0.6 and 0.999 replaces 1.0 (closer than 0.025); 0.5 replaces the uniform 0.5;
  // 0.137 is 0.037 from 0.1 and 0.063 from 0.2, so both stay.
  const std::vector<double> expected = {0,   0.1,  0.137, 0.2, 0.3, 0.4,
                                        0.5, 0.61, 0.7,   0.8, 0.9, 0.999};
  REQUIRE(vs.size() == Index(expected.size()));
  for (Index k = 0; k < vs.size(); ++k)
    CHECK(vs(k) ==
          Approx(expected[std::size_t(k)]).epsilon(0).margin(1e-15)); // uniform v0 + k h rounding
  for (double r : {0.61, 0.137, 0.5, 0.999}) {
    const Index k = std::find(vs.data(), vs.data() + vs.size(), r) - vs.data();
    REQUIRE(k < vs.size()); // the required value itself, bitwise
    // The row is S(u_i, r) evaluated at exactly these parameters: identical doubles (the grid is
    // evaluated point by point with the same evaluate()).
    double diff = 0;
    for (Index i = 0; i < us.size(); ++i)
      diff = std::max(
          diff,
          (V.row(i + us.size() * k).transpose() - evaluate(s, us(i), r)).cwiseAbs().maxCoeff());
    CHECK(diff == 0.0);
  }
  CHECK(check_mesh(V, F).degenerate_faces == 0);
}

TEST_CASE("surface_mesh capped tube is a watertight solid whose volume converges at order 2",
          "[mesh]") {
  const Sweep w = twisted_ellipse_tube();
  const PiecewiseSurface s = to_piecewise(w.surface);
  const double exact = exact_volume(w);
  REQUIRE(exact > 0);
  std::vector<double> err;
  for (int level = 0; level < 3; ++level) {
    SurfaceMeshOptions o;
    o.nu = 32 << level;
    o.nv = (8 << level) + 1; // spacing 1/8, 1/16, 1/32
    o.cap = true;
    MatrixXd V;
    MatrixXi F;
    surface_mesh(s, o, V, F);
    CHECK(F.rows() == 2 * o.nu * (o.nv - 1) + 2 * (o.nu - 2));
    const MeshReport r = check_mesh(V, F);
    CHECK(r.watertight());
    CHECK(r.boundary_edges == 0);
    CHECK(r.nonmanifold_edges == 0);
    CHECK(r.nonmanifold_vertices == 0);
    CHECK(r.consistently_oriented);
    CHECK(r.euler == 2);
    CHECK(r.genus == 0);
    CHECK(r.volume > 0);
    err.push_back(std::abs(r.volume - exact));
  }
  // Piecewise-linear interpolation of a smooth surface: volume error O(h^2) in both directions.
  const double p1 = std::log2(err[0] / err[1]), p2 = std::log2(err[1] / err[2]);
  INFO("volume errors " << err[0] << " " << err[1] << " " << err[2] << ", orders " << p1 << " "
                        << p2);
  CHECK(p1 > 1.7);
  CHECK(p1 < 2.3);
  CHECK(p2 > 1.8);
  CHECK(p2 < 2.2);
  CHECK(err[2] < 1e-3 * exact);
}

TEST_CASE("surface_mesh caps a thin cambered blade into a solid", "[mesh]") {
  const Sweep w = twisted_blade();
  const PiecewiseSurface s = to_piecewise(w.surface);
  const double exact = exact_volume(w);
  // 400 x 40 as in production, and 1600 around (tiny leading-edge triangles in the caps).
  for (const auto& [nu, nv] : {std::pair{400, 40}, std::pair{1600, 2}}) {
    INFO("nu " << nu << ", nv " << nv);
    SurfaceMeshOptions o;
    o.nu = nu;
    o.nv = nv;
    o.cap = true;
    MatrixXd V;
    MatrixXi F;
    surface_mesh(s, o, V, F);
    const MeshReport r = check_mesh(V, F);
    CHECK(r.watertight());
    CHECK(r.euler == 2);
    CHECK(r.genus == 0);
    CHECK(r.volume > 0);
    if (nv == 40) // O(h^2) error; measured 7e-5 relative (the v direction dominates)
      CHECK(std::abs(r.volume - exact) < 1e-3 * exact);

    // The loop at v = 0 is non-convex (concave pressure side). Its cap is a valid
    // triangulation: every cap face lies in z = 0 and points down (-z, out of the solid). The
    // mesh being closed and consistently oriented, the cap faces form a 2-chain bounded by the
    // loop; all of them having the same orientation means they tile the polygon without
    // overlap, and then their areas add up to the polygon's (shoelace).
    const Index grid_faces = 2 * Index(nu) * (Index(r.vertices) / nu - 1);
    double cap_area = 0, shoelace = 0;
    long wrong_side = 0;
    for (Index f = grid_faces; f < grid_faces + nu - 2; ++f) {
      const Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
      REQUIRE(a.z() == 0.0);
      const double nz = (b - a).cross(c - a).z();
      wrong_side += nz >= 0;
      cap_area += -0.5 * nz;
    }
    for (int i = 0; i < nu; ++i) {
      const Index j = (i + 1) % nu;
      shoelace += 0.5 * (V(i, 0) * V(j, 1) - V(j, 0) * V(i, 1));
    }
    CHECK(wrong_side == 0);
    CHECK(cap_area == Approx(shoelace).epsilon(1e-12)); // sums of O(1) terms, ~1e-15 each
    // Is the loop really non-convex? Some vertices turn the other way.
    long reflex = 0;
    for (int i = 0; i < nu; ++i) {
      const Vector3d p = V.row((i + nu - 1) % nu), q = V.row(i), t = V.row((i + 1) % nu);
      reflex += (q - p).cross(t - q).z() < 0;
    }
    CHECK(reflex > 10);

    // u distribution: each sample interval carries 1/nu of the weight, 49.5% of which is the
    // share of turning, so the curve turns by at most Theta / (0.495 nu) between samples and
    // a polygon vertex by at most twice that (its exterior angle lies between the tangent
    // directions at its neighbours).
    const VectorXd turn = turning_angles(V.topRows(nu));
    const double Theta = turn.sum();
    INFO("max turning " << turn.maxCoeff() << " rad, total " << Theta);
    CHECK(turn.maxCoeff() <= 2 * Theta / (0.495 * nu));
    // Independent comparison: nu points at equal arc length on the same section (dense
    // polyline, 200 points per sample) turn far more at the leading edge.
    const VectorXd t = VectorXd::LinSpaced(200 * nu + 1, w.section.knots(0),
                                           w.section.knots(w.section.knots.size() - 1));
    const MatrixXd C = evaluate(w.section, t);
    VectorXd arc(t.size());
    arc(0) = 0;
    for (Index k = 1; k < t.size(); ++k)
      arc(k) = arc(k - 1) + (C.row(k) - C.row(k - 1)).norm();
    MatrixXd A = MatrixXd::Zero(nu, 3);
    for (int i = 0, k = 0; i < nu; ++i) {
      const double target = arc(t.size() - 1) * i / nu;
      while (arc(k + 1) < target)
        ++k;
      A.row(i).head<2>() = C.row(k);
    }
    CHECK(turn.maxCoeff() < 0.25 * turning_angles(A).maxCoeff());
  }
}

TEST_CASE("surface_mesh orients clockwise sections outward", "[mesh]") {
  // The same tube with the section running clockwise: S_u x S_v points inward, so the faces
  // must be flipped to give a positive volume.
  const MatrixXd Q = ellipse_polygon(12, 1.0, 0.6).colwise().reverse();
  const Sweep w = make_sweep(closed_section(Q), 7, 2.0, 0.8, 0.3);
  const PiecewiseSurface s = to_piecewise(w.surface);
  SurfaceMeshOptions o;
  o.nu = 64;
  o.nv = 17;
  MatrixXd V;
  MatrixXi F;
  surface_mesh(s, o, V, F);
  long inward = 0;
  for (Index f = 0; f < F.rows(); ++f) {
    const Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Vector3d n = (b - a).cross(c - a), centre = (a + b + c) / 3;
    inward += n.x() * centre.x() + n.y() * centre.y() <= 0;
  }
  CHECK(inward == 0);
  o.cap = true;
  surface_mesh(s, o, V, F);
  const MeshReport r = check_mesh(V, F);
  CHECK(r.watertight());
  CHECK(r.volume > 0);
  // exact_volume is signed by the section's sense; h ~ 1/64 gives ~1e-3 relative error.
  CHECK(r.volume == Approx(-exact_volume(w)).epsilon(0.01));
}

TEST_CASE("surface_mesh of an open surface and argument errors", "[mesh]") {
  // Bilinear plane patch S(u, v) = (2u, v, 0) as a cubic B-spline (control points at the
  // Greville abscissae): the mesh is exact, area 2, normals +z (S_u x S_v).
  BSplineSurface b;
  b.knots_u.resize(8);
  b.knots_u << 0, 0, 0, 0, 1, 1, 1, 1;
  b.knots_v = b.knots_u;
  b.num_u = b.num_v = 4;
  b.ctrl.resize(16, 3);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i)
      b.ctrl.row(i + 4 * j) << 2.0 * i / 3.0, j / 3.0, 0;
  const PiecewiseSurface s = to_piecewise(b);
  SurfaceMeshOptions o;
  o.nu = 7;
  o.nv = 5;
  MatrixXd V;
  MatrixXi F;
  VectorXd us;
  surface_mesh(s, o, V, F, &us);
  CHECK(us(0) == 0.0);
  CHECK(us(6) == 1.0);
  CHECK(F.rows() == 2 * 6 * 4);
  const MeshReport r = check_mesh(V, F);
  CHECK(r.boundary_edges == 2 * 6 + 2 * 4);
  CHECK(r.euler == 1);
  CHECK(r.area == Approx(2.0).epsilon(1e-14));
  for (Index f = 0; f < F.rows(); ++f) {
    const Vector3d a = V.row(F(f, 0)), bb = V.row(F(f, 1)), c = V.row(F(f, 2));
    CHECK((bb - a).cross(c - a).z() > 0);
  }
  o.cap = true;
  CHECK_THROWS_AS(surface_mesh(s, o, V, F), std::invalid_argument); // cap needs closed_u
  o.cap = false;
  o.nu = 2;
  CHECK_THROWS_AS(surface_mesh(s, o, V, F), std::invalid_argument);
  o.nu = 7;
  o.nv = 1;
  CHECK_THROWS_AS(surface_mesh(s, o, V, F), std::invalid_argument);
  o.nv = 5;
  o.required_v = {1.5};
  CHECK_THROWS_AS(surface_mesh(s, o, V, F), std::invalid_argument);
}

TEST_CASE("write_mesh and read_mesh round trip every format", "[mesh]") {
  const Sweep w = twisted_ellipse_tube();
  SurfaceMeshOptions o;
  o.nu = 48;
  o.nv = 12;
  o.cap = true;
  MatrixXd V;
  MatrixXi F;
  surface_mesh(to_piecewise(w.surface), o, V, F);
  const test::TempDir scratch("mesh-roundtrip");
  const auto& dir = scratch.path();
  for (const std::string ext : {".stl", ".obj", ".ply", ".off", ".STL"}) {
    INFO(ext);
    const std::string path = (dir / ("tube" + ext)).string();
    write_mesh(path, V, F);
    REQUIRE(std::filesystem::exists(path));
    MatrixXd Vr;
    MatrixXi Fr;
    read_mesh(path, Vr, Fr);
    REQUIRE(Fr.rows() == F.rows());
    // PLY and OBJ carry doubles exactly; STL stores float32 and OpenMesh hands its OFF writer
    // floats (printed with 17 digits), so there each coordinate comes back rounded to the
    // nearest float: relative error <= 2^-24, plus 1e-17 for the decimal printing.
    const bool exact = ext == ".ply" || ext == ".obj";
    double worst = 0;
    for (Index f = 0; f < F.rows(); ++f)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k) {
          const double x = V(F(f, j), k), y = Vr(Fr(f, j), k);
          worst = std::max(worst, std::abs(y - x) / (0x1p-24 * std::abs(x) + 1e-17));
        }
    CHECK(worst <= (exact ? 0.0 : 1.0));
    if (ext == ".stl" || ext == ".STL") {
      // STL has no shared vertices; OpenMesh merges equal positions back into a closed mesh.
      CHECK(Vr.rows() == V.rows());
      CHECK(check_mesh(Vr, Fr).watertight());
    } else {
      CHECK(Vr.rows() == V.rows());
      CHECK(Fr == F); // same vertex order and corner order
    }
  }
}

TEST_CASE("write_mesh errors leave no file", "[mesh]") {
  MatrixXd V(3, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  MatrixXi F(1, 3);
  F << 0, 1, 2;
  const test::TempDir scratch("mesh-errors");
  const auto& dir = scratch.path();
  const std::string unknown = (dir / "mesh.xyz").string();
  try {
    write_mesh(unknown, V, F);
    FAIL("no exception for an unknown extension");
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    CHECK(what.find(".stl") != std::string::npos);
    CHECK(what.find(".off") != std::string::npos);
  }
  CHECK_FALSE(std::filesystem::exists(unknown));
  const std::string missing = (dir / "no-such-dir" / "mesh.stl").string();
  try {
    write_mesh(missing, V, F);
    FAIL("no exception for a missing directory");
  } catch (const std::runtime_error& e) {
    CHECK(std::string(e.what()).find(missing) != std::string::npos);
  }
  CHECK_FALSE(std::filesystem::exists(missing));
  CHECK(std::filesystem::is_empty(dir)); // no temporary left behind either
  CHECK_THROWS_AS(read_mesh(missing, V, F), std::runtime_error);
}
