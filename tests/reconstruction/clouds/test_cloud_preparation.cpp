// Cloud preparation: degenerate clouds, outliers, downsampling, normals, orientation, noise.

#include "interlin/reconstruction/clouds/cloud_checks.h"
#include "interlin/reconstruction/clouds/cloud_filters.h"
#include "interlin/reconstruction/clouds/noise_level.h"
#include "interlin/reconstruction/clouds/orient_normals.h"
#include "interlin/reconstruction/clouds/prepare_cloud.h"
#include "interlin/reconstruction/clouds/read_point_cloud.h"
#include "interlin/reconstruction/io/input_error.h"

#include "support/test_clouds.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <random>

using namespace interlin;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

std::string check_error(const PointCloud& c) {
  try {
    check_cloud("c.xyz", c);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

PointCloud points(const Eigen::MatrixX3d& P) {
  PointCloud c;
  c.points = P;
  return c;
}

// Number of normals pointing into the body (against the exact outward normals).
long wrong_signs(const Eigen::MatrixX3d& N, const Eigen::MatrixX3d& truth) {
  return static_cast<long>(((N.array() * truth.array()).rowwise().sum() < 0).count());
}

} // namespace

TEST_CASE("degenerate clouds: one clear line each", "[clouds][checks]") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1, 1);
  Eigen::MatrixX3d plane(200, 3), line(200, 3), same(200, 3);
  for (int i = 0; i < 200; ++i) {
    const double a = U(rng), b = U(rng);
    plane.row(i) << a, b, 0.5 * a - 0.25 * b + 3; // a tilted plane
    line.row(i) << a, 2 * a, -a;
    same.row(i) << 1, 2, 3;
  }
  CHECK_THAT(check_error(points(plane)),
             StartsWith("c.xyz: all 200 points lie on one plane (spread"));
  CHECK_THAT(check_error(points(line)), StartsWith("c.xyz: all 200 points lie on one line"));
  CHECK_THAT(check_error(points(same)),
             StartsWith("c.xyz: only 1 distinct point(s) (after removing 199 repeated point(s)): "
                        "fitting a surface needs at least 20"));
  CHECK_THAT(check_error(points(plane.topRows(3))),
             StartsWith("c.xyz: only 3 distinct point(s): fitting a surface needs at least 20"));
  // repeated points are removed, not fatal
  const PointCloud s = test::sample_shape({test::Shape::sphere}, 100, 0, 1);
  PointCloud twice = s;
  twice.points = Eigen::MatrixX3d(200, 3);
  twice.points << s.points, s.points;
  twice.normals = Eigen::MatrixX3d(200, 3);
  twice.normals << s.normals, s.normals;
  std::vector<std::string> notes;
  const PointCloud d = check_cloud("c.xyz", twice, &notes);
  CHECK(d.points == s.points);
  CHECK(d.normals == s.normals);
  CHECK_THAT(notes.at(0), Contains("100 repeated point(s) removed"));
}

TEST_CASE("statistical outlier removal drops scattered points, keeps the surface",
          "[clouds][filters]") {
  PointCloud c = test::sample_shape({test::Shape::sphere}, 4000, 0, 2);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> U(-3, 3);
  const int k = 40;
  c.points.conservativeResize(4000 + k, 3);
  c.normals.conservativeResize(4000 + k, 3);
  for (int i = 0; i < k; ++i) {
    Eigen::Vector3d p(U(rng), U(rng), U(rng));
    if (p.norm() < 1.5) // keep the outliers well off the sphere
      p *= 1.5 / p.norm() + 0.5;
    c.points.row(4000 + i) = p.transpose();
    c.normals.row(4000 + i) << 1, 0, 0;
  }
  Eigen::Index removed = 0;
  const PointCloud f = remove_statistical_outliers(c, 16, 3.0, &removed);
  CHECK(f.points.rows() == 4000 + k - removed);
  CHECK((f.points.rowwise().norm().array() - 1).abs().maxCoeff() < 1e-12); // no outlier left
  CHECK(removed == k); // and every surface point kept (on_quadric)
}

