// The volume between boundary facets and F = 0 (facet_sag): exact integrals on chords of a
// paraboloid, the sphere's mesh volume plus the sag against 4 pi / 3 and the sag's order h^2, and
// a thin rod whose coarse volume meshes lose 4-11 % of its volume, which the sag accounts for and
// cell_for_sag's cell brings within 0.5 %.
#include "interlin/reconstruction/meshing/facet_sag.h"
#include "interlin/reconstruction/meshing/implicit_mesh.h"
#include "interlin/reconstruction/meshing/mesh_check.h"
#include "interlin/reconstruction/meshing/volume_mesh.h"
#include "interlin/reconstruction/meshing/volume_quality.h"

#include "support/test_implicits.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

using namespace interlin;

namespace {

// The body under z = 1 - x^2 - y^2 (F without a gradient: central differences).
ImplicitFunction paraboloid_cap() {
  return test::implicit([](double x, double y, double z) { return 1 - x * x - y * y - z; },
                        test::cube_box(2));
}

// A rod of radius r along z, |z| <= 2 (R0 conjunction of the cylinder and the slab); box to +-1.05
// r and +-2.1.
ImplicitFunction rod(double r) {
  ImplicitFunction f = test::implicit(
      [r](double x, double y, double z) {
        return test::r0_and(1 - (x * x + y * y) / (r * r), 1 - z * z / 4);
      },
      Eigen::AlignedBox3d(Eigen::Vector3d(-1.05 * r, -1.05 * r, -2.1),
                          Eigen::Vector3d(1.05 * r, 1.05 * r, 2.1)));
  return f;
}

double slope(const std::vector<double>& x, const std::vector<double>& y) { // least squares in log
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = double(x.size());
  for (size_t i = 0; i < x.size(); ++i) {
    const double a = std::log(x[i]), b = std::log(y[i]);
    sx += a, sy += b, sxx += a * a, sxy += a * b;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

} // namespace

TEST_CASE("facet_sag: chords of a paraboloid cap give the exact integrals of the height", "[sag]") {
  const ImplicitFunction f = paraboloid_cap();
  // Along +z the distance from the facet (z = 0) to F = 0 is the height g = 1 - x^2 - y^2, a
  // quadratic: edge midpoints and Simpson's 3 x 3 rule integrate it exactly. The root is found to
  // 1e-9 of the facet's diameter, so 1e-9 relative.
  SECTION("the equilateral triangle inscribed in the unit circle: 9 sqrt(3) / 16") {
    const double s = std::sqrt(3.0) / 2;
    Eigen::MatrixXd V(3, 3);
    V << 1, 0, 0, -0.5, s, 0, -0.5, -s, 0;
    Eigen::MatrixXi B(1, 3);
    B << 0, 1, 2; // counter-clockwise from +z, the outside
    const FacetSag r = facet_sag(f, V, B, 1);
    CHECK(r.volume == Approx(9 * std::sqrt(3.0) / 16).epsilon(1e-9));
    CHECK(r.max_distance == Approx(0.75).epsilon(1e-9)); // g at the edge midpoints
    CHECK(r.area == Approx(3 * std::sqrt(3.0) / 4).epsilon(1e-12));
    CHECK(r.skipped_area == 0);
    B << 0, 2, 1; // facing into the body: its normal is 180 degrees from -grad F
    const FacetSag flipped = facet_sag(f, V, B, 1);
    CHECK(flipped.volume == 0);
    CHECK(flipped.skipped_area == Approx(3 * std::sqrt(3.0) / 4).epsilon(1e-12));
  }
  SECTION("the square inscribed in the unit circle: 4 / 3, 1 at the centre") {
    const double a = std::sqrt(0.5);
    Eigen::MatrixXd V(4, 3);
    V << -a, -a, 0, a, -a, 0, a, a, 0, -a, a, 0;
    Eigen::MatrixXi B(1, 4);
    B << 0, 1, 2, 3;
    const FacetSag r = facet_sag(f, V, B, 1);
    CHECK(r.volume == Approx(4.0 / 3).epsilon(1e-9));
    CHECK(r.max_distance == Approx(1.0).epsilon(1e-9));
    CHECK(r.area == Approx(2.0).epsilon(1e-12));
  }
}

TEST_CASE("facet_sag: a sphere's meshes plus their sag make its volume, the sag of order h^2",
          "[sag]") {
  const ImplicitFunction f = test::sphere(1.0);
  const double exact = 4 * M_PI / 3;
  std::vector<double> cells, sags;
  for (int resolution : {12, 24, 48}) {
    ImplicitMeshOptions o;
    o.resolution = resolution;
    Eigen::MatrixXd V;
    Eigen::MatrixXi F;
    ImplicitMeshInfo info;
    implicit_mesh(f, o, V, F, &info);
    const double mesh = check_mesh(V, F).volume;
    const FacetSag s = facet_sag(f, V, F);
    INFO("resolution " << resolution << ": mesh " << mesh << ", sag " << s.volume);
    CHECK(s.volume > 0); // chords of a convex surface
    CHECK(s.skipped_area == 0);
    // What the quadrature leaves (the height is quadratic only to leading order): under 1 % of
    // the sag (measured 0.01-0.4 %).
    CHECK(std::abs(mesh + s.volume - exact) < 0.01 * s.volume);
    const FacetSag s3 = facet_sag(f, V, F, 3);
    CHECK(s3.volume == s.volume); // partial sums in facet order
    cells.push_back(info.grid.spacing(0)), sags.push_back(s.volume);
  }
  CHECK(slope(cells, sags) == Approx(2).margin(0.15));
}

TEST_CASE("facet_sag: a rod 3 cells across loses 4-11 % of its volume to the sag, and "
          "cell_for_sag's cell keeps it within 0.5 %",
          "[sag][volume]") {
  const double r = 0.05, exact = M_PI * r * r * 4;
  const ImplicitFunction f = rod(r);
  for (VolumeElements e : {VolumeElements::tetrahedra, VolumeElements::hexahedra}) {
    VolumeMeshOptions o;
    o.elements = e;
    o.resolution = 128; // the CLI's default: cell 0.033, the diameter 3 cells
    VolumeMeshInfo info;
    const VolumeMesh m = volume_mesh(f, o, &info);
    const double mesh = volume_quality(m.V, m.C).volume;
    const FacetSag s = facet_sag(f, m.V, m.B);
    INFO((e == VolumeElements::tetrahedra ? "tetrahedra" : "hexahedra")
         << ": mesh " << mesh << ", sag " << s.volume << " of " << exact);
    CHECK(mesh < 0.97 * exact);                              // measured -3.6 % and -10.3 %
    CHECK(std::abs(mesh + s.volume - exact) < 0.01 * exact); // measured +0.02 % and -0.6 %
    o.resolution = 0;
    o.cell = cell_for_sag(info.grid.spacing(0), s.volume / mesh, 0.005);
    const VolumeMesh fine = volume_mesh(f, o);
    CHECK(std::abs(volume_quality(fine.V, fine.C).volume - exact) < 0.005 * exact);
  }
}
