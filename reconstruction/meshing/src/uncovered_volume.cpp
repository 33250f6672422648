// The part of the body a volume mesh leaves out, measured on the grid's clipped tetrahedra.
#include "interlin/reconstruction/meshing/uncovered_volume.h"

#include "interlin/reconstruction/meshing/volume_mesh.h"

#include "parallel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
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

// Elements by the cubes of g their bounding boxes overlap: (cube, element) sorted by cube, and
// the elements whose boxes span more than kMaxCubes cubes apart (a distorted element must not
// fill memory with pairs; each of those is tried for every point).
struct ElementBuckets {
  static constexpr long kMaxCubes = 4096;
  std::vector<std::pair<long, int>> by_cube;
  std::vector<int> oversized;
};

ElementBuckets elements_by_cube(const RegularGrid& g, const Eigen::MatrixXd& V,
                                const Eigen::MatrixXi& C) {
  const Eigen::Array3i cells = g.nodes - 1;
  auto cube = [&](double x, int a) {
    const double i = std::floor((x - g.origin(a)) / g.spacing(a));
    return std::isnan(i) ? 0L : long(std::clamp(i, 0.0, double(cells(a) - 1)));
  };
  ElementBuckets out;
  for (long e = 0; e < C.rows(); ++e) {
    Eigen::Array3d lo = V.row(C(e, 0)).transpose(), hi = lo;
    for (long j = 1; j < C.cols(); ++j) {
      lo = lo.min(V.row(C(e, j)).transpose().array());
      hi = hi.max(V.row(C(e, j)).transpose().array());
    }
    long span = 1;
    for (int a = 0; a < 3; ++a)
      span *= cube(hi(a), a) - cube(lo(a), a) + 1;
    if (span > ElementBuckets::kMaxCubes || !lo.allFinite() || !hi.allFinite()) {
      out.oversized.push_back(int(e));
      continue;
    }
    for (long k = cube(lo(2), 2); k <= cube(hi(2), 2); ++k)
      for (long j = cube(lo(1), 1); j <= cube(hi(1), 1); ++j)
        for (long i = cube(lo(0), 0); i <= cube(hi(0), 0); ++i)
          out.by_cube.emplace_back(i + cells(0) * (j + cells(1) * k), int(e));
  }
  std::sort(out.by_cube.begin(), out.by_cube.end());
  return out;
}

// The area of each tetrahedron's faces that lie on the boundary of T (F = 0 or the box), and the
// sum over the flagged ones (in batches of tetrahedra on `threads` threads, added in order).
double boundary_area_of(const Eigen::MatrixXd& P, const Eigen::MatrixXi& T,
                        const std::vector<char>& flagged, std::vector<double>& per_tetrahedron,
                        int threads) {
  const Eigen::MatrixXi B = boundary_facets(T, threads);
  std::vector<std::array<int, 3>> keys(size_t(B.rows()));
  for (long r = 0; r < B.rows(); ++r) {
    keys[size_t(r)] = {B(r, 0), B(r, 1), B(r, 2)};
    std::sort(keys[size_t(r)].begin(), keys[size_t(r)].end());
  }
  std::sort(keys.begin(), keys.end());
  per_tetrahedron.assign(size_t(T.rows()), 0);
  constexpr long kChunk = 4096; // tetrahedra per task; partial sums added in task order
  std::vector<double> part(size_t(detail::chunk_count(T.rows(), kChunk)), 0);
  detail::parallel_chunks(T.rows(), kChunk, threads, [&](long task, long e0, long e1) {
    for (long e = e0; e < e1; ++e)
      for (int skip = 0; skip < 4; ++skip) {
        std::array<int, 3> k;
        for (int j = 0, n = 0; j < 4; ++j)
          if (j != skip)
            k[size_t(n++)] = T(e, j);
        std::sort(k.begin(), k.end());
        if (!std::binary_search(keys.begin(), keys.end(), k))
          continue;
        const Eigen::Vector3d a = P.row(k[0]), b = P.row(k[1]), c = P.row(k[2]);
        const double facet = (b - a).cross(c - a).norm() / 2;
        per_tetrahedron[size_t(e)] += facet;
        if (flagged[size_t(e)])
          part[size_t(task)] += facet;
      }
  });
  double area = 0;
  for (double a : part)
    area += a;
  return area;
}