TEST_CASE("statistical outlier removal keeps a clean scan's sparse stretches",
          "[clouds][filters]") {
  // PCL's filter alone flags the points of a random sampling's widest gaps: 75, 68 and 50 of
  // 20,000 on these clouds (measured). They lie on their neighbours' surface and are kept;
  // removing them widens the gaps into holes (the 300,000-point car: 892 flagged, the flood
  // fill leaked).
  for (const test::Shape shape :
       {test::Shape::sphere, test::Shape::torus, test::Shape::ellipsoid}) {
    const PointCloud c = test::sample_shape({shape}, 20000, 0, 41);
    Eigen::Index removed = -1;
    const PointCloud f = remove_statistical_outliers(c, 16, 3.0, &removed);
    INFO("shape " << int(shape));
    CHECK(removed == 0);
    CHECK(f.points == c.points);
  }
}

TEST_CASE("normal neighbours from the noise: k = 2 sqrt(pi) sigma / (spacing 0.1), clamped",
          "[clouds][normals]") {
  // A square of side 1 sampled at random: spacing 1 / sqrt(n); the spacing estimate from the
  // 16th neighbour's distance is within a few per cent (its median, pi d^2 n ~ Gamma(16)).
  const int n = 40000;
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> U(0, 1);
  Eigen::MatrixX3d P(n, 3);
  for (int i = 0; i < n; ++i)
    P.row(i) << U(rng), U(rng), 0;
  const double s = 1 / std::sqrt(double(n));
  CHECK(normal_neighbours_for_noise(P, 0) == 16);
  CHECK(normal_neighbours_for_noise(P, 0.002) == 16); // k = 14.2: the floor
  for (const double sigma : {0.003, 0.005}) {
    const double k = 2 * std::sqrt(M_PI) * sigma / (s * 0.1); // 21.3, 35.4
    CHECK(normal_neighbours_for_noise(P, sigma) == Approx(k).epsilon(0.08));
  }
  CHECK(normal_neighbours_for_noise(P, 0.01) == 64); // k = 71: the cap
  CHECK(normal_neighbours_for_noise(P, 0.01, 4, 20) == 20);
  CHECK_THROWS(normal_neighbours_for_noise(P, -1));
  CHECK_THROWS(normal_neighbours_for_noise(P, 0.01, 2));
  CHECK_THROWS(normal_neighbours_for_noise(P.topRows(10), 0.01));
}

TEST_CASE("prepare_cloud: normals of dense noisy scans from neighbourhoods wider than the noise",
          "[clouds][normals]") {
  // Spheres of 20,000 points (spacing 0.025) with noise 0.4 to 1.2 spacings. 16 neighbours span
  // about 2.3 spacings, so the noise tilts their plane by 2 sqrt(pi) sigma / (16 spacing): up to
  // 0.27 rad, and the orientation's smooth patches break up. Measured wrong signs with k = 16
  // against k from the noise (16, 23, 28): sigma 0.01: 0 / 0, 0.02: 103 / 10, 0.03: 1253 / 40.
  for (const double sigma : {0.01, 0.02, 0.03}) {
    const PointCloud c = test::sample_shape({test::Shape::sphere}, 20000, sigma, 43);
    PointCloud bare;
    bare.points = c.points;
    CloudPrepOptions o;
    o.outlier_neighbours = 0; // the points stay in order: the truth's normals match
    CloudPrepReport r16, rk;
    o.normal_neighbours = 16;
    const PointCloud p16 = prepare_cloud("s.xyz", bare, o, &r16);
    o.normal_neighbours = 0;
    const PointCloud pk = prepare_cloud("s.xyz", bare, o, &rk);
    const long w16 = wrong_signs(p16.normals, c.normals), wk = wrong_signs(pk.normals, c.normals);
    INFO("sigma " << sigma << ": k " << rk.normal_neighbours << ", wrong signs " << w16
                  << " with k = 16, " << wk << " with it");
    CHECK(r16.normal_neighbours == 16);
    CHECK(wk <= 20000 / 400);
    if (sigma >= 0.02) {
      CHECK(rk.normal_neighbours > 16);
      CHECK(5 * wk < w16);
    }
  }
}

