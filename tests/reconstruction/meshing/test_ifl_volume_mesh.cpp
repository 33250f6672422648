// Volume meshes of the three kinds of .ifl file interlin writes (section_body, normalized_rf,
// cloud_pu), each written to disk and read back through load_implicit as `interlin mesh` reads
// it: tetrahedra (the default) and hexahedra, no inverted element, every boundary node on F = 0
// except those the mesher reports held or not projected, and the volume against a reference
// that does not come from the implicit model (a closed form, or the capped loft mesh).
#include "interlin/interflatation/load_implicit.h"
#include "interlin/interflatation/models/ifl_file.h"
#include "interlin/reconstruction/clouds/cloud_implicit_ifl.h"
#include "interlin/reconstruction/implicit/normalize_model.h"
#include "interlin/reconstruction/implicit/section_body_build.h"
#include "interlin/reconstruction/meshing/mesh_check.h"
#include "interlin/reconstruction/meshing/volume_mesh.h"
#include "interlin/reconstruction/meshing/volume_quality.h"

#include "../implicit/section_body_checks.h"
#include "support/test_blades.h"
#include "support/test_clouds.h"
#include "support/test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

using namespace interlin;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A boundary node counts as on F = 0 when its first-order distance |F| / |grad F| is below
// kOnZero cells: the roots are found to 1e-10 of their grid edge or projection step
// (RootOptions), and a factor 100 covers an edge at a slant to the surface and the change of
// |grad F| across the final bracket.
constexpr double kOnZero = 1e-8;

struct IflBody {
  ImplicitFunction f;
  double reference = 0; // the body's volume from outside the implicit model
};

// `block` written to dir/name and read back the way the CLI reads it.
ImplicitFunction through_file(const IflBlock& block, const test::TempDir& dir,
                              const std::string& name) {
  const std::string path = dir / name;
  std::ofstream out(path, std::ios::binary);
  write_ifl(out, block);
  out.close();
  return load_implicit(path);
}

// A thick cambered, twisted, tapered NACA blade (30 % thick: the hexahedral layer needs walls of
// a few cells) lofted from 5 sections; reference: the volume of the capped loft mesh (800 x 200,
// `interlin loft --cap`), a mesh of the loft surface itself, not of omega.
const IflBody& section_body() {
  static const IflBody body = [] {
    test::BladeFamily family;
    family.thickness = 0.3;
    family.sections = 5;
    family.span = 1.0;
    SectionBodyOptions o;
    o.resolution = 16; // the far field: omega = 0 exactly on the loft at any grid
    const SectionBodyBuild b = build_section_body(test::blade_sections(family), o);
    Eigen::MatrixXd V;
    Eigen::MatrixXi F;
    test::capped_mesh(b, V, F);
    test::TempDir d("iflvolume");
    return IflBody{through_file(to_ifl(b.model), d, "blade.ifl"), check_mesh(V, F).volume};
  }();
  return body;
}

// A tube, R-function difference of two cylinders (sharp rims), normalised; closed form
// pi (R^2 - r^2) 2 h.
const IflBody& normalized_tube() {
  static const IflBody body = [] {
    test::TempDir d("iflvolume");
    std::ofstream(d / "tube.rf") << "box(-1, -1, -0.7, 1, 1, 0.7);\n"
                                    "res = sub0(cylinder(x, y, z, 0.8, 0.5), "
                                    "cylinder(x, y, z, 0.35, 1));\n";
    NormalizeOptions o;
    o.resolution = 32;
    o.mesh_resolution = 96;
    const NormalizeBuild b = normalize_model(d / "tube.rf", {}, o);
    return IflBody{through_file(to_ifl(b.model), d, "tube.ifl"),
                   kPi * (0.8 * 0.8 - 0.35 * 0.35) * 2 * 0.5};
  }();
  return body;
}

// The partition of unity fitted to 6000 noise-free points of the ellipsoid with semi-axes
// (1, 0.6, 0.5); closed form 4/3 pi a b c.
const IflBody& cloud_ellipsoid() {
  static const IflBody body = [] {
    register_cloud_ifl_kind();
    test::SampledShape shape{test::Shape::ellipsoid, 1, 0.5};
    const PointCloud c = test::sample_shape(shape, 6000, 0, 7);
    CloudFitOptions o;
    o.noise = 0;
    const CloudImplicit m = fit_cloud_implicit(c, o);
    test::TempDir d("iflvolume");
    return IflBody{through_file(to_ifl(m, 0), d, "ellipsoid.ifl"), 4 * kPi / 3 * 1 * 0.6 * 0.5};
  }();
  return body;
}

struct Meshed {
  VolumeQuality quality;
  VolumeMeshInfo info;
  long boundary = 0; // boundary nodes
  long off_zero = 0; // ... with |F| / |grad F| >= kOnZero cells
};

Meshed mesh(const ImplicitFunction& f, VolumeElements elements, int resolution,
            VolumeBoundary boundary = VolumeBoundary::cut) {
  VolumeMeshOptions o;
  o.elements = elements;
  o.resolution = resolution;
  o.boundary = boundary;
  Meshed r;
  const VolumeMesh m = volume_mesh(f, o, &r.info);
  r.quality = volume_quality(m.V, m.C);
  Points3 P(std::count(m.boundary.begin(), m.boundary.end(), char(1)), 3);
  for (long v = 0, k = 0; v < m.V.rows(); ++v)
    if (m.boundary[size_t(v)])
      P.row(k++) = m.V.row(v);
  Eigen::VectorXd F(P.rows());
  Points3 G(P.rows(), 3);
  f.gradient(P, F, G);
  const double h = r.info.grid.spacing(0);
  r.boundary = P.rows();
  r.off_zero = (F.array().abs() >= kOnZero * h * G.rowwise().norm().array()).count();
  return r;
}

