// triangulate_loop: a valid disk on the loop's vertices for non-convex, non-planar and clockwise
// loops, and the constrained Delaunay triangulation: its smallest angle is the largest that any
// triangulation of the polygon can have, checked against an independent O(n^3) dynamic program
// over all triangulations.
#include "interlin/reconstruction/meshing/surface_mesh.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

using namespace interlin;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::MatrixXi;
using Eigen::Vector2d;

namespace {

// Checks that T triangulates the closed loop 0..n-1: every loop edge i -> i+1 used once in the
// loop's direction, every other edge twice in opposite directions (a disk bounded by the loop).
void check_disk(const MatrixXi& T, Index n) {
  REQUIRE(T.rows() == n - 2);
  std::vector<std::pair<long, long>> directed;
  for (Index f = 0; f < T.rows(); ++f)
    for (int j = 0; j < 3; ++j)
      directed.emplace_back(T(f, j), T(f, (j + 1) % 3));
  std::sort(directed.begin(), directed.end());
  long loop_edges = 0, bad = 0;
  for (const auto& [a, b] : directed) {
    const bool loop_edge = b == (a + 1) % n;
    const long same = std::count(directed.begin(), directed.end(), std::make_pair(a, b));
    const long opposite = std::count(directed.begin(), directed.end(), std::make_pair(b, a));
    if (loop_edge)
      loop_edges += same == 1 && opposite == 0;
    else
      bad += !(same == 1 && opposite == 1);
  }
  CHECK(loop_edges == n);
  CHECK(bad == 0);
}

double cross2(const Vector2d& a, const Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

double min_angle(const Vector2d& a, const Vector2d& b, const Vector2d& c) {
  const auto angle = [](const Vector2d& p, const Vector2d& q, const Vector2d& r) {
    const Vector2d u = q - p, v = r - p;
    return std::atan2(std::abs(cross2(u, v)), u.dot(v));
  };
  return std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)});
}

// The largest smallest angle over all triangulations of the simple counter-clockwise polygon Q
// (Klincsek's dynamic program over sub-polygons i..j): best(i, j) = max over k of
// min(best(i, k), best(k, j), angle of triangle (i, k, j)), taking only chords inside the polygon.
double optimal_min_angle(const std::vector<Vector2d>& Q) {
  const int n = int(Q.size());
  const auto proper_cross = [](const Vector2d& a, const Vector2d& b, const Vector2d& c,
                               const Vector2d& d) {
    const double d1 = cross2(b - a, c - a), d2 = cross2(b - a, d - a);
    const double d3 = cross2(d - c, a - c), d4 = cross2(d - c, b - c);
    return d1 * d2 < 0 && d3 * d4 < 0;
  };
  const auto inside = [&](const Vector2d& p) { // crossing number
    bool in = false;
    for (int i = 0, j = n - 1; i < n; j = i++)
      if ((Q[i].y() > p.y()) != (Q[j].y() > p.y()) &&
          p.x() < (Q[j].x() - Q[i].x()) * (p.y() - Q[i].y()) / (Q[j].y() - Q[i].y()) + Q[i].x())
        in = !in;
    return in;
  };
  std::vector<std::vector<char>> chord(n, std::vector<char>(n, 0));
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      if (j == i + 1 || (i == 0 && j == n - 1)) {
        chord[i][j] = 1; // a polygon edge
        continue;
      }
      bool ok = inside(0.5 * (Q[i] + Q[j]));
      for (int e = 0; e < n && ok; ++e) {
        const int f = (e + 1) % n;
        if (e != i && e != j && f != i && f != j && proper_cross(Q[i], Q[j], Q[e], Q[f]))
          ok = false;
      }
      chord[i][j] = ok;
    }
  std::vector<std::vector<double>> best(n, std::vector<double>(n, -1.0)); // -1: impossible
  for (int i = 0; i + 1 < n; ++i)
    best[i][i + 1] = M_PI;
  for (int len = 2; len < n; ++len)
    for (int i = 0; i + len < n; ++i) {
      const int j = i + len;
      if (!chord[i][j])
        continue;
      for (int k = i + 1; k < j; ++k)
        if (best[i][k] >= 0 && best[k][j] >= 0 && cross2(Q[k] - Q[i], Q[j] - Q[i]) > 0)
          best[i][j] =
              std::max(best[i][j], std::min({best[i][k], best[k][j], min_angle(Q[i], Q[k], Q[j])}));
    }
  return best[0][n - 1];
}