TEST_CASE("voxel downsampling: one centroid per occupied voxel", "[clouds][filters]") {
  const PointCloud c = test::sample_shape({test::Shape::sphere}, 20000, 0, 5);
  const PointCloud f = voxel_downsample(c, 0.1);
  CHECK(f.points.rows() < 2000);
  CHECK(f.points.rows() > 1000); // about area / leaf^2 = 4 pi / 0.01
  // centroids of points within a voxel lie near the sphere (inside the chord, < leaf^2 / 2)
  CHECK((f.points.rowwise().norm().array() - 1).abs().maxCoeff() < 0.1);
  REQUIRE(f.has_normals());
  CHECK(((f.normals.array() * f.points.array()).rowwise().sum() > 0.9).all());
  CHECK_THROWS_WITH(voxel_downsample(c, 1e-9), Contains("use at least"));
}

TEST_CASE("normals: PCL estimates, orientation outward on spheres, tori and thin walls",
          "[clouds][normals]") {
  for (const test::Shape shape : {test::Shape::sphere, test::Shape::torus, test::Shape::ellipsoid})
    for (const double sigma : {0.0, 0.003}) {
      const PointCloud c = test::sample_shape({shape}, 6000, sigma, 7);
      INFO("shape " << int(shape) << " sigma " << sigma);
      Eigen::MatrixX3d N = estimate_normals(c.points, 16);
      // unoriented estimates are close to the true normals up to sign
      const Eigen::ArrayXd cosine = (N.array() * c.normals.array()).rowwise().sum().abs();
      CHECK((cosine > 0.9).count() >= 0.97 * 6000);
      // PCL turns them towards a viewpoint; random signs make the orientation do the work
      std::mt19937 rng(8);
      for (Eigen::Index i = 0; i < N.rows(); ++i)
        if (rng() % 2)
          N.row(i) *= -1;
      CHECK(orientation_disagreement(c.points, N, 10) > 0.3);
      OrientationInfo info;
      orient_normals(c.points, N, 10, &info);
      CHECK(info.components == 1);
      // the thin wall's rim (0.15 thick) is where propagation could cross to the other side
      CHECK(wrong_signs(N, c.normals) <= 6000 / 500);
      CHECK(orientation_disagreement(c.points, N, 10) < 0.005);
    }
}

TEST_CASE("noise estimate recovers sigma within 25 %", "[clouds][noise]") {
  for (const test::Shape shape : {test::Shape::sphere, test::Shape::torus})
    for (const double sigma : {0.002, 0.005, 0.01}) {
      const PointCloud c = test::sample_shape({shape}, 20000, sigma, 11);
      INFO("shape " << int(shape) << " sigma " << sigma);
      CHECK(estimate_noise(c.points) == Approx(sigma).epsilon(0.25));
    }
  // noise-free: the quadric's approximation error only, far below the spacing (~0.025)
  CHECK(estimate_noise(test::sample_shape({test::Shape::sphere}, 20000, 0, 12).points) < 1e-4);
}

TEST_CASE("prepare_cloud: normals from the file kept when consistent, else re-oriented",
          "[clouds][prepare]") {
  PointCloud c = test::sample_shape({test::Shape::torus}, 5000, 0, 13);
  CloudPrepReport r;
  PointCloud p = prepare_cloud("t.xyzn", c, {}, &r);
  CHECK_FALSE(r.normals_estimated);
  CHECK_FALSE(r.normals_reoriented);
  CHECK(r.outliers <= 50);
  // flip a third of the file's normals: they are re-oriented, all outward again
  for (Eigen::Index i = 0; i < c.points.rows(); i += 3)
    c.normals.row(i) *= -1;
  std::vector<std::string> notes;
  CloudPrepOptions o;
  o.outlier_neighbours = 0;
  p = prepare_cloud("t.xyzn", c, o, &r, &notes);
  CHECK(r.normals_reoriented);
  CHECK_THAT(notes.at(0), Contains("not consistently oriented"));
  const PointCloud truth = test::sample_shape({test::Shape::torus}, 5000, 0, 13);
  CHECK(wrong_signs(p.normals, truth.normals) == 0);
  // no normals at all: estimated and oriented
  c.normals.resize(0, 3);
  p = prepare_cloud("t.xyz", c, o, &r);
  CHECK(r.normals_estimated);
  CHECK(wrong_signs(p.normals, truth.normals) <= 5);
  o.normals = NormalSource::file;
  CHECK_THROWS_AS(prepare_cloud("t.xyz", c, o), InputError);
}

