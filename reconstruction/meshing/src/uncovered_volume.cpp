// The part of the body a volume mesh leaves out, measured on the grid's clipped tetrahedra.
#include "interlin/reconstruction/meshing/uncovered_volume.h"

#include "interlin/reconstruction/meshing/volume_mesh.h"

#include "parallel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

namespace interlin {

namespace {

// The hexahedron (VTK order) as 6 tetrahedra around its diagonal 0-6.
constexpr int kHexTets[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6},
                                {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};

double det(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
           const Eigen::Vector3d& d) {
  return (b - a).cross(c - a).dot(d - a);
}

// p in the tetrahedron (either orientation) up to kSlack of its volume per barycentric coordinate
// (a centroid on a face shared by two elements is in one of them).
bool in_tetrahedron(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                    const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  constexpr double kSlack = 1e-9;
  const double D = det(a, b, c, d);
  if (D == 0)
    return false;
  const double s = D > 0 ? 1 : -1, floor = -kSlack * std::abs(D);
  return s * det(p, b, c, d) >= floor && s * det(a, p, c, d) >= floor &&
         s * det(a, b, p, d) >= floor && s * det(a, b, c, p) >= floor;
}

bool element_contains(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C, long e,
                      const Eigen::Vector3d& p) {
  auto at = [&](int j) -> Eigen::Vector3d { return V.row(C(e, j)).transpose(); };
  if (C.cols() == 4)
    return in_tetrahedron(p, at(0), at(1), at(2), at(3));
  for (const auto& t : kHexTets)
    if (in_tetrahedron(p, at(t[0]), at(t[1]), at(t[2]), at(t[3])))
      return true;
  return false;
}

// (cube, element) for every cube of g that an element's bounding box overlaps, sorted by cube.
std::vector<std::pair<long, int>> elements_by_cube(const RegularGrid& g, const Eigen::MatrixXd& V,
                                                   const Eigen::MatrixXi& C) {
  const Eigen::Array3i cells = g.nodes - 1;
  auto cube = [&](double x, int a) {
    const long i = long(std::floor((x - g.origin(a)) / g.spacing(a)));
    return std::clamp(i, 0L, long(cells(a)) - 1);
  };
  std::vector<std::pair<long, int>> out;
  for (long e = 0; e < C.rows(); ++e) {
    Eigen::Array3d lo = V.row(C(e, 0)).transpose(), hi = lo;
    for (long j = 1; j < C.cols(); ++j) {
      lo = lo.min(V.row(C(e, j)).transpose().array());
      hi = hi.max(V.row(C(e, j)).transpose().array());
    }
    for (long k = cube(lo(2), 2); k <= cube(hi(2), 2); ++k)
      for (long j = cube(lo(1), 1); j <= cube(hi(1), 1); ++j)
        for (long i = cube(lo(0), 0); i <= cube(hi(0), 0); ++i)
          out.emplace_back(i + cells(0) * (j + cells(1) * k), int(e));
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The area of the faces of the flagged tetrahedra of T that lie on the boundary of T.
double boundary_area_of(const Eigen::MatrixXd& P, const Eigen::MatrixXi& T,
                        const std::vector<char>& flagged) {
  const Eigen::MatrixXi B = boundary_facets(T);
  std::vector<std::array<int, 3>> keys(size_t(B.rows()));
  for (long r = 0; r < B.rows(); ++r) {
    keys[size_t(r)] = {B(r, 0), B(r, 1), B(r, 2)};
    std::sort(keys[size_t(r)].begin(), keys[size_t(r)].end());
  }
  std::sort(keys.begin(), keys.end());
  double area = 0;
  for (long e = 0; e < T.rows(); ++e) {
    if (!flagged[size_t(e)])
      continue;
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> k;
      for (int j = 0, n = 0; j < 4; ++j)
        if (j != skip)
          k[size_t(n++)] = T(e, j);
      std::sort(k.begin(), k.end());
      if (std::binary_search(keys.begin(), keys.end(), k)) {
        const Eigen::Vector3d a = P.row(k[0]), b = P.row(k[1]), c = P.row(k[2]);
        area += (b - a).cross(c - a).norm() / 2;
      }
    }
  }
  return area;
}

} // namespace

UncoveredVolume uncovered_volume(const CutTetrahedra& body, const RegularGrid& g,
                                 const Eigen::MatrixXd& V, const Eigen::MatrixXi& C, int threads) {
  if (C.cols() != 4 && C.cols() != 8)
    throw std::invalid_argument("uncovered_volume: C must be #C by 4 or #C by 8");
  if (V.cols() != 3)
    throw std::invalid_argument("uncovered_volume: V must be #V by 3");
  const std::vector<std::pair<long, int>> buckets = elements_by_cube(g, V, C);
  const Eigen::Array3i cells = g.nodes - 1;
  const Eigen::MatrixXd& P = body.V;
  const Eigen::MatrixXi& T = body.C;
  constexpr long kChunk = 4096; // pieces per task; partial sums added in task order (deterministic)
  const long tasks = (T.rows() + kChunk - 1) / kChunk;
  std::vector<double> body_part(size_t(tasks), 0), lost_part(size_t(tasks), 0);
  std::vector<char> lost(size_t(T.rows()), 0);
  detail::parallel_for(tasks, detail::resolve_threads(threads), [&](long task, int) {
    for (long e = task * kChunk; e < std::min(T.rows(), (task + 1) * kChunk); ++e) {
      const Eigen::Vector3d a = P.row(T(e, 0)), b = P.row(T(e, 1)), c = P.row(T(e, 2)),
                            d = P.row(T(e, 3));
      const double volume = std::abs(det(a, b, c, d)) / 6;
      const Eigen::Vector3d p = (a + b + c + d) / 4;
      long cube = 0;
      for (int axis = 2; axis >= 0; --axis) {
        const long i = long(std::floor((p(axis) - g.origin(axis)) / g.spacing(axis)));
        cube = cube * cells(axis) + std::clamp(i, 0L, long(cells(axis)) - 1);
      }
      const auto range =
          std::equal_range(buckets.begin(), buckets.end(), std::pair<long, int>{cube, -1},
                           [](const auto& x, const auto& y) { return x.first < y.first; });
      bool covered = false;
      for (auto it = range.first; it != range.second && !covered; ++it)
        covered = element_contains(V, C, it->second, p);
      body_part[size_t(task)] += volume;
      if (!covered)
        lost[size_t(e)] = 1, lost_part[size_t(task)] += volume;
    }
  });
  UncoveredVolume out;
  for (long t = 0; t < tasks; ++t)
    out.body += body_part[size_t(t)], out.lost += lost_part[size_t(t)];
  if (out.lost > 0)
    out.lost_area = boundary_area_of(P, T, lost);
  return out;
}

} // namespace interlin