// (cube, sum of (volume, area)) over the pieces e with keep[e], one entry per cube, by cube.
std::vector<std::pair<long, Eigen::Vector2d>> per_cube(const std::vector<long>& cube_of,
                                                       const std::vector<Eigen::Vector2d>& value,
                                                       const std::vector<char>* keep) {
  std::vector<std::pair<long, Eigen::Vector2d>> out;
  for (size_t e = 0; e < cube_of.size(); ++e)
    if (keep == nullptr || (*keep)[e]) {
      if (!out.empty() && out.back().first == cube_of[e])
        out.back().second += value[e];
      else
        out.emplace_back(cube_of[e], value[e]);
    }
  std::stable_sort(out.begin(), out.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  size_t n = 0; // pieces of one cube that were not consecutive
  for (size_t m = 0; m < out.size(); ++m)
    if (n > 0 && out[n - 1].first == out[m].first)
      out[n - 1].second += out[m].second;
    else
      out[n++] = out[m];
  out.resize(n);
  return out;
}

// (local wall thickness, lost volume) per cube with lost pieces, thinnest first: 2 V / A of the
// body's volume V and boundary area A within kThicknessReach cubes (infinite with no boundary
// there).
std::vector<std::pair<double, double>>
thickness_distribution(const std::vector<std::pair<long, Eigen::Vector2d>>& lost_in_cube,
                       const std::vector<std::pair<long, Eigen::Vector2d>>& body_in_cube,
                       const Eigen::Array3i& cells) {
  std::vector<std::pair<double, double>> out;
  out.reserve(lost_in_cube.size());
  const long nx = cells(0), ny = cells(1), nz = cells(2), r = kThicknessReach;
  for (const auto& [cube, lost] : lost_in_cube) {
    const long i = cube % nx, j = (cube / nx) % ny, k = cube / (nx * ny);
    Eigen::Vector2d near = Eigen::Vector2d::Zero(); // body volume, boundary area
    for (long z = std::max(0L, k - r); z <= std::min(nz - 1, k + r); ++z)
      for (long y = std::max(0L, j - r); y <= std::min(ny - 1, j + r); ++y) {
        const long row = nx * (y + ny * z);
        // a row of cubes i - r .. i + r is contiguous in cube order
        auto it =
            std::lower_bound(body_in_cube.begin(), body_in_cube.end(), row + std::max(0L, i - r),
                             [](const auto& x, long c) { return x.first < c; });
        for (; it != body_in_cube.end() && it->first <= row + std::min(nx - 1, i + r); ++it)
          near += it->second;
      }
    out.emplace_back(near(1) > 0 ? 2 * near(0) / near(1) : std::numeric_limits<double>::infinity(),
                     lost(0));
  }
  std::sort(out.begin(), out.end());
  return out;
}

// out.lost_area and out.lost_by_thickness from the lost pieces (flagged) and each piece's cube.
void measure_lost_walls(const CutTetrahedra& body, const Eigen::Array3i& cells,
                        const std::vector<char>& lost, const std::vector<long>& cube_of,
                        UncoveredVolume& out, int threads) {
  const Eigen::MatrixXd& P = body.V;
  const Eigen::MatrixXi& T = body.C;
  std::vector<double> area;
  out.lost_area = boundary_area_of(P, T, lost, area, threads);
  std::vector<Eigen::Vector2d> piece(size_t(T.rows())); // volume, boundary area
  for (long e = 0; e < T.rows(); ++e) {
    const Eigen::Vector3d a = P.row(T(e, 0)), b = P.row(T(e, 1)), c = P.row(T(e, 2)),
                          d = P.row(T(e, 3));
    piece[size_t(e)] = Eigen::Vector2d(std::abs(det(a, b, c, d)) / 6, area[size_t(e)]);
  }
  out.lost_by_thickness = thickness_distribution(per_cube(cube_of, piece, &lost),
                                                 per_cube(cube_of, piece, nullptr), cells);
}

} // namespace