TEST_CASE("orientation by the winding number: flipped sides of thin walls are turned back",
          "[clouds][normals]") {
  // Estimated normals given the true signs, then one side (z < 0), everything, or nothing
  // flipped, as propagation across a noisy rim leaves them, on ellipsoids 0.3 and 0.1 thick
  // (>= 4 point spacings), noise 0.002 (sigma = 0 measured alike: at most 20 % remain). Bounds: a
  // right orientation stays right; a wrong one keeps at most 40 % of its wrong signs (measured at
  // most 35 %: the patches by the sharp rim and the grid cells' faces are decided less surely).
  // Walls of about 1.5 spacings (thickness 0.04) are not repaired: there the two sides join one
  // patch. These bounds are the patch repair's (thin_walls off); with thin_walls a right
  // orientation keeps at least 99 % right (measured: 0 and 32 of 6000 turned wrong, on the 0.1
  // thick one's sharp rim).
  constexpr double kKeptShare = 0.4, kSigma = 0.002;
  for (const double c : {0.15, 0.05})
    for (const int flip : {0, 1, 2}) { // none, the lower side, all
      const test::SampledShape truth{test::Shape::ellipsoid, 1, c};
      const PointCloud cloud = test::sample_shape(truth, 6000, kSigma, 9);
      Eigen::MatrixX3d N = estimate_normals(cloud.points, 16);
      for (Eigen::Index i = 0; i < N.rows(); ++i) {
        if (N.row(i).dot(cloud.normals.row(i)) < 0)
          N.row(i) *= -1;
        if (flip == 2 || (flip == 1 && cloud.points(i, 2) < 0))
          N.row(i) *= -1;
      }
      const long before = wrong_signs(N, cloud.normals);
      if (flip == 0) {
        Eigen::MatrixX3d thin = N;
        orient_by_winding_number(cloud.points, thin, 10, true);
        INFO("thickness " << 2 * c << ", thin_walls: wrong " << wrong_signs(thin, cloud.normals));
        CHECK(wrong_signs(thin, cloud.normals) <= 60);
      }
      const Eigen::Index negated = orient_by_winding_number(cloud.points, N, 10, false);
      const long after = wrong_signs(N, cloud.normals);
      INFO("thickness " << 2 * c << " flip " << flip << ": wrong before " << before << ", after "
                        << after << ", negated " << negated);
      CHECK(double(after) <= kKeptShare * double(before));
    }
  // Right orientations stay: dense clouds, and sparse ones (400 points, about PCL's bunny scan),
  // where nearly every point is its own patch and free single-point signs would scatter flips.
  for (const test::Shape shape : {test::Shape::sphere, test::Shape::torus})
    for (const Eigen::Index n : {6000, 400}) {
      const PointCloud cloud = test::sample_shape({shape}, n, 0.002, 10);
      Eigen::MatrixX3d N = estimate_normals(cloud.points, 16);
      for (Eigen::Index i = 0; i < N.rows(); ++i)
        if (N.row(i).dot(cloud.normals.row(i)) < 0)
          N.row(i) *= -1;
      INFO(n << " points");
      for (const bool thin : {false, true}) {
        Eigen::MatrixX3d M = N;
        INFO("thin_walls " << thin);
        CHECK(orient_by_winding_number(cloud.points, M, 10, thin) == 0);
      }
    }
}

