// A user's program built against the installed interlin: each step exercises one module and its
// private dependencies at link time (FLANN: project_to_surface, OpenMesh: write_mesh/read_mesh,
// libpng: write_preview_png, threads: implicit_mesh, PCL: estimate_normals). Exit 0 only when every
// check holds.
#include <interlin/interflatation/rfunctions/expression.h>
#include <interlin/interflatation/rfunctions/primitives.h>
#include <interlin/reconstruction/clouds/cloud_filters.h>
#include <interlin/reconstruction/io/mesh_io.h>
#include <interlin/reconstruction/io/preview.h>
#include <interlin/reconstruction/io/section_csv.h>
#include <interlin/reconstruction/loft/closest_point.h>
#include <interlin/reconstruction/loft/loft.h>
#include <interlin/reconstruction/meshing/implicit_mesh.h>
#include <interlin/reconstruction/meshing/mesh_check.h>
#include <interlin/reconstruction/meshing/surface_mesh.h>
#include <interlin/splines/spline_basis.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

int failures = 0;

void check(bool ok, const std::string& what) {
  std::printf("%s %s\n", ok ? "ok  " : "FAIL", what.c_str());
  failures += !ok;
}

// Section k: an ellipse with semi-axes growing along z.
interlin::Section ellipse_section(int k) {
  const int n = 40;
  interlin::Section s;
  s.id = std::to_string(k);
  s.points.resize(n, 3);
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n;
    s.points.row(i) << (2.0 + 0.2 * k) * std::cos(t), (1.0 + 0.1 * k) * std::sin(t), k;
    s.lines.push_back(i + 2);
  }
  return s;
}

} // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : ".";

  // splines: partition of unity of the explicit basis (seed 001 Theorem 1).
  const Eigen::VectorXd knots = (Eigen::VectorXd(9) << 0, 0, 0, 0, 0.3, 1, 1, 1, 1).finished();
  const Eigen::MatrixXd N = interlin::basis_derivatives(interlin::explicit_basis(knots, 3), 0.5, 0);
  check(std::abs(N.sum() - 1) < 1e-14, "explicit basis sums to 1");

  // reconstruction: sections through a file, the loft, distances, mesh files, preview.
  std::vector<interlin::Section> sections;
  for (int k = 0; k < 4; ++k)
    sections.push_back(ellipse_section(k));
  interlin::write_sections_csv(dir + "/sections.csv", sections);
  const interlin::SectionSet set = interlin::read_sections(dir + "/sections.csv");
  const interlin::LoftResult loft = interlin::loft_sections(set.sections);
  check(loft.max_deviation <= 1e-9 * loft.bbox_diagonal, "loft exact on every section");
  const interlin::PiecewiseSurface S = interlin::to_piecewise(loft.surface);
  const Eigen::MatrixXd P = sections[2].points.topRows(5);
  const interlin::SurfaceProjection proj = interlin::project_to_surface(S, P);
  check(proj.distance.maxCoeff() < 1e-9, "input points lie on the surface (FLANN starts)");

  interlin::SurfaceMeshOptions mo;
  mo.nu = 60, mo.nv = 12, mo.cap = true;
  Eigen::MatrixXd V, V2;
  Eigen::MatrixXi F, F2;
  interlin::surface_mesh(S, mo, V, F);
  check(interlin::check_mesh(V, F).watertight(), "capped loft mesh is watertight");
  interlin::write_mesh(dir + "/blade.stl", V, F);
  interlin::read_mesh(dir + "/blade.stl", V2, F2);
  check(F2.rows() == F.rows(), "STL round trip through OpenMesh");
  interlin::write_preview_png(dir + "/blade.png", V, F);

  // interflatation + meshing: an R-function sphere meshed on two threads.
  using namespace interlin::rf;
  const interlin::ImplicitFunction ball =
      compile(sphere(Expr::x(), Expr::y(), Expr::z(), 1.0),
              Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-1.5), Eigen::Vector3d::Constant(1.5)));
  interlin::ImplicitMeshOptions io;
  io.resolution = 24;
  io.threads = 2;
  interlin::implicit_mesh(ball, io, V, F);
  const interlin::MeshReport r = interlin::check_mesh(V, F);
  check(r.watertight() && std::abs(r.volume - 4 * M_PI / 3) < 0.05, "implicit sphere mesh");

  // clouds: PCL's normals of points on the implicit sphere point along the radius.
  const Eigen::MatrixX3d cloud = V.topRows(std::min<Eigen::Index>(V.rows(), 400));
  const Eigen::MatrixX3d normals = interlin::estimate_normals(cloud, 8, 1);
  double worst = 1;
  for (Eigen::Index i = 0; i < cloud.rows(); ++i)
    worst = std::min(worst, std::abs(normals.row(i).dot(cloud.row(i).normalized())));
  check(worst > 0.9, "PCL normals of a sphere are radial");

  std::printf("%s\n", failures ? "consumer: FAILED" : "consumer: all checks passed");
  return failures ? 1 : 0;
}