double cell_keeping(const UncoveredVolume& u, double h, double budget, double cells_across_wall,
                    double kept_wall_cells) {
  if (u.lost <= budget)
    return 0;
  double edges = 0; // lost from walls the grid should keep
  for (const auto& [thickness, volume] : u.lost_by_thickness)
    edges += thickness >= kept_wall_cells * h ? volume : 0;
  constexpr int kSteps = 32, kMaxHalvings = 8; // candidates h 2^(-k / 32), down to h / 256
  for (int k = 1; k <= kSteps * kMaxHalvings; ++k) {
    const double cell = h * std::exp2(-double(k) / kSteps);
    double lost = edges * cell / h;
    for (const auto& [thickness, volume] : u.lost_by_thickness) {
      if (thickness >= cells_across_wall * cell) // thinnest first: the rest are kept
        break;
      lost += thickness < kept_wall_cells * h ? volume : 0;
    }
    if (lost <= budget)
      return cell;
  }
  return h * std::exp2(-kMaxHalvings);
}

UncoveredVolume uncovered_volume(const CutTetrahedra& body, const RegularGrid& g,
                                 const Eigen::MatrixXd& V, const Eigen::MatrixXi& C, int threads) {
  if (C.cols() != 4 && C.cols() != 8)
    throw std::invalid_argument("uncovered_volume: C must be #C by 4 or #C by 8");
  if (V.cols() != 3)
    throw std::invalid_argument("uncovered_volume: V must be #V by 3");
  const ElementBuckets buckets = elements_by_cube(g, V, C);
  const Eigen::Array3i cells = g.nodes - 1;
  const Eigen::MatrixXd& P = body.V;
  const Eigen::MatrixXi& T = body.C;
  constexpr long kChunk = 4096; // pieces per task; partial sums added in task order (deterministic)
  const long tasks = detail::chunk_count(T.rows(), kChunk);
  std::vector<double> body_part(size_t(tasks), 0), lost_part(size_t(tasks), 0);
  std::vector<char> lost(size_t(T.rows()), 0);
  std::vector<long> cube_of(size_t(T.rows()));
  detail::parallel_chunks(T.rows(), kChunk, threads, [&](long task, long e0, long e1) {
    for (long e = e0; e < e1; ++e) {
      const Eigen::Vector3d a = P.row(T(e, 0)), b = P.row(T(e, 1)), c = P.row(T(e, 2)),
                            d = P.row(T(e, 3));
      const double volume = std::abs(det(a, b, c, d)) / 6;
      const Eigen::Vector3d p = (a + b + c + d) / 4;
      long cube = 0;
      for (int axis = 2; axis >= 0; --axis) {
        const long i = long(std::floor((p(axis) - g.origin(axis)) / g.spacing(axis)));
        cube = cube * cells(axis) + std::clamp(i, 0L, long(cells(axis)) - 1);
      }
      const auto range = std::equal_range(
          buckets.by_cube.begin(), buckets.by_cube.end(), std::pair<long, int>{cube, -1},
          [](const auto& x, const auto& y) { return x.first < y.first; });
      bool covered = false;
      for (auto it = range.first; it != range.second && !covered; ++it)
        covered = element_contains(V, C, it->second, p);
      for (size_t k = 0; k < buckets.oversized.size() && !covered; ++k)
        covered = element_contains(V, C, buckets.oversized[k], p);
      cube_of[size_t(e)] = cube;
      body_part[size_t(task)] += volume;
      if (!covered)
        lost[size_t(e)] = 1, lost_part[size_t(task)] += volume;
    }
  });
  UncoveredVolume out;
  for (long t = 0; t < tasks; ++t)
    out.body += body_part[size_t(t)], out.lost += lost_part[size_t(t)];
  if (out.lost == 0)
    return out;
  measure_lost_walls(body, cells, lost, cube_of, out, threads);
  return out;
}

} // namespace interlin