TEST_CASE("orientation by the winding number: sides the flood fill sees are turned back whole",
          "[clouds][normals]") {
  // Bodies thick enough for inside voxels behind the shell (exterior_side.h): a sphere, a torus
  // and the ellipsoid 0.3 thick, 6000 points, sigma 0.002, with the lower side's (z < 0) or one
  // half's (x < 0) normals flipped, as propagation across a rim leaves them.
  for (const test::SampledShape truth :
       {test::SampledShape{test::Shape::sphere}, test::SampledShape{test::Shape::torus},
        test::SampledShape{test::Shape::ellipsoid, 1, 0.15}})
    for (const int axis : {2, 0}) {
      const PointCloud cloud = test::sample_shape(truth, 6000, 0.002, 12);
      Eigen::MatrixX3d N = estimate_normals(cloud.points, 16);
      for (Eigen::Index i = 0; i < N.rows(); ++i)
        if ((N.row(i).dot(cloud.normals.row(i)) < 0) != (cloud.points(i, axis) < 0))
          N.row(i) *= -1;
      const long before = wrong_signs(N, cloud.normals);
      orient_by_winding_number(cloud.points, N, 10, true);
      INFO("shape " << int(truth.shape) << " axis " << axis << ": wrong before " << before
                    << ", after " << wrong_signs(N, cloud.normals));
      CHECK(wrong_signs(N, cloud.normals) <= 0);
    }
}

TEST_CASE("prepare_cloud on a sparse real scan: the winding-number repair scatters no flips",
          "[clouds][normals]") {
  // PCL's bunny (397 points, one range scan): nearly every point is its own patch. Up to the global
  // sign the re-oriented normals agree with the file's on all but 27 points (the file's own are
  // not consistent everywhere); when single points were free patches, 192 of 397 disagreed.
  const PointCloud c = read_point_cloud(INTERLIN_DATA_DIR "/clouds/bun0.pcd");
  CloudPrepOptions o;
  o.outlier_neighbours = 0;
  for (const NormalSource source : {NormalSource::automatic, NormalSource::estimate}) {
    o.normals = source;
    CloudPrepReport r;
    const PointCloud p = prepare_cloud("bun0.pcd", c, o, &r);
    const long against = wrong_signs(p.normals, c.normals);
    const long wrong = std::min(against, long(c.normals.rows()) - against);
    INFO("disagree with the file's normals: " << wrong);
    CHECK(wrong <= 40); // 10 %
  }
}

TEST_CASE("orientation at thin walls' edges: the thin-wall sides turn inward normals back",
          "[clouds][normals]") {
  // prepare_cloud's steps (PCL normals, propagation, the winding-number repair) on ellipsoids
  // 0.08-0.12 thick in the middle (3-5 point spacings of 0.025), rims as sharp as a blade's
  // edge, noise 0.001 and 0.003. Without thin_walls 93-858 of the 6000 normals point inward
  // (measured; the family's total 2874); with it 89-688 (total 1832, 36 % fewer, every case
  // fewer; session 8's rule without the re-propagation and the wall test: 2207). Bounds: the
  // family's total falls by at least 25 %; no case gains more than 5 (ties within the
  // platforms' rounding).
  long total[2] = {0, 0};
  for (const double c : {0.04, 0.05, 0.06})
    for (const double sigma : {0.001, 0.003}) {
      const test::SampledShape truth{test::Shape::ellipsoid, 1, c};
      const PointCloud cloud = test::sample_shape(truth, 6000, sigma, 21);
      long wrong[2] = {0, 0};
      for (const bool thin : {false, true}) {
        Eigen::MatrixX3d N = estimate_normals(cloud.points, 16);
        orient_normals(cloud.points, N, 10);
        orient_by_winding_number(cloud.points, N, 10, thin);
        wrong[thin] = wrong_signs(N, cloud.normals);
        total[thin] += wrong[thin];
      }
      INFO("thickness " << 2 * c << " sigma " << sigma << ": inward " << wrong[0] << " -> "
                        << wrong[1]);
      CHECK(wrong[1] <= wrong[0] + 5);
    }
  INFO("inward over the family " << total[0] << " -> " << total[1]);
  CHECK(total[0] > 6 * 6000 / 100); // the old orientation measurably fails (> 1 %)
  CHECK(double(total[1]) <= 0.75 * double(total[0]));
}