// A random star-shaped loop around the origin: n jittered angles (gaps below pi, so the origin
// sees every edge), radii in [0.4, 1], squashed to `thickness` in y (thin like a blade section
// when small), counter-clockwise.
std::vector<Vector2d> star_loop(int n, double thickness, std::mt19937& rng) {
  std::uniform_real_distribution<double> jitter(0, 0.8), radius(0.4, 1.0);
  std::vector<double> t(n);
  for (int i = 0; i < n; ++i)
    t[i] = 2 * M_PI * (i + jitter(rng)) / n;
  std::vector<Vector2d> Q;
  for (double x : t) {
    const double r = radius(rng);
    Q.emplace_back(r * std::cos(x), thickness * r * std::sin(x));
  }
  return Q;
}

} // namespace

TEST_CASE("triangulate_loop reaches the largest smallest angle of all triangulations",
          "[mesh][triangulate]") {
  std::mt19937 rng(20261121);
  // 40 random loops of 8..30 vertices, round and thin, lifted onto a tilted plane in 3D (the
  // optimum is a property of the polygon in its own plane, so the lift must not change it).
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 8 + trial % 23;
    const double thickness = trial % 2 ? 1.0 : 0.08;
    const std::vector<Vector2d> Q = star_loop(n, thickness, rng);
    MatrixXd P(n, 3);
    for (int i = 0; i < n; ++i)
      P.row(i) = (R * Eigen::Vector3d(Q[i].x(), Q[i].y(), 0)).transpose();
    const MatrixXi T = triangulate_loop(P);
    check_disk(T, n);
    double ours = M_PI;
    for (Index f = 0; f < T.rows(); ++f)
      ours = std::min(ours, min_angle(Q[T(f, 0)], Q[T(f, 1)], Q[T(f, 2)]));
    const double optimum = optimal_min_angle(Q);
    INFO("trial " << trial << ", n = " << n << ", thickness " << thickness);
    REQUIRE(optimum > 0);
    // Equal up to the rounding of the rotation into 3D and back (angles of O(1e-2) rad computed
    // from coordinates with ~1e-16 relative error).
    CHECK(ours == Approx(optimum).epsilon(1e-9));
  }
}

TEST_CASE("triangulate_loop triangulates non-convex, non-planar loops", "[mesh]") {
  SECTION("comb") {
    // A comb with 8 deep teeth, lifted out of plane by a gentle saddle.
    std::vector<Eigen::RowVector3d> pts;
    const int teeth = 8;
    pts.push_back({0, 0, 0});
    pts.push_back({2.0 * teeth, 0, 0});
    for (int k = teeth - 1; k >= 0; --k) {
      pts.push_back({2.0 * k + 1.6, 5, 0});
      pts.push_back({2.0 * k + 1.4, 0.5, 0});
      pts.push_back({2.0 * k + 0.6, 0.5, 0});
      pts.push_back({2.0 * k + 0.4, 5, 0});
    }
    pts.pop_back();
    pts.push_back({0, 5, 0});
    MatrixXd P(Index(pts.size()), 3);
    for (std::size_t i = 0; i < pts.size(); ++i) {
      P.row(Index(i)) = pts[i];
      P(Index(i), 2) = 0.01 * (P(Index(i), 0) - teeth) * (P(Index(i), 1) - 2.5);
    }
    const MatrixXi T = triangulate_loop(P);
    check_disk(T, P.rows());
    // All triangles counter-clockwise seen from +z (the loop's own sense), hence a tiling.
    long cw = 0;
    double area = 0;
    for (Index f = 0; f < T.rows(); ++f) {
      const Eigen::Vector2d a = P.row(T(f, 0)).head<2>(), b = P.row(T(f, 1)).head<2>(),
                            c = P.row(T(f, 2)).head<2>();
      const double o = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
      cw += o <= 0;
      area += 0.5 * o;
    }
    CHECK(cw == 0);
    // The tiles add up to the polygon area (shoelace, in the xy projection).
    double shoelace = 0;
    for (Index i = 0; i < P.rows(); ++i) {
      const Index j = (i + 1) % P.rows();
      shoelace += 0.5 * (P(i, 0) * P(j, 1) - P(j, 0) * P(i, 1));
    }
    CHECK(area == Approx(shoelace).epsilon(1e-12));
  }
  SECTION("clockwise loop keeps its direction") {
    MatrixXd P(5, 3);
    P << 0, 0, 0, 0, 1, 0, 1, 1, 0, 0.5, 0.4, 0, 1, 0, 0; // clockwise, one reflex vertex
    const MatrixXi T = triangulate_loop(P);
    check_disk(T, 5);
  }
  CHECK_THROWS_AS(triangulate_loop(MatrixXd::Zero(2, 3)), std::invalid_argument);
}
