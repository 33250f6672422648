// Volume meshes of an implicit body: interlin's volume_mesh (seed 003's solid-element method,
// tetrahedra) against CGAL's Mesh_3 (Delaunay refinement with ODT, perturbation and exudation) on
// the same R-function model, in one run: element counts, the quality figures of volume_quality
// for both meshes, the volume, the largest |F| at a boundary node, and the time (median of the
// repeats, with the spread) with the ratio CGAL / interlin. interlin runs on 1 thread (CGAL is
// sequential here) and on all cores, and with seed 003's projected boundary layer on 1 thread (the
// default is the clipped grid). A timed CLI run (docs/benchmarks.md, "Volume meshes").
//
// Usage: volume_mesh_baseline [--repeat N] [--cgal-size S] MODEL.rf CELL [MODEL.rf CELL ...]
//   CELL  interlin's grid cell; CGAL's facet_size and cell_size are S x CELL (default S = 1),
//         its facet_distance CELL / 10.

#include "cgal_mesh_3.h"

#include "interlin/interflatation/rfunctions/model.h"
#include "interlin/reconstruction/meshing/volume_mesh.h"
#include "interlin/reconstruction/meshing/volume_quality.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

using namespace interlin;

namespace {

struct Run {
  std::string method;
  VolumeQuality q;
  long nodes = 0, boundary_facets = 0;
  double max_boundary_f = 0;
  std::vector<double> seconds;
};

template <class F>
std::vector<double> timed(int repeat, F&& f) {
  std::vector<double> s;
  for (int r = 0; r < repeat; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    s.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(s.begin(), s.end());
  return s;
}

double median(const std::vector<double>& s) {
  return s[s.size() / 2];
}

double max_abs_f(const ImplicitFunction& f, const Eigen::MatrixXd& V, const Eigen::MatrixXi& B) {
  std::vector<int> ids(B.data(), B.data() + B.size());
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  Points3 P(long(ids.size()), 3);
  for (size_t i = 0; i < ids.size(); ++i)
    P.row(long(i)) = V.row(ids[i]);
  Eigen::VectorXd F(P.rows());
  f.value(P, F);
  return P.rows() ? F.cwiseAbs().maxCoeff() : 0;
}

Run run_interlin(const ImplicitFunction& f, double h, int threads, int repeat,
                 VolumeBoundary boundary = VolumeBoundary::cut) {
  VolumeMeshOptions o;
  o.cell = h;
  o.threads = threads;
  o.boundary = boundary;
  VolumeMesh m;
  Run r;
  const unsigned n =
      threads > 0 ? unsigned(threads) : std::max(1u, std::thread::hardware_concurrency());
  r.method = std::string("interlin volume_mesh tet") +
             (boundary == VolumeBoundary::projected ? " --boundary projected" : "") + ", " +
             std::to_string(n) + " thread" + (n == 1 ? "" : "s");
  r.seconds = timed(repeat, [&] { m = volume_mesh(f, o); });
  r.q = volume_quality(m.V, m.C);
  r.nodes = m.V.rows();
  r.boundary_facets = m.B.rows();
  r.max_boundary_f = max_abs_f(f, m.V, m.B);
  return r;
}

Run run_cgal(const ImplicitFunction& f, double h, double size_factor, int repeat) {
  auto F = [&f](double x, double y, double z) {
    Points3 p(1, 3);
    p << x, y, z;
    Eigen::VectorXd v(1);
    f.value(p, v);
    return v(0);
  };
  bench::CgalMeshOptions o;
  o.size = size_factor * h;
  o.facet_distance = h / 10;
  const Eigen::Vector3d c = f.box.center();
  const double radius = 0.5 * f.box.diagonal().norm() * 1.01;
  Eigen::MatrixXd V;
  Eigen::MatrixXi T, B;
  Run r;
  r.method = "CGAL Mesh_3 (size " + std::to_string(size_factor).substr(0, 4) + " h)";
  r.seconds = timed(repeat, [&] { bench::cgal_mesh_3(F, c, radius, o, V, T, B); });
  r.q = volume_quality(V, T);
  r.nodes = V.rows();
  r.boundary_facets = B.rows();
  r.max_boundary_f = max_abs_f(f, V, B);
  return r;
}

void print(const std::string& model, double h, const Run& r, double reference_seconds) {
  const double t = median(r.seconds);
  std::printf("| %s | %g | %s | %ld | %ld | %ld | %.2f | %.2f | %.3f | %.3f | %.3f | %ld | %ld | "
              "%.6g | %.1e | %.3f (%.3f..%.3f) | %.2f |\n",
              model.c_str(), h, r.method.c_str(), r.q.elements, r.nodes, r.boundary_facets,
              r.q.min_dihedral_deg, r.q.max_dihedral_deg, r.q.min_scaled_jacobian,
              r.q.min_radius_ratio, r.q.mean_radius_ratio, r.q.outside_10_170, r.q.inverted,
              r.q.volume, r.max_boundary_f, t, r.seconds.front(), r.seconds.back(),
              t / reference_seconds);
  std::fflush(stdout);
}

} // namespace

int main(int argc, char** argv) {
  int repeat = 3;
  double size_factor = 1;
  std::vector<std::pair<std::string, double>> cases;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--repeat" && i + 1 < argc)
      repeat = std::max(1, std::atoi(argv[++i]));
    else if (a == "--cgal-size" && i + 1 < argc)
      size_factor = std::atof(argv[++i]);
    else if (i + 1 < argc)
      cases.emplace_back(a, std::atof(argv[++i]));
    else
      cases.clear(), i = argc;
  }
  if (cases.empty() || !(size_factor > 0)) {
    std::fprintf(stderr, "usage: volume_mesh_baseline [--repeat N] [--cgal-size S] MODEL.rf CELL "
                         "[MODEL.rf CELL ...]\n");
    return 2;
  }
  std::printf("| model | cell h | method | elements | nodes | boundary facets | min dihedral | "
              "max dihedral | min scaled Jacobian | min radius ratio | mean radius ratio | "
              "outside [10, 170] | inverted | volume | max abs F at boundary | seconds, median "
              "(min..max of %d) | time / interlin 1 thread |\n",
              repeat);
  std::string rule = "|";
  for (int c = 0; c < 17; ++c)
    rule += "---|";
  std::printf("%s\n", rule.c_str());
  for (const auto& [path, h] : cases) {
    const ImplicitFunction f = load_model(path);
    const std::string model = path.substr(path.find_last_of('/') + 1);
    const Run one = run_interlin(f, h, 1, repeat);
    const double ref = median(one.seconds);
    print(model, h, one, ref);
    print(model, h, run_interlin(f, h, 0, repeat), ref);
    print(model, h, run_interlin(f, h, 1, repeat, VolumeBoundary::projected), ref);
    print(model, h, run_cgal(f, h, size_factor, repeat), ref);
  }
}
