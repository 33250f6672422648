// R-function model -> normalised model (reconstruction/implicit/normalize_model.h).
#include "interlin/reconstruction/implicit/normalize_model.h"

#include "interlin/interflatation/read_input_file.h"
#include "interlin/reconstruction/meshing/implicit_mesh.h"
#include "interlin/reconstruction/meshing/parallel_for.h"

#include <flann/flann.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace interlin {

using Eigen::Index;
using Eigen::Vector3d;

namespace {

// Distance from p to the triangle (a, b, c): the closest point by its Voronoi region
// (vertex, edge or face), Ericson, Real-Time Collision Detection §5.1.5.
double triangle_distance(const Vector3d& p, const Vector3d& a, const Vector3d& b,
                         const Vector3d& c) {
  const Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0)
    return ap.norm();
  const Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3)
    return bp.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0)
    return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6)
    return cp.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0)
    return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double den = 1 / (va + vb + vc);
  return (p - (a + ab * (vb * den) + ac * (vc * den))).norm();
}

} // namespace

NormalizeBuild normalize_model(const std::string& rf_path, const ModelOptions& mo,
                               const NormalizeOptions& o) {
  if (o.resolution < 8 || o.resolution > 1024 || o.mesh_resolution < 0 || o.mesh_resolution > 4096)
    throw std::invalid_argument("normalize: resolution must be from 8 to 1024 (mesh up to 4096)");
  if (!(o.band_inner > 0 && o.band_outer > o.band_inner))
    throw std::invalid_argument("normalize: need 0 < band_inner < band_outer");
  const auto progress = [&](const std::string& s) {
    if (o.progress)
      o.progress(s);
  };
  const int threads = detail::resolve_threads(o.threads);
  NormalizeBuild out;
  NormalizedModel& M = out.model;
  M.source = read_input_file(rf_path);
  M.path = std::filesystem::absolute(rf_path).lexically_normal().string();
  M.options = mo;
  const ImplicitFunction F = parse_model(M.source, rf_path, mo); // messages name the file as given
  M.box = F.box;

  ImplicitMeshOptions mesh;
  mesh.resolution = o.mesh_resolution > 0 ? o.mesh_resolution : std::max(128, 2 * o.resolution);
  mesh.threads = threads;
  progress("meshing F = 0 at resolution " + std::to_string(mesh.resolution));
  Eigen::MatrixXd V;
  Eigen::MatrixXi T;
  implicit_mesh(F, mesh, V, T);
  if (T.rows() == 0)
    throw std::runtime_error(rf_path + ": the model has no surface F = 0 in its box");
  out.report.mesh_vertices = V.rows();
  out.report.mesh_triangles = T.rows();
  std::vector<std::vector<int>> faces_of(static_cast<size_t>(V.rows()));
  for (Index t = 0; t < T.rows(); ++t)
    for (int k = 0; k < 3; ++k)
      faces_of[static_cast<size_t>(T(t, k))].push_back(static_cast<int>(t));

  // Grid over the model's box, two cells beyond it on every side.
  NodeGrid& g = M.grid;
  g.h = M.box.sizes().maxCoeff() / o.resolution;
  g.origin = M.box.min().array() - 2 * g.h;
  for (int a = 0; a < 3; ++a)
    g.n(a) = static_cast<int>(std::ceil(M.box.sizes()(a) / g.h)) + 5;
  const long nodes = static_cast<long>(g.n(0)) * g.n(1) * g.n(2);
  progress("signed distance at " + std::to_string(nodes) + " grid nodes");
  Points3 N(nodes, 3);
  for (int k = 0; k < g.n(2); ++k)
    for (int j = 0; j < g.n(1); ++j)
      for (int i = 0; i < g.n(0); ++i)
        N.row(i + g.n(0) * (j + static_cast<long>(g.n(1)) * k)) =
            (g.origin + g.h * Vector3d(i, j, k)).transpose();
  Eigen::VectorXd sign(nodes);
  F.value(N, sign);
  using RowPoints = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
  RowPoints data = V, query = N;
  flann::Index<flann::L2<double>> index(
      flann::Matrix<double>(data.data(), static_cast<size_t>(data.rows()), 3),
      flann::KDTreeSingleIndexParams(12));
  index.buildIndex();
  std::vector<std::vector<size_t>> nn;
  std::vector<std::vector<double>> d2;
  // The nearest point of a mesh of small triangles lies on a triangle of one of the nearest
  // vertices; 16 of them cover the fans around it.
  index.knnSearch(flann::Matrix<double>(query.data(), static_cast<size_t>(nodes), 3), nn, d2,
                  std::min<int>(16, static_cast<int>(V.rows())),
                  flann::SearchParams(flann::FLANN_CHECKS_UNLIMITED));
  g.values.resize(static_cast<size_t>(nodes));
  detail::parallel_for(nodes, threads, [&](long i, int) {
    const Vector3d p = N.row(i).transpose();
    double best = INFINITY;
    for (size_t v : nn[static_cast<size_t>(i)])
      for (int t : faces_of[v])
        best = std::min(best,
                        triangle_distance(p, V.row(T(t, 0)).transpose(), V.row(T(t, 1)).transpose(),
                                          V.row(T(t, 2)).transpose()));
    g.values[static_cast<size_t>(i)] = sign(i) >= 0 ? best : -best;
  });
  M.band_inner = o.band_inner * g.h;
  M.band_outer = o.band_outer * g.h;

  // Measured on the mesh vertices, points of F = 0.
  const ImplicitFunction w = normalized_model_function(M);
  Points3 P = V;
  Eigen::VectorXd wv(P.rows()), fv(P.rows());
  Points3 G(P.rows(), 3);
  w.value(P, wv);
  F.gradient(P, fv, G);
  out.report.max_zero_omega = wv.cwiseAbs().maxCoeff();
  for (Index i = 0; i < P.rows(); ++i)
    out.report.max_zero_first_order =
        std::max(out.report.max_zero_first_order, std::abs(fv(i)) / G.row(i).norm());
  return out;
}

} // namespace interlin
