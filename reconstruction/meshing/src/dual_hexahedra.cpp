// Zhang & Bajaj 2006 (§3): hexahedra dual to the inside grid nodes; seed 003's projection of
// boundary points onto F = 0 (§5.1, project_along).
#include "interlin/reconstruction/meshing/dual_hexahedra.h"

#include "interlin/reconstruction/meshing/project_to_zero.h"
#include "interlin/reconstruction/meshing/volume_smoothing.h"

#include "corner_jacobian.h"
#include "node_colouring.h"
#include "parallel.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

namespace interlin {

namespace {

// Halvings of a folded element's boundary points towards their cells' centres before they go all
// the way (a point h / 1024 from the centre folds only where its neighbours do).
constexpr int kHoldHalvings = 10;

// Elements with a corner's scaled Jacobian (alpha over its three edge lengths) below this hold
// their boundary points back. Without it (alpha > 0 only) an inside node near an oblique surface
// gets a hexahedron with 7 corners on F = 0, flat at the outer corner: min 4e-16 on the UAV at
// h = 0.06, 509 elements outside 10 .. 170 degrees; 0.2: min 0.2, none outside, the volume within
// 0.4 % (docs/benchmarks.md, dual hexahedra).
constexpr double kMinScaledJacobian = 0.2;

// restore_held: sweeps over the held points, and the fractions of the way from a cell's centre to
// its target tried, largest first.
constexpr int kRestoreSweeps = 3;
constexpr double kRestoreSteps[] = {1, 0.75, 0.5, 0.25};

// The 12 edges of a cube as pairs of corners (a, b, c) -> a + 2 b + 4 c.
constexpr int kCubeEdge[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                                  {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
// VTK hexahedron corner j -> the cube corner (a, b, c) as a + 2 b + 4 c.
constexpr int kVtkCorner[8] = {0, 1, 3, 2, 4, 5, 7, 6};

// The grid node of cube corner c = a + 2 b + 4 c, as an offset from the cell's lower corner node
// (nx nodes per row, slice per z-plane).
long corner_offset(int c, long nx, long slice) {
  return (c & 1) + ((c >> 1) & 1) * nx + (c >> 2) * slice;
}

// The position of cube corner c of the cell whose lower corner is p0.
Eigen::Vector3d corner_point(const RegularGrid& g, const Eigen::Vector3d& p0, int c) {
  return p0 + Eigen::Vector3d(c & 1, (c >> 1) & 1, c >> 2).cwiseProduct(g.spacing);
}

// The cells (lower corner node indices) with an inside node, in cell order, and per inside node of
// the grid's interior its hexahedron's cells.
struct DualCells {
  std::vector<long> cell; // lower-corner node index of each used cell, ascending
  std::vector<long> node; // the inside nodes of the grid's interior, ascending
  Eigen::MatrixXi C;      // #node by 8: rows of `cell`
};

DualCells dual_cells(const RegularGrid& g, const std::vector<char>& in, int threads) {
  const long nx = g.nodes(0), ny = g.nodes(1), nz = g.nodes(2);
  std::vector<std::vector<long>> nodes(static_cast<size_t>(nz));
  detail::parallel_for(nz, detail::resolve_threads(threads), [&](long k, int) {
    if (k == 0 || k == nz - 1)
      return;
    for (long j = 1; j + 1 < ny; ++j)
      for (long i = 1; i + 1 < nx; ++i)
        if (in[size_t(g.index(i, j, k))])
          nodes[size_t(k)].push_back(g.index(i, j, k));
  });
  DualCells d;
  std::vector<long>& inside = d.node;
  for (const auto& l : nodes)
    inside.insert(inside.end(), l.begin(), l.end());
  const long slice = nx * ny;
  for (long n : inside)
    for (int c = 0; c < 8; ++c)
      d.cell.push_back(n - 1 - nx - slice + corner_offset(c, nx, slice));
  std::sort(d.cell.begin(), d.cell.end());
  d.cell.erase(std::unique(d.cell.begin(), d.cell.end()), d.cell.end());
  d.C.resize(long(inside.size()), 8);
  for (size_t e = 0; e < inside.size(); ++e)
    for (int j = 0; j < 8; ++j) {
      const int c = kVtkCorner[j];
      const long cell = inside[e] - 1 - nx - slice + corner_offset(c, nx, slice);
      d.C(long(e), j) = int(std::lower_bound(d.cell.begin(), d.cell.end(), cell) - d.cell.begin());
    }
  return d;
}

// Each cell's centre, and for cells with a node not inside the mean of the linear roots on its
// edges from an inside to an outside node (flagged in `cut`).
void cell_points(const RegularGrid& g, const Eigen::VectorXd& S, const std::vector<char>& in,
                 const std::vector<long>& cell, Eigen::MatrixXd& centre, Eigen::MatrixXd& mean,
                 std::vector<char>& cut, int threads) {
  const long nx = g.nodes(0), slice = nx * g.nodes(1), n = long(cell.size());
  centre.resize(n, 3);
  mean.resize(n, 3);
  cut.assign(size_t(n), 0);
  detail::parallel_for(n, detail::resolve_threads(threads), [&](long r, int) {
    const long base = cell[size_t(r)];
    const Eigen::Vector3d p0 = g.point(base % nx, (base / nx) % g.nodes(1), base / slice);
    long node[8];
    for (int c = 0; c < 8; ++c)
      node[c] = base + corner_offset(c, nx, slice);
    auto corner = [&](int c) { return corner_point(g, p0, c); };
    centre.row(r) = (p0 + 0.5 * g.spacing).transpose();
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int roots = 0;
    for (const auto& e : kCubeEdge) {
      const int a = in[size_t(node[e[0]])] ? e[0] : e[1], b = a == e[0] ? e[1] : e[0];
      if (!in[size_t(node[a])] || in[size_t(node[b])])
        continue;
      const double fa = S(node[a]), fb = S(node[b]);
      // fb may be NaN or +-inf (outside): the root then sits at the outside node
      const double t = std::isfinite(fb) && fa - fb > 0 ? std::clamp(fa / (fa - fb), 0.0, 1.0) : 1;
      sum += corner(a) + t * (corner(b) - corner(a));
      ++roots;
    }
    cut[size_t(r)] = roots > 0;
    mean.row(r) = roots > 0 ? Eigen::RowVector3d(sum.transpose() / roots) : centre.row(r);
  });
}

// The cut cells' points projected onto F = 0 along -grad F from their means, within a cell
// (further roots belong to another part of the surface). Returns the points left at their means
// (flagged, #target).
std::vector<char> project_cut_points(const ImplicitFunction& f, const RegularGrid& g,
                                     const std::vector<char>& cut, Eigen::MatrixXd& target,
                                     int threads) {
  const double h = g.spacing.minCoeff();
  std::vector<long> rows;
  for (size_t r = 0; r < cut.size(); ++r)
    if (cut[r])
      rows.push_back(long(r));
  Eigen::MatrixXd P(long(rows.size()), 3);
  for (size_t k = 0; k < rows.size(); ++k)
    P.row(long(k)) = target.row(rows[k]);
  const Eigen::MatrixXd D = outward_directions(f, P, 1e-3 * h, threads);
  RootOptions ro;
  ro.threads = threads;
  std::vector<char> ok;
  constexpr double kStep = 0.25, kReach = 4; // h / 4 steps up to a cell
  const Eigen::MatrixXd before = P;
  project_along(f, P, D, Eigen::VectorXd::Constant(P.rows(), kStep * h), ro, &ok, kReach, 1);
  std::vector<char> missed(cut.size(), 0);
  for (size_t k = 0; k < rows.size(); ++k) {
    if (ok[k] && (P.row(long(k)) - before.row(long(k))).norm() <= h)
      target.row(rows[k]) = P.row(long(k));
    else
      missed[size_t(rows[k])] = 1;
  }
  return missed;
}

// The smallest corner scaled Jacobian of hexahedron e (corner_scaled_jacobian); its alpha_j from
// row e of A when given.
double min_corner_jacobian(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C, long e,
                           const Eigen::MatrixXi& corners, const Eigen::MatrixXd* A = nullptr) {
  Eigen::Vector3d p[8];
  double alpha[8];
  for (int j = 0; j < 8; ++j) {
    p[j] = V.row(C(e, j)).transpose();
    alpha[j] = A != nullptr ? (*A)(e, j) : 0;
  }
  return detail::corner_scaled_jacobian(p, corners, A != nullptr ? alpha : nullptr).min_scaled;
}

// The hold moves every boundary point of a poor element, though one of them often suffices. Each
// held point in turn (point order, kRestoreSweeps sweeps) goes back towards its target by the
// largest fraction of kRestoreSteps that keeps every element around it at kMinScaledJacobian.
void restore_held(const Eigen::MatrixXd& centre, const Eigen::MatrixXd& target,
                  const Eigen::MatrixXi& C, const Eigen::MatrixXi& corners, Eigen::MatrixXd& V,
                  std::vector<double>& s) {
  const detail::NodeElements ne(C, V.rows());
  for (int sweep = 0; sweep < kRestoreSweeps; ++sweep)
    for (size_t v = 0; v < s.size(); ++v) {
      if (s[v] >= 1)
        continue;
      const Eigen::RowVector3d keep = V.row(long(v));
      for (const double t : kRestoreSteps) {
        if (t <= s[v])
          break;
        V.row(long(v)) = centre.row(long(v)) + t * (target.row(long(v)) - centre.row(long(v)));
        bool good = true;
        for (long k = ne.start[v]; k < ne.start[v + 1] && good; ++k)
          good = min_corner_jacobian(V, C, ne.at[size_t(k)], corners) >= kMinScaledJacobian;
        if (good) {
          s[v] = t;
          break;
        }
        V.row(long(v)) = keep;
      }
    }
}

// The points still held after restore_held, each projected onto F = 0 from where it stands
// (along -grad F in one batch, within a cell; the restore only moves along the line from the
// cell's centre to its target, the point's own nearest surface point may shape its elements
// better), kept in point order where every element around it stays at kMinScaledJacobian.
void project_held(const ImplicitFunction& f, double h, const Eigen::MatrixXi& C,
                  const Eigen::MatrixXi& corners, const std::vector<char>& missed,
                  Eigen::MatrixXd& V, std::vector<double>& s, int threads) {
  std::vector<long> rows;
  for (size_t v = 0; v < s.size(); ++v)
    if (s[v] < 1 && !missed[v])
      rows.push_back(long(v));
  if (rows.empty())
    return;
  Eigen::MatrixXd P(long(rows.size()), 3);
  for (size_t k = 0; k < rows.size(); ++k)
    P.row(long(k)) = V.row(rows[k]);
  const Eigen::MatrixXd before = P, D = outward_directions(f, P, 1e-3 * h, threads);
  RootOptions ro;
  ro.threads = threads;
  std::vector<char> ok;
  project_along(f, P, D, Eigen::VectorXd::Constant(P.rows(), 0.25 * h), ro, &ok, 4, 1);
  const detail::NodeElements ne(C, V.rows());
  for (size_t k = 0; k < rows.size(); ++k) {
    const long v = rows[k];
    if (!ok[k] || (P.row(long(k)) - before.row(long(k))).norm() > h)
      continue;
    const Eigen::RowVector3d keep = V.row(v);
    V.row(v) = P.row(long(k));
    bool good = true;
    for (long j = ne.start[size_t(v)]; j < ne.start[size_t(v) + 1] && good; ++j)
      good = min_corner_jacobian(V, C, ne.at[size_t(j)], corners) >= kMinScaledJacobian;
    if (good)
      s[size_t(v)] = 1;
    else
      V.row(v) = keep;
  }
}

// The outside corners of a cell (bit c of `inside` clear; corner c = a + 2 b + 4 c) in components
// connected along the cell's edges: label[c] = the component, -1 for inside corners. Returns the
// number of components (one per side of the surface through the cell).
int outside_components(unsigned inside, std::array<signed char, 8>& label) {
  label.fill(-1);
  int count = 0;
  for (int c = 0; c < 8; ++c) {
    if ((inside >> c & 1u) || label[size_t(c)] >= 0)
      continue;
    int stack[8], top = 0;
    stack[top++] = c;
    label[size_t(c)] = static_cast<signed char>(count);
    while (top > 0) {
      const int a = stack[--top];
      for (int axis = 0; axis < 3; ++axis) {
        const int b = a ^ (1 << axis);
        if (!(inside >> b & 1u) && label[size_t(b)] < 0)
          label[size_t(b)] = static_cast<signed char>(count), stack[top++] = b;
      }
    }
    ++count;
  }
  return count;
}

// The pillow layer's surface points of the cells: one per outside component of each cell (first
// surface point of cell r at start[r]), before projection: the mean of the linear roots on the
// edges from inside corners to the component, with the mean of those inside corners and the
// edges' mean unit direction (the component's side).
struct SidePoints {
  std::vector<std::array<signed char, 8>> label; // per cell: outside_components
  std::vector<long> start;                       // #cells + 1
  Eigen::MatrixXd root, inner, side;             // #points by 3
};

SidePoints side_points(const RegularGrid& g, const Eigen::VectorXd& S, const std::vector<char>& in,
                       const std::vector<long>& cell) {
  const long nx = g.nodes(0), slice = nx * g.nodes(1), n = long(cell.size());
  SidePoints sp;
  sp.label.resize(size_t(n));
  sp.start.assign(size_t(n + 1), 0);
  for (long r = 0; r < n; ++r) {
    unsigned inside = 0;
    for (int c = 0; c < 8; ++c)
      inside |= unsigned(in[size_t(cell[size_t(r)] + corner_offset(c, nx, slice))]) << c;
    sp.start[size_t(r + 1)] = sp.start[size_t(r)] + outside_components(inside, sp.label[size_t(r)]);
  }
  const long points = sp.start.back();
  sp.root = Eigen::MatrixXd::Zero(points, 3);
  sp.inner = Eigen::MatrixXd::Zero(points, 3);
  sp.side = Eigen::MatrixXd::Zero(points, 3);
  Eigen::VectorXi roots = Eigen::VectorXi::Zero(points);
  for (long r = 0; r < n; ++r) {
    if (sp.start[size_t(r)] == sp.start[size_t(r + 1)])
      continue;
    const long base = cell[size_t(r)];
    const Eigen::Vector3d p0 = g.point(base % nx, (base / nx) % g.nodes(1), base / slice);
    auto corner = [&](int c) { return Eigen::RowVector3d(corner_point(g, p0, c).transpose()); };
    auto node = [&](int c) { return base + corner_offset(c, nx, slice); };
    for (const auto& e : kCubeEdge) {
      const int a = in[size_t(node(e[0]))] ? e[0] : e[1], b = a == e[0] ? e[1] : e[0];
      if (!in[size_t(node(a))] || in[size_t(node(b))])
        continue;
      const double fa = S(node(a)), fb = S(node(b));
      // fb may be NaN, +-inf or (outer layer) positive: the root then sits at the outside node
      const double t = std::isfinite(fb) && fa - fb > 0 ? std::clamp(fa / (fa - fb), 0.0, 1.0) : 1;
      const long k = sp.start[size_t(r)] + sp.label[size_t(r)][size_t(b)];
      sp.root.row(k) += corner(a) + t * (corner(b) - corner(a));
      sp.inner.row(k) += corner(a);
      sp.side.row(k) += (corner(b) - corner(a)).normalized();
      ++roots(k);
    }
  }
  for (long k = 0; k < points; ++k) {
    sp.root.row(k) /= roots(k);
    sp.inner.row(k) /= roots(k);
    sp.side.row(k).normalize();
  }
  return sp;
}

// The side points projected onto F = 0: along the side direction, then along -grad F, within a
// cell, then within two, each kept only on the component's side of its inside corners ((p - inner)
// . side > 0: from inside a wall thinner than a cell the gradient may lead to the other face);
// last, along -grad F within a cell on either side. The side direction first: the gradient
// gathers neighbouring cells' points onto creases (impeller at h = 0.25: 28 pillows folded before
// untangling, 410 with the gradient first). Returns the points, and flags those with no root
// found (left at the roots' mean).
Eigen::MatrixXd project_side_points(const ImplicitFunction& f, double h, const SidePoints& sp,
                                    std::vector<char>& missed, int threads) {
  constexpr double kStep = 0.25; // h / 4 steps
  RootOptions ro;
  ro.threads = threads;
  const long n = sp.root.rows();
  Eigen::MatrixXd P = sp.root;
  missed.assign(size_t(n), 1);
  std::vector<long> rows(static_cast<size_t>(n));
  for (long k = 0; k < n; ++k)
    rows[size_t(k)] = k;
  for (int pass = 0; pass < 5 && !rows.empty(); ++pass) {
    const bool along_side = pass % 2 == 0 && pass < 4, sided = pass < 4;
    const double reach = pass < 2 || pass == 4 ? 1 : 2; // cells
    Eigen::MatrixXd Q(long(rows.size()), 3), D(long(rows.size()), 3);
    for (size_t j = 0; j < rows.size(); ++j)
      Q.row(long(j)) = sp.root.row(rows[j]), D.row(long(j)) = sp.side.row(rows[j]);
    if (!along_side)
      D = outward_directions(f, Q, 1e-3 * h, threads);
    std::vector<char> ok;
    project_along(f, Q, D, Eigen::VectorXd::Constant(Q.rows(), kStep * h), ro, &ok, reach / kStep,
                  1);
    std::vector<long> again;
    for (size_t j = 0; j < rows.size(); ++j) {
      const long k = rows[j];
      if (ok[j] && (Q.row(long(j)) - sp.root.row(k)).norm() <= reach * h &&
          (!sided || (Q.row(long(j)) - sp.inner.row(k)).dot(sp.side.row(k)) > 0))
        P.row(k) = Q.row(long(j)), missed[size_t(k)] = 0;
      else
        again.push_back(k);
    }
    rows = again;
  }
  return P;
}

// The inside nodes made a manifold core where the pillows need it (Mitchell & Tautges 1995 pillow a
// manifold shrink set): the dual hexahedra of two inside nodes at opposite corners of a grid
// square whose other two corners are outside meet along an edge only; when those two outside
// corners are joined around a cube on the square (one side of the surface, one surface point),
// that point lies over core faces facing opposite ways and no pillow under it is valid. The same
// for the only two inside corners of a cube, opposite ones (they meet at a point). In each such
// square or cube the inside node with the smaller S leaves the core (its neighbours' pillows reach
// F = 0 past it), in passes until none is left. Walls under about a cell thick and oblique to the
// grid are such squares throughout and lose their core (docs/benchmarks.md). Returns the nodes
// removed.
long manifold_core(const RegularGrid& g, const Eigen::VectorXd& S, std::vector<char>& in) {
  const long nx = g.nodes(0), ny = g.nodes(1), nz = g.nodes(2), slice = nx * ny;
  // A cube's faces as corner quadruples (a, b, c, d) in cyclic order.
  constexpr int kSquare[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                 {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
  long removed = 0;
  for (bool changed = true; changed;) {
    changed = false;
    for (long k = 0; k + 1 < nz; ++k)
      for (long j = 0; j + 1 < ny; ++j)
        for (long i = 0; i + 1 < nx; ++i) {
          const long base = g.index(i, j, k);
          long node[8];
          unsigned inside = 0;
          for (int c = 0; c < 8; ++c) {
            node[c] = base + corner_offset(c, nx, slice);
            inside |= unsigned(in[size_t(node[c])]) << c;
          }
          auto drop_weaker = [&](long a, long b) {
            const long n = S(a) <= S(b) ? a : b;
            in[size_t(n)] = 0;
            ++removed;
            changed = true;
          };
          if (inside == 0x81u || inside == 0x42u || inside == 0x24u || inside == 0x18u) {
            const int c = std::countr_zero(inside);
            drop_weaker(node[c], node[c ^ 7]);
            continue;
          }
          std::array<signed char, 8> side;
          outside_components(inside, side);
          for (const auto& q : kSquare) {
            const bool a = inside >> q[0] & 1u, b = inside >> q[1] & 1u, c = inside >> q[2] & 1u,
                       d = inside >> q[3] & 1u;
            const bool joined = a ? side[size_t(q[1])] == side[size_t(q[3])]
                                  : side[size_t(q[0])] == side[size_t(q[2])];
            if (a == c && b == d && a != b && joined) {
              drop_weaker(a ? node[q[0]] : node[q[1]], a ? node[q[2]] : node[q[3]]);
              break;
            }
          }
        }
  }
  return removed;
}

} // namespace

PillowedHexahedra pillowed_hexahedra(const ImplicitFunction& f, const RegularGrid& g,
                                     const Eigen::VectorXd& S, double epsilon, int threads) {
  const long nx = g.nodes(0), ny = g.nodes(1), slice = nx * ny;
  std::vector<char> in(size_t(S.size()));
  for (long n = 0; n < S.size(); ++n)
    in[size_t(n)] = S(n) > epsilon && !g.outer(n % nx, (n / nx) % ny, n / slice);
  const long trimmed = manifold_core(g, S, in);
  const DualCells d = dual_cells(g, in, threads);
  const long cells = long(d.cell.size());
  const SidePoints sp = side_points(g, S, in, d.cell);
  std::vector<char> missed_side;
  const Eigen::MatrixXd surface =
      project_side_points(f, g.spacing.minCoeff(), sp, missed_side, threads);
  const long points = surface.rows();
  PillowedHexahedra out;
  out.trimmed = trimmed;
  out.V.resize(cells + points, 3);
  out.V.bottomRows(points) = surface;
  out.boundary.assign(size_t(cells + points), 0);
  out.missed.assign(size_t(cells + points), 0);
  for (long k = 0; k < points; ++k)
    out.boundary[size_t(cells + k)] = 1, out.missed[size_t(cells + k)] = missed_side[size_t(k)];
  // Core points: the centre of a cell inside, else halfway from its inside corners to its surface
  // points (inside the body where it is convex between them).
  for (long r = 0; r < cells; ++r) {
    const long base = d.cell[size_t(r)];
    const Eigen::RowVector3d p0 = g.point(base % nx, (base / nx) % ny, base / slice).transpose();
    const long first = sp.start[size_t(r)], last = sp.start[size_t(r + 1)];
    if (first == last) {
      out.V.row(r) = p0 + 0.5 * g.spacing.transpose();
      continue;
    }
    Eigen::RowVector3d inner = Eigen::RowVector3d::Zero();
    int count = 0;
    for (int c = 0; c < 8; ++c)
      if (sp.label[size_t(r)][size_t(c)] < 0)
        inner += corner_point(g, p0.transpose(), c).transpose(), ++count;
    inner /= count;
    const Eigen::RowVector3d mean = surface.middleRows(first, last - first).colwise().mean();
    out.V.row(r) = inner + 0.5 * (mean - inner);
    out.split += last - first > 1;
  }
  // The core, then a pillow on each core face towards an outside node: the core hexahedron's face
  // (VTK corners, counter-clockwise seen from outside) for the steps -z, +z, -y, +x, +y, -x.
  constexpr int kFace[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                               {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  const long kStep[6] = {-slice, slice, -nx, 1, nx, -1};
  std::vector<std::array<int, 8>> pillow;
  for (size_t e = 0; e < d.node.size(); ++e)
    for (int s = 0; s < 6; ++s) {
      const long m = d.node[e] + kStep[s];
      if (in[size_t(m)])
        continue;
      std::array<int, 8> h;
      for (int j = 0; j < 4; ++j) {
        const int r = d.C(long(e), kFace[s][j]);
        const long off = m - d.cell[size_t(r)];
        const int c = int(off % nx) + 2 * int((off / nx) % ny) + 4 * int(off / slice);
        h[size_t(j)] = r;
        h[size_t(j + 4)] = int(cells + sp.start[size_t(r)] + sp.label[size_t(r)][size_t(c)]);
      }
      pillow.push_back(h);
    }
  out.core = d.C.rows();
  out.C.resize(out.core + long(pillow.size()), 8);
  out.C.topRows(out.core) = d.C;
  for (size_t q = 0; q < pillow.size(); ++q)
    for (int j = 0; j < 8; ++j)
      out.C(out.core + long(q), j) = pillow[q][size_t(j)];
  return out;
}

DualHexahedra dual_hexahedra(const ImplicitFunction& f, const RegularGrid& g,
                             const Eigen::VectorXd& S, double epsilon, int threads) {
  std::vector<char> in(size_t(S.size()));
  for (long n = 0; n < S.size(); ++n)
    in[size_t(n)] = S(n) > epsilon;
  const DualCells d = dual_cells(g, in, threads);
  DualHexahedra out;
  out.C = d.C;
  Eigen::MatrixXd centre, target;
  cell_points(g, S, in, d.cell, centre, target, out.boundary, threads);
  const std::vector<char> missed = project_cut_points(f, g, out.boundary, target, threads);
  out.unprojected = std::count(missed.begin(), missed.end(), char(1));
  // Hold: boundary points of poor elements go towards their cells' centres; then back one at a
  // time as far as their elements allow.
  out.V = target;
  std::vector<double> s(out.boundary.size(), 1);
  const Eigen::MatrixXi corners = corner_table(8);
  for (int round = 0;; ++round) {
    const Eigen::MatrixXd A =
        corner_alphas(out.V, out.C, threads); // per round (moves within it lag)
    bool folded = false;
    for (long e = 0; e < out.C.rows(); ++e) {
      if (min_corner_jacobian(out.V, out.C, e, corners, &A) >= kMinScaledJacobian)
        continue;
      for (int j = 0; j < 8; ++j) {
        const size_t v = size_t(out.C(e, j));
        if (!out.boundary[v] || s[v] == 0)
          continue;
        s[v] = round < kHoldHalvings ? 0.5 * s[v] : 0;
        out.V.row(long(v)) =
            centre.row(long(v)) + s[v] * (target.row(long(v)) - centre.row(long(v)));
        folded = true;
      }
    }
    if (!folded)
      break;
  }
  restore_held(centre, target, out.C, corners, out.V, s);
  project_held(f, g.spacing.minCoeff(), out.C, corners, missed, out.V, s, threads);
  out.held.assign(out.boundary.size(), 0);
  for (size_t v = 0; v < s.size(); ++v) {
    out.held[v] = missed[v] || s[v] < 1;
    out.held_points += s[v] < 1 && !missed[v];
  }
  return out;
}

} // namespace interlin