const char* kind_name(VolumeElements e) {
  return e == VolumeElements::tetrahedra ? "tetrahedra" : "hexahedra";
}

// The checks every .ifl mesh passes at `resolution` cells along the box: no inverted element;
// every boundary node reported on F = 0 is on it (the others are those held or not projected);
// the volume within `tolerance` (relative) of the reference.
Meshed check(const IflBody& body, VolumeElements e, int resolution, double tolerance,
             VolumeBoundary boundary = VolumeBoundary::cut) {
  const Meshed m = mesh(body.f, e, resolution, boundary);
  const double error = m.quality.volume / body.reference - 1;
  INFO(kind_name(e) << " at " << resolution << " cells: " << m.quality.elements << " elements, "
                    << m.boundary << " boundary nodes, " << m.off_zero << " off F = 0, held "
                    << m.info.held << ", not projected " << m.info.unprojected << ", volume "
                    << m.quality.volume << " (" << 100 * error << " %)");
  REQUIRE(m.quality.elements > 0);
  CHECK(m.quality.inverted == 0);
  CHECK(m.info.clipped == 0); // the .ifl boxes hold their bodies
  CHECK(m.boundary - m.off_zero >= m.info.on_zero);
  CHECK(m.off_zero <= m.info.held + m.info.unprojected);
  CHECK(std::abs(error) < tolerance);
  return m;
}

} // namespace

// Tolerances: twice the error measured at the test's 24 cells, from the hidden convergence test
// below (Release, 2026-11-28, pillowed hexahedra 2026-11-29; errors at 16 / 24 / 32 / 48 / 64
// cells, fitted order): the volume converges at second order for every kind (flat or bilinear
// facets through points on F = 0), so a tolerance a few times the measured error still catches a
// change of order. The meshes' errors are all negative (chords inside the surface, lost thin
// edges).

TEST_CASE("ifl volume meshes: section body", "[volume][ifl]") {
  // Tetrahedra -4.0 / -1.55 / -0.97 / -0.43 / -0.24 %, order 2.0. Hexahedra (pillowed) -3.6 /
  // -1.27 / -0.85 / -0.33 / -0.20 %, order 2.1. The projected layer -22.8 / -7.4 / -5.0 / -2.2 /
  // -1.3 %: it loses the thin trailing edge (the coverage diagnostic reports 5.4 % lost at 24
  // cells), so the CLI warns.
  check(section_body(), VolumeElements::tetrahedra, 24, 0.031);
  check(section_body(), VolumeElements::hexahedra, 24, 0.026);
  const Meshed layer =
      check(section_body(), VolumeElements::hexahedra, 24, 0.15, VolumeBoundary::projected);
  CHECK(layer.info.held > 0); // the trailing edge holds layer nodes short of F = 0 ...
  CHECK(layer.info.lost_fraction() > kLostVolumeWarning); // ... and the loss is reported
}

TEST_CASE("ifl volume meshes: normalised R-function model", "[volume][ifl]") {
  // Tetrahedra -2.1 / -0.65 / -0.45 / -0.27 / -0.10 %, order 2.0; hexahedra (pillowed) -1.76 /
  // -0.46 / -0.26 / -0.20 / -0.07 %, order 2.3 (the projected layer -5.5 / -1.5 / -0.74 / -0.32 /
  // -0.21 %: the sharp rims are rounded off by the layer).
  check(normalized_tube(), VolumeElements::tetrahedra, 24, 0.013);
  check(normalized_tube(), VolumeElements::hexahedra, 24, 0.0092);
}

TEST_CASE("ifl volume meshes: point-cloud partition of unity", "[volume][ifl]") {
  // Tetrahedra -1.6 / -0.77 / -0.43 / -0.21 / -0.12 %, order 1.9; hexahedra (pillowed) -2.05 /
  // -0.85 / -0.50 / -0.23 / -0.14 %, order 1.9 (the projected layer -3.3 / -1.3 / -0.63 / -0.27 /
  // -0.15 %); the fit's own volume error is below the 0.12 % at 64 cells.
  check(cloud_ellipsoid(), VolumeElements::tetrahedra, 24, 0.016);
  check(cloud_ellipsoid(), VolumeElements::hexahedra, 24, 0.017);
}

TEST_CASE("ifl volume meshes: convergence of the volume", "[volume][ifl][.measure]") {
  // The measurement behind the tolerances above (about 35 s in Release).
  const std::pair<const char*, const IflBody*> bodies[] = {{"section body", &section_body()},
                                                           {"normalised tube", &normalized_tube()},
                                                           {"cloud ellipsoid", &cloud_ellipsoid()}};
  for (const auto& [name, body] : bodies)
    for (const VolumeElements e : {VolumeElements::tetrahedra, VolumeElements::hexahedra})
      for (const int n : {16, 24, 32, 48, 64}) {
        const Meshed m = mesh(body->f, e, n);
        std::printf("%-16s %-10s %3d cells: %8ld elements, inverted %ld, volume %.6f, "
                    "reference %.6f, error %+.3f %%, off F = 0 %ld of %ld (held %ld, not "
                    "projected %ld, reported on F = 0 %ld), lost %.3f %%\n",
                    name, kind_name(e), n, long(m.quality.elements), long(m.quality.inverted),
                    m.quality.volume, body->reference,
                    100 * (m.quality.volume / body->reference - 1), m.off_zero, m.boundary,
                    m.info.held, m.info.unprojected, m.info.on_zero, 100 * m.info.lost_fraction());
        CHECK(m.quality.inverted == 0);
      }
}