namespace {

// n points uniform by area on the boundary of the prism over a simple polygon (counter-clockwise
// in the x y plane, z in [0, h]) whose caps are the union of the given axis-aligned rectangles
// (x0, y0, x1, y1); exact outward normals, Gaussian noise sigma on each coordinate.
PointCloud sample_prism(const std::vector<Eigen::Vector2d>& polygon,
                        const std::vector<Eigen::Vector4d>& rects, double h, int n, double sigma,
                        unsigned seed) {
  struct Face {
    Eigen::Vector3d o, u, v, n;
  };
  std::vector<Face> faces;
  const Eigen::Vector3d Z = Eigen::Vector3d::UnitZ();
  for (size_t k = 0; k < polygon.size(); ++k) {
    const Eigen::Vector2d a = polygon[k], d = polygon[(k + 1) % polygon.size()] - a;
    faces.push_back({Eigen::Vector3d(a(0), a(1), 0), Eigen::Vector3d(d(0), d(1), 0), h * Z,
                     Eigen::Vector3d(d(1), -d(0), 0).normalized()});
  }
  for (const Eigen::Vector4d& r : rects)
    for (const double z : {0.0, h})
      faces.push_back({Eigen::Vector3d(r(0), r(1), z), Eigen::Vector3d(r(2) - r(0), 0, 0),
                       Eigen::Vector3d(0, r(3) - r(1), 0), z > 0 ? Z : Eigen::Vector3d(-Z)});
  std::vector<double> cum;
  double total = 0;
  for (const Face& f : faces)
    cum.push_back(total += f.u.norm() * f.v.norm());
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0, 1);
  std::normal_distribution<double> G(0, sigma);
  PointCloud c;
  c.points.resize(n, 3);
  c.normals.resize(n, 3);
  for (int i = 0; i < n; ++i) {
    const Face& f =
        faces[size_t(std::lower_bound(cum.begin(), cum.end(), U(rng) * total) - cum.begin())];
    const Eigen::Vector3d p = f.o + U(rng) * f.u + U(rng) * f.v;
    c.points.row(i) = (p + Eigen::Vector3d(G(rng), G(rng), G(rng))).transpose();
    c.normals.row(i) = f.n.transpose();
  }
  return c;
}

} // namespace

TEST_CASE("orientation at concave edges and narrow slots: the thin-wall sides add no inward "
          "normals there",
          "[clouds][normals]") {
  // A block 2 x 1 x 0.5 with a slot of width w cut from its face y = 1 down to y = 0.4, through
  // its height: the slot's walls face each other w apart (w = 0.06: about 2 point spacings), and
  // meet its floor at concave edges; to the thin-wall test's local geometry a narrow slot is a
  // thin wall seen from inside (R-function models' slots and gaps: docs/benchmarks.md "Thin walls
  // by default"). PCL normals, propagation, the winding-number repair, without and with
  // thin_walls. Measured: by the slot 0-35 inward without, the same +0 or +1 with (session 8's
  // rule without the wall test: 35 -> 92 and 32 -> 97 at w = 0.06). Bounds: at most 3 more by
  // the slot and in the whole cloud (ties within the platforms' rounding).
  for (const double w : {0.15, 0.1, 0.06})
    for (const double sigma : {0.001, 0.003}) {
      const double h = 0.5, a = 1 - w / 2, b = 1 + w / 2, y0 = 0.4;
      const PointCloud cloud =
          sample_prism({{0, 0}, {2, 0}, {2, 1}, {b, 1}, {b, y0}, {a, y0}, {a, 1}, {0, 1}},
                       {{0, 0, 2, y0}, {0, y0, a, 1}, {b, y0, 2, 1}}, h, 6000, sigma, 31);
      long wrong[2] = {0, 0}, at_slot[2] = {0, 0};
      for (const bool thin : {false, true}) {
        Eigen::MatrixX3d N = estimate_normals(cloud.points, 16);
        orient_normals(cloud.points, N, 10);
        orient_by_winding_number(cloud.points, N, 10, thin);
        wrong[thin] = wrong_signs(N, cloud.normals);
        for (Eigen::Index i = 0; i < N.rows(); ++i)
          at_slot[thin] += std::abs(cloud.points(i, 0) - 1) < w / 2 + 0.1 &&
                           cloud.points(i, 1) > y0 - 0.1 && N.row(i).dot(cloud.normals.row(i)) < 0;
      }
      INFO("slot " << w << " sigma " << sigma << ": inward " << wrong[0] << " -> " << wrong[1]
                   << ", by the slot " << at_slot[0] << " -> " << at_slot[1]);
      CHECK(at_slot[1] <= at_slot[0] + 3);
      CHECK(wrong[1] <= wrong[0] + 3);
    }
}
