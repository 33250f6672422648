// Seed 003, digest §6.2: the solid-element method for tetrahedra and hexahedra.
#include "interlin/reconstruction/meshing/volume_mesh.h"

#include "interlin/reconstruction/meshing/cut_tetrahedra.h"
#include "interlin/reconstruction/meshing/dual_hexahedra.h"
#include "interlin/reconstruction/meshing/project_to_zero.h"
#include "interlin/reconstruction/meshing/surface_smoothing.h"

#include "corner_jacobian.h"
#include "open_flat_corners.h"
#include "parallel.h"
#include "untangle.h"
#include "value_and_gradient.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <stdexcept>
#include <string>

namespace interlin {

namespace {

// A boundary node's surface point is at most a cell diagonal (sqrt 3 h) away when the grid
// resolves the body there, but the smoothed normal may run at a slant; the projection looks 4
// cells (8 steps of h/2) far. Nodes beyond that
// sit under features thinner than a cell and are reported (unprojected).
constexpr double kLayerReach = 8;

constexpr int kTetFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
constexpr int kHexFace[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

// The facets of the elements C (#C by 4 or 8), numbered id = element x faces + face, their
// corners in the order of kTetFace or kHexFace (outward).
struct ElementFacets {
  const Eigen::MatrixXi& C;
  bool tets = C.cols() == 4;
  int faces = tets ? 4 : 6, per = tets ? 3 : 4;

  int corner(long id, int j) const {
    return C(id / faces, tets ? kTetFace[id % faces][j] : kHexFace[id % faces][j]);
  }
  int smallest(long id) const {
    int m = corner(id, 0);
    for (int j = 1; j < per; ++j)
      m = std::min(m, corner(id, j));
    return m;
  }
  std::array<int, 4> key(long id) const { // the sorted corners (a triangle's fourth INT_MAX)
    std::array<int, 4> k;
    k.fill(INT_MAX);
    for (int j = 0; j < per; ++j)
      k[size_t(j)] = corner(id, j);
    std::sort(k.begin(), k.end());
    return k;
  }
  // Flags (once[id]) the facets of `bucket` (key, id) whose key no other one has.
  static void mark_once(std::vector<std::pair<std::array<int, 4>, long>>& bucket,
                        std::vector<char>& once) {
    std::sort(bucket.begin(), bucket.end());
    for (size_t s = 0; s < bucket.size(); ++s)
      once[size_t(bucket[s].second)] =
          (s == 0 || bucket[s - 1].first != bucket[s].first) &&
          (s + 1 == bucket.size() || bucket[s + 1].first != bucket[s].first);
  }
};

constexpr long kBatch = 4096; // points or elements per task

// F at the rows of P, in batches on `threads` threads.
Eigen::VectorXd values(const ImplicitFunction& f, const Points3& P, int threads) {
  Eigen::VectorXd F(P.rows());
  detail::parallel_chunks(P.rows(), kBatch, threads, [&](long, long r0, long r1) {
    f.value(P.middleRows(r0, r1 - r0), F.segment(r0, r1 - r0));
  });
  return F;
}

// value_and_gradient at the rows of P, in batches on `threads` threads.
void values_and_gradients(const ImplicitFunction& f, const Points3& P, double d, int threads,
                          Eigen::VectorXd& F, Points3& G) {
  F.resize(P.rows());
  G.resize(P.rows(), 3);
  detail::parallel_chunks(P.rows(), kBatch, threads, [&](long, long r0, long r1) {
    const long m = r1 - r0;
    detail::value_and_gradient(f, P.middleRows(r0, m), d, F.segment(r0, m), G.middleRows(r0, m));
  });
}

// Nodes with |F| <= epsilon none of whose 26 neighbours is outside (F < -epsilon) lie on a sheet
// where F touches zero inside the body (R-function unions of parts that meet face to face, such
// as the impeller's blades and shroud at z = 4): they are interior, not boundary. Their values are
// set to 2 epsilon (inside by either rule). Returns their number.
long fill_zero_sheets(const RegularGrid& g, Eigen::VectorXd& S, double epsilon, int threads) {
  const long nx = g.nodes(0), ny = g.nodes(1), nz = g.nodes(2);
  std::vector<std::vector<long>> per_slice(static_cast<size_t>(nz));
  detail::parallel_for(nz, detail::resolve_threads(threads), [&](long k, int) {
    for (long j = 0; j < ny; ++j)
      for (long i = 0; i < nx; ++i) {
        if (!(std::abs(S(g.index(i, j, k))) <= epsilon))
          continue;
        bool outside = false;
        for (long dk = -1; dk <= 1 && !outside; ++dk)
          for (long dj = -1; dj <= 1 && !outside; ++dj)
            for (long di = -1; di <= 1 && !outside; ++di) {
              const long a = i + di, b = j + dj, c = k + dk;
              outside = a < 0 || b < 0 || c < 0 || a >= nx || b >= ny || c >= nz ||
                        !(S(g.index(a, b, c)) >= -epsilon);
            }
        if (!outside)
          per_slice[size_t(k)].push_back(g.index(i, j, k));
      }
  });
  long filled = 0;
  for (const auto& l : per_slice)
    for (long n : l)
      S(n) = 2 * epsilon, ++filled;
  return filled;
}

// Inside nodes (by the rule) with F <= 0 at `distance` from them down the gradient (nearer to the
// surface than that) are set to -1 (outside). Only nodes of a cube with a node that is not inside
// are candidates: any node nearer to the surface than one cell is one (distance < h). Returns the
// number of nodes dropped.
long drop_near_surface(const ImplicitFunction& f, const RegularGrid& g, Eigen::VectorXd& S,
                       const BoundaryMeshOptions& bo, double distance) {
  auto inside = [&](double v) {
    return bo.rule == ZeroRule::strict ? v > bo.epsilon : v >= -bo.epsilon;
  };
  const long nx = g.nodes(0), ny = g.nodes(1), nz = g.nodes(2), slice = nx * ny;
  std::vector<std::vector<long>> per_slice(static_cast<size_t>(nz));
  detail::parallel_for(nz, detail::resolve_threads(bo.threads), [&](long k, int) {
    for (long j = 0; j < ny; ++j)
      for (long i = 0; i < nx; ++i) {
        const long n = g.index(i, j, k);
        if (!inside(S(n)))
          continue;
        bool near = false;
        for (long dk = -1; dk <= 1 && !near; ++dk)
          for (long dj = -1; dj <= 1 && !near; ++dj)
            for (long di = -1; di <= 1 && !near; ++di) {
              const long a = i + di, b = j + dj, c = k + dk;
              near = a >= 0 && b >= 0 && c >= 0 && a < nx && b < ny && c < nz &&
                     !inside(S(g.index(a, b, c)));
            }
        if (near)
          per_slice[size_t(k)].push_back(n);
      }
  });
  std::vector<long> cand;
  for (const auto& l : per_slice)
    cand.insert(cand.end(), l.begin(), l.end());
  Points3 P(long(cand.size()), 3);
  for (size_t r = 0; r < cand.size(); ++r) {
    const long n = cand[r];
    P.row(long(r)) = g.point(n % nx, (n / nx) % ny, n / slice).transpose();
  }
  Eigen::VectorXd F;
  Points3 G;
  values_and_gradients(f, P, 1e-3 * g.spacing.minCoeff(), bo.threads, F, G);
  // The point `distance` down the gradient: the node is near the surface when F has changed sign
  // there (F / |grad F| alone misleads where an R-function joins parts: inside the union the
  // gradient of the part that vanishes on the seam dominates).
  Points3 Q = P;
  for (long r = 0; r < P.rows(); ++r) {
    const double grad = G.row(r).norm();
    if (std::isfinite(grad) && grad > 0)
      Q.row(r) -= distance / grad * G.row(r);
  }
  const Eigen::VectorXd FQ = values(f, Q, bo.threads);
  long dropped = 0;
  for (size_t r = 0; r < cand.size(); ++r)
    if (!(FQ(long(r)) > 0) && G.row(long(r)).allFinite() && G.row(long(r)).norm() > 0) {
      S(cand[r]) = -1;
      ++dropped;
    }
  return dropped;
}

// The 3 tetrahedra of the prism with bottom b[0..2] (outward, counter-clockwise from outside)
// and top t[0..2] (their projections; every top index exceeds every bottom index). Dompierre et
// al.'s rule: rotate so the smallest index is local vertex 0, then each quadrilateral face is cut
// along the diagonal from its smallest index, which neighbouring prisms share.
void split_prism(const int b[3], const int t[3], std::array<std::array<int, 4>, 3>& out) {
  const int r = int(std::min_element(b, b + 3) - b);
  const int v[6] = {b[r], b[(r + 1) % 3], b[(r + 2) % 3], t[r], t[(r + 1) % 3], t[(r + 2) % 3]};
  // Local tetrahedra, positively oriented on the right prism (bottom counter-clockwise seen from
  // the top).
  static constexpr int kFirst[3][4] = {{0, 1, 2, 5}, {0, 1, 5, 4}, {0, 4, 5, 3}};
  static constexpr int kSecond[3][4] = {{0, 1, 2, 4}, {0, 4, 2, 5}, {0, 4, 5, 3}};
  const auto& local = std::min(v[1], v[5]) < std::min(v[2], v[4]) ? kFirst : kSecond;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 4; ++j)
      out[size_t(k)][size_t(j)] = v[local[k][j]];
}

// is(e) for the elements e in [0, elements), in batches on `threads` threads.
template <class Predicate>
std::vector<char> element_flags(long elements, int threads, Predicate&& is) {
  std::vector<char> flags(static_cast<size_t>(elements));
  detail::parallel_chunks(elements, kBatch, threads, [&](long, long e0, long e1) {
    for (long e = e0; e < e1; ++e)
      flags[size_t(e)] = is(e);
  });
  return flags;
}

// The elements folded at a corner (alpha <= 0) or, hexahedra, at the centre (the trilinear map's
// Jacobian <= 0 there, though every corner may be convex: volume_quality counts both).
std::vector<char> folded_elements(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C, int threads) {
  const Eigen::MatrixXd A = corner_alphas(V, C, threads);
  return element_flags(C.rows(), threads, [&](long e) {
    if (!(A.row(e).minCoeff() > 0))
      return true;
    if (C.cols() != 8)
      return false;
    Eigen::Vector3d p[8];
    for (int j = 0; j < 8; ++j)
      p[j] = V.row(C(e, j)).transpose();
    return !(detail::centre_jacobian(p) > 0);
  });
}

// A projected boundary layer: its nodes n_inner + r are the copies of the inner nodes below[r];
// the facets bottom (#P by 3 or 4, inner nodes, outward) and top (their copies).
struct ProjectedLayer {
  long n_inner = 0;
  std::vector<int> below;
  Eigen::MatrixXi bottom, top;
};

// A unit direction d with d . n > 0 for every n in N (#N by 3, unit rows) where one is easily
// found: from their mean, steps towards the worst-served n (a perceptron) until each gets
// kMinCosine. Returns the best one found.
Eigen::RowVector3d direction_above(const Eigen::MatrixXd& N) {
  constexpr int kSteps = 50;
  constexpr double kMinCosine = 0.1; // about 6 degrees above every face
  Eigen::RowVector3d d = N.colwise().sum();
  d = d.norm() > 0 ? Eigen::RowVector3d(d.normalized()) : Eigen::RowVector3d(N.row(0));
  for (int k = 0; k < kSteps; ++k) {
    Eigen::Index worst;
    const double c = (N * d.transpose()).minCoeff(&worst);
    if (c >= kMinCosine)
      break;
    d += (kMinCosine - c) * N.row(worst);
    d.normalize();
  }
  return d;
}

// The unit corner normals of the bottom facets at their top nodes: bottom (#P by 3 or 4, inner
// nodes, outward) and top (B, their copies n_inner + r) -> #top lists of (p[j+1] - p[j]) x
// (p[j-1] - p[j]) at corner j of each bottom facet.
std::vector<std::vector<Eigen::RowVector3d>> layer_corner_normals(const Eigen::MatrixXi& bottom,
                                                                  const Eigen::MatrixXi& top,
                                                                  long n_inner, long n_top,
                                                                  const Eigen::MatrixXd& V) {
  std::vector<std::vector<Eigen::RowVector3d>> out(static_cast<size_t>(n_top));
  const long k = bottom.cols();
  for (long q = 0; q < bottom.rows(); ++q)
    for (long j = 0; j < k; ++j) {
      const Eigen::RowVector3d p = V.row(bottom(q, j));
      const Eigen::RowVector3d u = V.row(bottom(q, (j + 1) % k)) - p,
                               v = V.row(bottom(q, (j + k - 1) % k)) - p;
      const Eigen::RowVector3d n = u.cross(v);
      if (n.norm() > 0)
        out[size_t(top(q, j) - n_inner)].push_back(n.normalized());
    }
  return out;
}

// Flags the layer nodes n_inner + r (in[r], #n_top) of the folded elements (folded_elements).
// Returns whether there is one.
bool folded_layer_nodes(const Eigen::MatrixXi& C, const Eigen::MatrixXd& V, long n_inner,
                        long n_top, int threads, std::vector<char>& in) {
  const std::vector<char> folded = folded_elements(V, C, threads);
  in.assign(size_t(n_top), 0);
  bool any = false;
  for (long e = 0; e < C.rows(); ++e)
    if (folded[size_t(e)])
      for (long j = 0; j < C.cols(); ++j)
        if (C(e, j) >= n_inner)
          in[size_t(C(e, j) - n_inner)] = 1, any = true;
  return any;
}

// Each round halves, for every node n_inner + r of a folded element, the fraction s[r] of the way
// from its inner node below[r] (the other end of its layer element's edge) to target[r]; at most
// kHoldHalvings rounds (a layer element h / 1024 high folds only where its edge directions or its
// inner face do).
void halve_while_folded(const Eigen::MatrixXi& C, const std::vector<int>& below, long n_inner,
                        const Eigen::MatrixXd& target, int threads, std::vector<double>& s,
                        Eigen::MatrixXd& V) {
  constexpr int kHoldHalvings = 10;
  const long n_top = long(below.size());
  std::vector<char> pull;
  for (int round = 0; round < kHoldHalvings; ++round) {
    if (!folded_layer_nodes(C, V, n_inner, n_top, threads, pull))
      return;
    for (long r = 0; r < n_top; ++r)
      if (pull[size_t(r)]) {
        s[size_t(r)] *= 0.5;
        const Eigen::RowVector3d from = V.row(below[size_t(r)]);
        V.row(n_inner + r) = from + s[size_t(r)] * (target.row(r) - from);
      }
  }
}

// The projected layer's nodes n_inner + r of folded elements go back towards their inner nodes
// below[r] (halve_while_folded): where the projection crossed over (walls a few cells thin, parts
// touching) the layer elements overlap; held short, they do not. Elements still folded then have a
// top node whose way to F = 0 runs below one of its bottom faces (a smoothed normal at a
// staircase corner): such nodes get a direction above all their bottom faces (direction_above),
// the same length (at least h / 2), and are held again (at most kAimRounds times). Returns the
// nodes held short of F = 0 (flagged in held).
long hold_folded_layer(const Eigen::MatrixXi& C, const ProjectedLayer& layer, double h, int threads,
                       Eigen::MatrixXd& V, std::vector<char>& held) {
  const std::vector<int>& below = layer.below;
  const long n_inner = layer.n_inner, n_top = long(below.size());
  Eigen::MatrixXd target = V.bottomRows(n_top);
  std::vector<double> s(size_t(n_top), 1);
  halve_while_folded(C, below, n_inner, target, threads, s, V);
  constexpr int kAimRounds = 3; // re-aiming one node can fold an element of a neighbour
  const auto normals = layer_corner_normals(layer.bottom, layer.top, n_inner, n_top, V);
  std::vector<char> aimed(size_t(n_top), 0);
  std::vector<char> redo;
  for (int round = 0; round < kAimRounds; ++round) {
    if (!folded_layer_nodes(C, V, n_inner, n_top, threads, redo))
      break;
    for (long r = 0; r < n_top; ++r) {
      if (!redo[size_t(r)] || normals[size_t(r)].empty())
        continue;
      Eigen::MatrixXd N(long(normals[size_t(r)].size()), 3);
      for (long k = 0; k < N.rows(); ++k)
        N.row(k) = normals[size_t(r)][size_t(k)];
      const Eigen::RowVector3d from = V.row(below[size_t(r)]);
      const double length = std::max((target.row(r) - from).norm(), h / 2);
      target.row(r) = from + length * direction_above(N);
      s[size_t(r)] = 1;
      aimed[size_t(r)] = 1;
      V.row(n_inner + r) = target.row(r);
    }
    halve_while_folded(C, below, n_inner, target, threads, s, V);
  }
  held.assign(size_t(V.rows()), 0);
  long count = 0;
  for (long r = 0; r < n_top; ++r)
    if (s[size_t(r)] < 1 || aimed[size_t(r)])
      held[size_t(n_inner + r)] = 1, ++count;
  return count;
}

// The boundary nodes on F = 0: not flagged in `skip` (empty: none) and |F| <= kOnZero h |grad F|
// (the gradient exact when f has one, else by central differences with step 1e-4 h). Nodes the
// mesh leaves on the box faces where the body reaches the box are not. Sets max_f, the largest |F|
// over them (0 when there is none).
long boundary_on_zero(const ImplicitFunction& f, double h, const VolumeMesh& vm,
                      const std::vector<char>& skip, int threads, double& max_f) {
  constexpr double kOnZero = 1e-6; // the roots are found to 1e-10 of a bracket within a cell
  std::vector<long> nodes;
  for (size_t v = 0; v < vm.boundary.size(); ++v)
    if (vm.boundary[v] && (skip.empty() || !skip[v]))
      nodes.push_back(long(v));
  Points3 P(long(nodes.size()), 3);
  for (size_t r = 0; r < nodes.size(); ++r)
    P.row(long(r)) = vm.V.row(nodes[r]);
  Eigen::VectorXd F;
  Points3 G;
  values_and_gradients(f, P, 1e-4 * h, threads, F, G);
  long on = 0;
  max_f = 0;
  for (long r = 0; r < P.rows(); ++r)
    if (std::abs(F(r)) <= kOnZero * h * G.row(r).norm() || F(r) == 0)
      ++on, max_f = std::max(max_f, std::abs(F(r)));
  return on;
}

// The interior smoothing's guard (VolumeSmoothingOptions::keep): no move makes a corner whose
// scaled Jacobian is below it poorer. Without it the smoothing walked small elements' corners flat
// (default hexahedra, smallest scaled Jacobian: the UAV at cell 0.06 7e-16 with 179 elements
// below 1e-6, the impeller at 0.25 8e-14 with 30; at resolution 24 car 6e-13, impeller 9e-15, UAV
// 1e-12, valve 1e-14). With 0.02: 0.0012 and 0.0054 with none below 1e-6, at 24 0.019, 0.0059,
// 0.019, 0.0099; means within 2 %, volumes the same. 0.05 to 0.2 lift the minima further (the
// impeller at 0.25: 0.004 to 0.063) but cost coarse meshes up to 20 % of their mean, and each left
// folds that the unguarded smoothing had opened: a pillow folded at its centre (valve, cell 0.2,
// 0.1 and 0.2) or children the refinement could not untangle (impeller, cell 0.5, 0.05 and 0.2)
// (docs/benchmarks.md, "Flat corners").
constexpr double kKeptScaledJacobian = 0.02;

// Step (4) of volume_mesh on any mesh whose boundary nodes lie on F = 0: functional (12) over the
// boundary surface, then (15) over the interior, guarded by kKeptScaledJacobian. Before the
// interior moves, a projected layer's nodes of folded elements are held short of F = 0
// (hold_folded_layer), and interior moves that fold an element are undone; a cut boundary has no
// folds (its nodes stay on their grid edges). Sets held and the largest |F| at a boundary node not
// held. Dual hexahedra pass the nodes they held (`held`, #V) and are treated like a projected layer
// otherwise.
void smooth_and_hold(const ImplicitFunction& f, double h, const VolumeMeshOptions& o,
                     const ProjectedLayer* layer, VolumeMesh& vm, VolumeMeshInfo& out,
                     std::vector<char> held = {}) {
  const bool projected = layer != nullptr || !held.empty();
  auto say = [&](const std::string& m) {
    if (o.progress)
      o.progress(m);
  };
  std::vector<int> row(vm.boundary.size(), -1);
  std::vector<long> nodes;
  for (size_t v = 0; v < vm.boundary.size(); ++v)
    if (vm.boundary[v])
      row[v] = int(nodes.size()), nodes.push_back(long(v));
  if (o.surface_sweeps > 0) {
    say("smoothing the boundary surface, " + std::to_string(o.surface_sweeps) +
        " sweeps (functional 12)");
    Eigen::MatrixXd Vb(long(nodes.size()), 3);
    for (size_t r = 0; r < nodes.size(); ++r)
      Vb.row(long(r)) = vm.V.row(nodes[r]);
    Eigen::MatrixXi Fb = vm.B;
    for (long i = 0; i < Fb.size(); ++i)
      Fb.data()[i] = row[size_t(Fb.data()[i])];
    if (Fb.cols() == 4)
      Fb = triangulate_quads(Vb, Fb);
    SurfaceSmoothingOptions so;
    so.iterations = o.surface_sweeps;
    so.threads = o.threads;
    smooth_on_surface(f, Vb, Fb, so);
    const Eigen::MatrixXd before = vm.V;
    for (size_t r = 0; r < nodes.size(); ++r)
      vm.V.row(nodes[r]) = Vb.row(long(r));
    if (layer == nullptr) // the projected layer's folds are held below
      detail::restore_folded(before, vm.boundary, vm.C, o.threads, vm.V);
  }
  if (layer != nullptr) // a valid mesh before the interior moves
    out.held = hold_folded_layer(vm.C, *layer, h, o.threads, vm.V, held);
  if (interior_sweeps_of(o) > 0) {
    say("smoothing the interior, " + std::to_string(interior_sweeps_of(o)) +
        " sweeps (functional 15)");
    VolumeSmoothingOptions so;
    so.sweeps = interior_sweeps_of(o);
    so.threads = o.threads;
    so.keep = kKeptScaledJacobian;
    const Eigen::MatrixXd before = vm.V;
    out.smoothing = smooth_volume(vm.V, vm.C, vm.boundary, so);
    if (projected) { // moves beside a layer element h / 1024 high may fold it: those go back
      std::vector<char> interior(vm.boundary.size());
      std::transform(vm.boundary.begin(), vm.boundary.end(), interior.begin(),
                     [](char b) { return char(!b); });
      detail::restore_folded(before, interior, vm.C, o.threads, vm.V);
    }
  }
  out.on_zero = boundary_on_zero(f, h, vm, held, o.threads, out.max_boundary_f);
}

// vm.B, the element facets used once (facet_corners columns when there are no elements; on
// `threads` threads), and vm.boundary, which nodes lie on them.
void mark_boundary(VolumeMesh& vm, int facet_corners, int threads) {
  vm.B = vm.C.rows() > 0 ? boundary_facets(vm.C, threads) : Eigen::MatrixXi(0, facet_corners);
  vm.boundary.assign(size_t(vm.V.rows()), 0);
  for (long i = 0; i < vm.B.size(); ++i)
    vm.boundary[size_t(vm.B.data()[i])] = 1;
}

// F at the nodes of g (node order of RegularGrid), with the progress line; out.clipped counts the
// outer nodes where the body reaches the box (the mesh is cut there, as the surface mesher's).
Eigen::VectorXd sampled_grid(const ImplicitFunction& f, const RegularGrid& g,
                             const VolumeMeshOptions& o, VolumeMeshInfo& out) {
  if (o.progress)
    o.progress("grid " + std::to_string(g.nodes(0)) + " x " + std::to_string(g.nodes(1)) + " x " +
               std::to_string(g.nodes(2)) + " nodes, sampling F");
  Eigen::VectorXd S;
  sample_grid(f, g, S, o.threads);
  out.clipped = nodes_reaching_box(g, S);
  return S;
}

// The part of the body (the grid clipped at F = 0, zero sheets filled in `whole`) that no element
// of vm covers, and the cell that would keep the loss within kLostVolumeWarning.
void measure_coverage(const ImplicitFunction& f, const RegularGrid& g, const Eigen::VectorXd& whole,
                      const VolumeMeshOptions& o, const VolumeMesh& vm, double cells_across_wall,
                      VolumeMeshInfo& out) {
  if (o.progress)
    o.progress("measuring the volume the mesh leaves out (the grid clipped at F = 0)");
  const CutTetrahedra body = cut_tetrahedra(f, g, whole, o.epsilon, o.threads);
  out.coverage = uncovered_volume(body, g, vm.V, vm.C, o.threads);
  // Dual and pillowed hexahedra: the mean lost thickness (their walls and slivers differ from the
  // layer's), and no coarser than the cell at which a second-order loss (slivers under held
  // points, creases; volume orders 1.9-2.3) falls to the warning's level, with 10 % to spare.
  const double h = g.spacing.minCoeff(), lost = out.lost_fraction();
  out.suggested_cell = cells_across_wall == kCellsAcrossDualWall
                           ? std::min(out.coverage.thickness() / kCellsAcrossDualWall,
                                      lost > 0 ? 0.9 * h * std::sqrt(kLostVolumeWarning / lost) : h)
                           : cell_keeping(out.coverage, h, kLostVolumeWarning * out.coverage.body,
                                          kCellsAcrossWall, kKeptWallCells);
}

// The grid g0 padded by a layer of cells around the box (every inside node gets its 8 cells) into
// g, sampled, with nodes on internal zero sheets inside (dual and pillowed hexahedra).
Eigen::VectorXd padded_samples(const ImplicitFunction& f, const RegularGrid& g0,
                               const VolumeMeshOptions& o, VolumeMeshInfo& out, RegularGrid& g) {
  g = g0;
  g.origin -= g.spacing;
  g.nodes += 2;
  out.grid = g;
  Eigen::VectorXd S = sampled_grid(f, g, o, out);
  fill_zero_sheets(g, S, o.epsilon, o.threads);
  out.inside_nodes = (S.array() > o.epsilon).count();
  return S;
}

// The tetrahedral mesh of the lattice's tetrahedra clipped at F = 0 (cut_tetrahedra) on g (Kuhn)
// or on g padded by a cell (BCC, whose tetrahedra then cover g's box; its cube centres sampled
// after the nodes), nodes on internal zero sheets inside (of either grid); the boundary is the
// facets used once; then step (4) of volume_mesh with the boundary fixed.
VolumeMesh cut_mesh(const ImplicitFunction& f, const RegularGrid& g0, const VolumeMeshOptions& o,
                    VolumeMeshInfo& out) {
  RegularGrid g = g0;
  Eigen::VectorXd S;
  if (o.lattice == Lattice::bcc) {
    S = padded_samples(f, g0, o, out, g);
    const RegularGrid c = cube_centres(g);
    if (o.progress)
      o.progress("cube centres, sampling F (BCC lattice)");
    Eigen::VectorXd Sc;
    sample_grid(f, c, Sc, o.threads);
    fill_zero_sheets(c, Sc, o.epsilon, o.threads);
    S.conservativeResize(g.size() + c.size());
    S.tail(c.size()) = Sc;
  } else {
    S = sampled_grid(f, g, o, out);
    fill_zero_sheets(g, S, o.epsilon, o.threads);
  }
  out.inside_nodes = (S.array() > o.epsilon).count();
  if (o.progress)
    o.progress(std::string("cutting the ") + lattice_name(o.lattice) +
               " lattice's tetrahedra at F = 0");
  CutTetrahedra cut = cut_tetrahedra(f, g, S, o.epsilon, o.threads, o.lattice);
  VolumeMesh vm;
  vm.V = std::move(cut.V);
  vm.C = std::move(cut.C);
  out.inner_cells = cut.whole;
  out.layer_elements = vm.C.rows() - cut.whole;
  mark_boundary(vm, 3, o.threads);
  if (vm.C.rows() > 0)
    smooth_and_hold(f, g.spacing.minCoeff(), o, nullptr, vm, out);
  return vm;
}

// Hexahedra dual to the inside nodes of g padded by a cell (dual_hexahedra), nodes on internal zero
// sheets inside; then step (4) of volume_mesh with the held points fixed and the coverage.
VolumeMesh dual_mesh(const ImplicitFunction& f, const RegularGrid& g0, const VolumeMeshOptions& o,
                     VolumeMeshInfo& out) {
  RegularGrid g;
  const Eigen::VectorXd S = padded_samples(f, g0, o, out, g);
  if (o.progress)
    o.progress("hexahedra dual to " + std::to_string(out.inside_nodes) + " inside nodes");
  DualHexahedra d = dual_hexahedra(f, g, S, o.epsilon, o.threads);
  VolumeMesh vm;
  vm.V = std::move(d.V);
  vm.C = std::move(d.C);
  out.unprojected = d.unprojected;
  mark_boundary(vm, 4, o.threads);
  for (long e = 0; e < vm.C.rows(); ++e) {
    bool layer = false;
    for (int j = 0; j < 8; ++j)
      layer = layer || d.boundary[size_t(vm.C(e, j))];
    ++(layer ? out.layer_elements : out.inner_cells);
  }
  if (vm.C.rows() > 0) {
    smooth_and_hold(f, g.spacing.minCoeff(), o, nullptr, vm, out, d.held);
    out.held = d.held_points;
  }
  measure_coverage(f, g, S, o, vm, kCellsAcrossDualWall, out);
  return vm;
}

// The nodes of the poor elements (a corner scaled Jacobian <= tau; tau = 0: inverted) and of their
// neighbours (sharing a node); `poor` is set to their number.
std::vector<char> near_poor(const Eigen::MatrixXi& C, const Eigen::MatrixXd& V, double tau,
                            int threads, long& poor) {
  const Eigen::MatrixXi T = corner_table(8);
  const std::vector<char> poor_element = element_flags(C.rows(), threads, [&](long e) {
    Eigen::Vector3d p[8];
    for (int j = 0; j < 8; ++j)
      p[j] = V.row(C(e, j)).transpose();
    const detail::CornerJacobian cj = detail::corner_scaled_jacobian(p, T);
    return cj.inverted || !(cj.min_scaled > tau);
  });
  std::vector<char> bad(size_t(V.rows()), 0), near(size_t(V.rows()), 0);
  poor = 0;
  for (long e = 0; e < C.rows(); ++e) {
    if (!poor_element[size_t(e)])
      continue;
    ++poor;
    for (long j = 0; j < C.cols(); ++j)
      bad[size_t(C(e, j))] = 1;
  }
  for (long e = 0; e < C.rows(); ++e) {
    bool touches = false;
    for (long j = 0; j < C.cols() && !touches; ++j)
      touches = bad[size_t(C(e, j))];
    if (touches)
      for (long j = 0; j < C.cols(); ++j)
        near[size_t(C(e, j))] = 1;
  }
  return near;
}

// Rounds of untangling the nodes near poor elements (tau as for near_poor): functional (15) with a
// sharp exponent
// t = kSharpness / mean |alpha|, whose log-sum-exp is then nearly -t min alpha (the local max-min
// untangling of Freitag & Plassmann 2000, "Local optimization-based simplicial mesh untangling and
// improvement", through the seed's functional), over the nodes not flagged in `fixed_always`
// (sweeps of smooth_volume), and the nodes flagged in `slides` of poor elements sliding on F = 0
// under the same functional (slide_boundary_nodes; none when surface is null). Stops when no
// element is poor or after kRounds rounds (kStall without progress). The functional grows with an
// element's size, so a node of elements that stay folded can run off (a tube whose wall is 0.6
// cells: pillow nodes 300 cells out of the box, and the coverage's buckets then filled memory);
// nodes moved more than kRunaway mean edges beyond the box of the nodes' start go back, their
// elements staying folded. Returns the elements still poor.
long untangle_rounds(const Eigen::MatrixXi& C, const std::vector<char>& fixed_always,
                     const SlidingSurface* surface, const std::vector<char>& slides, double tau,
                     int threads, Eigen::MatrixXd& V) {
  constexpr int kRounds = 30, kStall = 3;
  constexpr double kSharpness = 30; // exp(-30) between the mean corner and a flat one
  constexpr double kRunaway = 16;
  Eigen::MatrixXd start; // V before the first move
  long poor = 0, best = -1;
  int stalled = 0;
  for (int round = 0; round < kRounds; ++round) {
    std::vector<char> fixed = near_poor(C, V, tau, threads, poor);
    if (poor == 0 || (best >= 0 && poor >= best && ++stalled >= kStall))
      break;
    if (best < 0)
      start = V;
    best = best < 0 ? poor : std::min(best, poor);
    for (size_t v = 0; v < fixed.size(); ++v)
      fixed[v] = fixed[v] && !fixed_always[v]; // now: the nodes that move
    VolumeSmoothingOptions so;
    so.sweeps = 4;
    so.threads = threads;
    so.t = kSharpness / corner_alphas(V, C, threads).cwiseAbs().mean();
    // Smoothed on the elements at the moving nodes only: a few among many (a refined mesh).
    const detail::SubMesh sub = detail::elements_at(C, fixed);
    Eigen::MatrixXd W = V(sub.node, Eigen::all);
    std::vector<char> stays(sub.node.size());
    for (size_t k = 0; k < stays.size(); ++k)
      stays[k] = !fixed[size_t(sub.node[k])];
    smooth_volume(W, sub.C, stays, so);
    V(sub.node, Eigen::all) = W;
    if (surface != nullptr)
      slide_boundary_nodes(V, C, slides, *surface, so.t, kSlideFlat, threads);
  }
  if (best >= 0 && V.rows() > 0) {
    const double far = kRunaway * detail::mean_edge(start, C);
    const Eigen::RowVector3d lo = start.colwise().minCoeff().array() - far,
                             hi = start.colwise().maxCoeff().array() + far;
    for (long v = 0; v < V.rows(); ++v)
      if (!((V.row(v).array() >= lo.array()).all() && (V.row(v).array() <= hi.array()).all()))
        V.row(v) = start.row(v);
  }
  near_poor(C, V, tau, threads, poor);
  return poor;
}

// Pillows with a corner scaled Jacobian below this are improved after the untangling (the same
// rounds): ellipsoid (1, 0.6, 0.35) at h = 0.07 min 4e-12 -> 0.30; the models' inverted counts
// unchanged (docs/benchmarks.md, pillowed hexahedra).
constexpr double kPoorPillow = 0.1;

// The pillow layer folds where the surface points of neighbouring cells crowd at a sharp edge or
// a concave crease: untangle_rounds with the core points free and the surface points sliding on
// F = 0 (those whose projection failed stay), first on the inverted elements, then on those below
// kPoorPillow. Returns the elements still inverted after the first.
long untangle_pillows(const ImplicitFunction& f, double h, const std::vector<char>& missed,
                      VolumeMesh& vm, int threads) {
  const SlidingSurface surface = detail::implicit_surface(f, h, threads);
  std::vector<char> slides(vm.boundary.size());
  for (size_t v = 0; v < slides.size(); ++v)
    slides[v] = vm.boundary[v] && !missed[v];
  const long inverted = untangle_rounds(vm.C, vm.boundary, &surface, slides, 0, threads, vm.V);
  untangle_rounds(vm.C, vm.boundary, &surface, slides, kPoorPillow, threads, vm.V);
  return inverted;
}

// The pillow layer as a projected layer (its surface points copies of the core points below them:
// a pillow's corner j + 4 stands on its corner j), so that its folds are held like that layer's.
ProjectedLayer pillow_layer(const PillowedHexahedra& p) {
  ProjectedLayer layer;
  const long points = long(std::count(p.boundary.begin(), p.boundary.end(), char(1)));
  layer.n_inner = long(p.boundary.size()) - points;
  layer.below.assign(size_t(points), -1);
  const long pillows = p.C.rows() - p.core;
  layer.bottom = p.C.block(p.core, 0, pillows, 4);
  layer.top = p.C.block(p.core, 4, pillows, 4);
  for (long q = 0; q < pillows; ++q)
    for (int j = 0; j < 4; ++j)
      layer.below[size_t(layer.top(q, j) - layer.n_inner)] = layer.bottom(q, j);
  return layer;
}

// Dual hexahedra with a pillow layer (pillowed_hexahedra) on g padded by a cell, nodes on internal
// zero sheets inside; the core points smoothed by functional (15), the folds untangled
// (untangle_pillows: core points free, surface points sliding on F = 0), step (4) of volume_mesh
// with the unprojected points held and the surface points of pillows still folded held short of
// F = 0 like a projected layer's (hold_folded_layer on pillow_layer), then the coverage.
VolumeMesh pillow_mesh(const ImplicitFunction& f, const RegularGrid& g0, const VolumeMeshOptions& o,
                       VolumeMeshInfo& out) {
  RegularGrid g;
  const Eigen::VectorXd S = padded_samples(f, g0, o, out, g);
  if (o.progress)
    o.progress("dual hexahedra of " + std::to_string(out.inside_nodes) +
               " inside nodes and their pillow layer");
  PillowedHexahedra p = pillowed_hexahedra(f, g, S, o.epsilon, o.threads);
  const ProjectedLayer layer = pillow_layer(p);
  VolumeMesh vm;
  vm.V = std::move(p.V);
  vm.C = std::move(p.C);
  vm.boundary = p.boundary;
  vm.B = vm.C.rows() > 0 ? boundary_facets(vm.C, o.threads) : Eigen::MatrixXi(0, 4);
  out.unprojected = std::count(p.missed.begin(), p.missed.end(), char(1));
  out.inner_cells = p.core;
  out.layer_elements = vm.C.rows() - p.core;
  out.dropped_nodes = p.trimmed;
  if (vm.C.rows() > 0) {
    if (o.progress)
      o.progress("untangling the pillow layer");
    VolumeSmoothingOptions so; // the core points spread first: fewer folds to untangle
    so.sweeps = interior_sweeps_of(o);
    so.threads = o.threads;
    smooth_volume(vm.V, vm.C, vm.boundary, so);
    untangle_pillows(f, g.spacing.minCoeff(), p.missed, vm, o.threads);
    smooth_and_hold(f, g.spacing.minCoeff(), o, &layer, vm, out, p.missed);
  }
  measure_coverage(f, g, S, o, vm, kCellsAcrossDualWall, out);
  return vm;
}

// The pillows' count of elements folded at a corner or at the centre (folded_elements).
long folded_count(const VolumeMesh& vm, int threads) {
  const std::vector<char> flags = folded_elements(vm.V, vm.C, threads);
  return std::count(flags.begin(), flags.end(), char(1));
}

// g offset by `fraction` of a cell towards -x, -y and -z, with a node more along each axis: the
// same box covered, no node on one of g's node planes. A model's internal zero sheets (F = 0
// inside the solid where R-function parts share a face: the valve's flange and neck at z = 3.5)
// that lie on g's node planes put pillow surface points inside the solid, and the pillows there
// fold; off the planes they do not. Thin walls met by other node planes fold other pillows.
RegularGrid offset_grid(const RegularGrid& g, double fraction) {
  RegularGrid h = g;
  h.origin -= fraction * g.spacing;
  h.nodes += 1;
  return h;
}

// The default hexahedra: pillowed (every boundary node on F = 0 but the few held, the volume of
// walls down to a node layer); where a pillow stays folded at a corner or at its centre (a scaled
// Jacobian <= 0: the trilinear map folds inside though every corner is convex; the impeller at 24
// cells, the UAV at 0.045), pillowed on the grid offset by half a cell (the valve at 0.1: 81
// folded on the grid, none offset), then by a quarter (the UAV at 0.1: 2 folded on the grid,
// walls lost at a half, none folded at a quarter); where those fold too or lose walls, dual on
// the grid (its points are held until every corner's scaled Jacobian is 0.2).
VolumeMesh default_hexahedra(const ImplicitFunction& f, const RegularGrid& g,
                             const VolumeMeshOptions& o, VolumeMeshInfo& out) {
  constexpr double kOffsets[] = {0.5, 0.25}; // fractions of a cell
  VolumeMesh vm = pillow_mesh(f, g, o, out);
  out.boundary = VolumeBoundary::pillow;
  const long folded = folded_count(vm, o.threads);
  if (folded == 0)
    return vm;
  for (double offset : kOffsets) {
    if (o.progress)
      o.progress(std::to_string(folded) + " pillows stayed folded: pillows on the grid offset by " +
                 (offset == 0.5 ? "half" : "a quarter of") + " a cell");
    VolumeMeshInfo moved;
    VolumeMesh vo = pillow_mesh(f, offset_grid(g, offset), o, moved);
    // Kept unless the offset grid misses walls the grid holds (the UAV at 0.1 offset by half a
    // cell: its body clipped at F = 0 4.6 % smaller).
    const bool walls_kept = moved.coverage.body >= (1 - kLostVolumeWarning) * out.coverage.body;
    if (walls_kept && folded_count(vo, o.threads) == 0) {
      out = moved;
      out.boundary = VolumeBoundary::pillow;
      out.folded_pillows = folded;
      out.offset_grid = offset;
      return vo;
    }
  }
  if (o.progress)
    o.progress("pillows folded there too, or walls lost: dual hexahedra instead");
  out = VolumeMeshInfo{};
  out.boundary = VolumeBoundary::dual;
  out.folded_pillows = folded;
  return dual_mesh(f, g, o, out);
}

} // namespace

long detail::untangle_hexahedra(const Eigen::MatrixXi& C, const std::vector<char>& fixed,
                                int threads, Eigen::MatrixXd& V) {
  return untangle_rounds(C, fixed, nullptr, {}, 0, threads, V);
}

long detail::untangle_hexahedra(const Eigen::MatrixXi& C, const std::vector<char>& fixed,
                                const SlidingSurface& surface, const std::vector<char>& slides,
                                int threads, Eigen::MatrixXd& V) {
  return untangle_rounds(C, fixed, &surface, slides, 0, threads, V);
}

detail::SubMesh detail::elements_at(const Eigen::MatrixXi& C, const std::vector<char>& at) {
  std::vector<long> kept;
  for (long e = 0; e < C.rows(); ++e)
    for (long j = 0; j < C.cols(); ++j)
      if (at[size_t(C(e, j))]) {
        kept.push_back(e);
        break;
      }
  std::vector<long> local(at.size(), -1);
  SubMesh sub;
  for (long e : kept)
    for (long j = 0; j < C.cols(); ++j)
      local[size_t(C(e, j))] = 0;
  for (size_t v = 0; v < local.size(); ++v)
    if (local[v] == 0)
      local[v] = long(sub.node.size()), sub.node.push_back(long(v));
  sub.C.resize(long(kept.size()), C.cols());
  for (size_t r = 0; r < kept.size(); ++r)
    for (long j = 0; j < C.cols(); ++j)
      sub.C(long(r), j) = int(local[size_t(C(kept[r], j))]);
  return sub;
}

long detail::restore_folded(const Eigen::MatrixXd& before, const std::vector<char>& movable,
                            const Eigen::MatrixXi& C, int threads, Eigen::MatrixXd& V) {
  long restored = 0;
  for (;;) {
    const std::vector<char> folded = folded_elements(V, C, threads);
    long moved = 0;
    for (long e = 0; e < C.rows(); ++e) {
      if (!folded[size_t(e)])
        continue;
      for (long j = 0; j < C.cols(); ++j) {
        const int v = C(e, j);
        if (movable[size_t(v)] && V.row(v) != before.row(v))
          V.row(v) = before.row(v), ++moved;
      }
    }
    restored += moved;
    if (moved == 0)
      return restored;
  }
}

SlidingSurface detail::implicit_surface(const ImplicitFunction& f, double h, int threads) {
  SlidingSurface s;
  s.normals = [f, h, threads](const Eigen::MatrixXd& P) {
    return outward_directions(f, P, 1e-3 * h, threads);
  };
  s.project = [f, h, threads](Eigen::MatrixXd& P) {
    std::vector<char> ok;
    RootOptions ro;
    ro.threads = threads;
    project_by_gradient_walk(f, P, Eigen::VectorXd::Constant(P.rows(), h / 4), 100, ro, &ok);
    return ok;
  };
  return s;
}

Eigen::MatrixXi boundary_facets(const Eigen::MatrixXi& C, int threads) {
  if (C.cols() != 4 && C.cols() != 8)
    throw std::invalid_argument("boundary_facets: C must be #C by 4 or #C by 8");
  const ElementFacets ef{C};
  const long nf = C.rows() * ef.faces, nv = C.size() > 0 ? long(C.maxCoeff()) + 1 : 0;
  // Facets bucketed by their smallest node, in id order (a counting sort): equal facets share a
  // bucket, and the buckets are matched independently.
  std::vector<long> start(size_t(nv + 1), 0);
  for (long id = 0; id < nf; ++id)
    ++start[size_t(ef.smallest(id) + 1)];
  for (long v = 0; v < nv; ++v)
    start[size_t(v + 1)] += start[size_t(v)];
  std::vector<long> at(static_cast<size_t>(nf)), fill(start.begin(), start.end() - 1);
  for (long id = 0; id < nf; ++id)
    at[size_t(fill[size_t(ef.smallest(id))]++)] = id;
  std::vector<char> once(size_t(nf), 0);
  detail::parallel_chunks(nv, kBatch, threads, [&](long, long v0, long v1) {
    std::vector<std::pair<std::array<int, 4>, long>> bucket;
    for (long v = v0; v < v1; ++v) {
      bucket.clear();
      for (long k = start[size_t(v)]; k < start[size_t(v + 1)]; ++k)
        bucket.emplace_back(ef.key(at[size_t(k)]), at[size_t(k)]);
      ef.mark_once(bucket, once);
    }
  });
  Eigen::MatrixXi B(long(std::count(once.begin(), once.end(), char(1))), ef.per);
  for (long id = 0, r = 0; id < nf; ++id)
    if (once[size_t(id)]) {
      for (int j = 0; j < ef.per; ++j)
        B(r, j) = ef.corner(id, j);
      ++r;
    }
  return B;
}

namespace {

// volume_mesh before the flat corners are opened.
VolumeMesh mesh_on_grid(const ImplicitFunction& f, const VolumeMeshOptions& o,
                        VolumeMeshInfo* info) {
  if (!f.value)
    throw std::invalid_argument("volume_mesh: the implicit function has no value");
  if (!(o.margin >= 0 && o.margin < 1))
    throw std::invalid_argument("volume_mesh: margin must be in [0, 1)");
  const Eigen::AlignedBox3d box = o.box.isEmpty() ? f.box : o.box;
  if (box.isEmpty())
    throw std::invalid_argument("volume_mesh: no box (neither given nor the function's)");
  const RegularGrid g =
      o.cell > 0 ? grid_with_cell(box, o.cell) : grid_with_resolution(box, o.resolution);
  auto say = [&](const std::string& m) {
    if (o.progress)
      o.progress(m);
  };
  VolumeMeshInfo local;
  VolumeMeshInfo& out = info ? *info : local;
  out = VolumeMeshInfo{};
  out.grid = g;
  const bool tets = o.elements == VolumeElements::tetrahedra;
  out.boundary = o.boundary;
  if (o.boundary == VolumeBoundary::dual) {
    if (tets)
      throw std::invalid_argument("volume_mesh: the dual boundary makes hexahedra only");
    return dual_mesh(f, g, o, out);
  }
  if (o.boundary == VolumeBoundary::pillow) {
    if (tets)
      throw std::invalid_argument("volume_mesh: the pillow boundary makes hexahedra only");
    return pillow_mesh(f, g, o, out);
  }
  if (!tets && o.boundary == VolumeBoundary::cut)
    return default_hexahedra(f, g, o, out);

  if (tets && o.boundary == VolumeBoundary::cut)
    return cut_mesh(f, g, o, out);
  Eigen::VectorXd S = sampled_grid(f, g, o, out);
  // The body as the clipped grid sees it (zero sheets inside), for the layer's coverage.
  Eigen::VectorXd whole = S;
  fill_zero_sheets(g, whole, o.epsilon, o.threads);
  auto coverage = [&](const VolumeMesh& vm) {
    measure_coverage(f, g, whole, o, vm, kCellsAcrossWall, out);
  };
  BoundaryMeshOptions bo;
  bo.cells = tets ? BackgroundCells::tetrahedra : BackgroundCells::hexahedra;
  bo.rule = o.rule;
  bo.epsilon = o.epsilon;
  bo.threads = o.threads;
  bo.reach = kLayerReach;
  bo.scan_step = 0.25; // features thinner than h / 8 along the normal are below the grid anyway
  if (o.margin > 0)    // not in the seed's configurations: they keep its counts
    S = whole;
  if (o.margin > 0)
    out.dropped_nodes = drop_near_surface(f, g, S, bo, o.margin * g.spacing.minCoeff());
  say("inner cells and boundary facets");
  bo.thin_cleanup = o.margin > 0; // the seed's configurations keep every cell
  BoundaryMesh m = boundary_mesh(g, S, bo);
  out.inside_nodes = m.inside_nodes + out.dropped_nodes;
  out.removed_cells = m.removed + m.thinned;
  out.inner_cells = m.cells;
  if (m.cells == 0) { // nothing inside: empty, with the shapes of a mesh
    VolumeMesh none;
    none.V.resize(0, 3);
    none.C.resize(0, tets ? 4 : 8);
    none.B.resize(0, tets ? 3 : 4);
    coverage(none);
    return none;
  }
  say("projecting " + std::to_string(m.V.rows()) + " boundary nodes onto F = 0");
  project_boundary_nodes(f, g, S, m, bo);
  out.unprojected = m.unprojected;

  // Nodes: the grid nodes of the kept cells (in grid order), then the projected copies of the
  // boundary nodes.
  const Eigen::MatrixXi inner = background_cell_nodes(g, bo.cells, m.kept);
  std::vector<int> used(inner.data(), inner.data() + inner.size());
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  auto index_of = [&](int grid_node) {
    return int(std::lower_bound(used.begin(), used.end(), grid_node) - used.begin());
  };
  const long n_inner = long(used.size()), n_top = m.V.rows();
  VolumeMesh vm;
  vm.V.resize(n_inner + n_top, 3);
  const long nx = g.nodes(0), ny = g.nodes(1);
  for (long r = 0; r < n_inner; ++r) {
    const long n = used[size_t(r)];
    vm.V.row(r) = g.point(n % nx, (n / nx) % ny, n / (nx * ny)).transpose();
  }
  vm.V.bottomRows(n_top) = m.V;
  vm.boundary.assign(size_t(n_inner + n_top), 0);
  std::fill(vm.boundary.begin() + n_inner, vm.boundary.end(), 1);

  // Elements: the inner cells, then the boundary layer.
  const long facets = m.P.rows(), per_facet = tets ? 3 : 1;
  out.layer_elements = facets * per_facet;
  vm.C.resize(inner.rows() + out.layer_elements, tets ? 4 : 8);
  for (long e = 0; e < inner.rows(); ++e)
    for (long j = 0; j < inner.cols(); ++j)
      vm.C(e, j) = index_of(inner(e, j));
  vm.B.resize(facets, m.P.cols());
  ProjectedLayer layer;
  layer.bottom.resize(facets, m.P.cols());
  for (long q = 0; q < facets; ++q) {
    const long row = inner.rows() + q * per_facet;
    int b[4], t[4];
    for (int j = 0; j < int(m.P.cols()); ++j) {
      b[j] = index_of(m.node(m.P(q, j)));
      t[j] = int(n_inner) + m.P(q, j);
      vm.B(q, j) = t[j];
      layer.bottom(q, j) = b[j];
    }
    if (tets) {
      std::array<std::array<int, 4>, 3> three;
      split_prism(b, t, three);
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 4; ++j)
          vm.C(row + k, j) = three[size_t(k)][size_t(j)];
    } else {
      vm.C.row(row) << b[0], b[1], b[2], b[3], t[0], t[1], t[2], t[3];
    }
  }

  layer.n_inner = n_inner;
  layer.top = vm.B;
  layer.below.resize(size_t(n_top));
  for (long r = 0; r < n_top; ++r)
    layer.below[size_t(r)] = index_of(m.node(r));
  smooth_and_hold(f, g.spacing.minCoeff(), o, &layer, vm, out);
  coverage(vm);
  return vm;
}

} // namespace

VolumeMesh volume_mesh(const ImplicitFunction& f, const VolumeMeshOptions& o,
                       VolumeMeshInfo* info) {
  VolumeMesh vm = mesh_on_grid(f, o, info);
  // Hexahedral corners the untangling left flat (2.5e-15 on body (11) at 128 cells), opened on
  // the mesh the default chose: a fold they untangle on the grid must not change that choice.
  if (vm.C.cols() == 8 && vm.C.rows() > 0)
    detail::open_flat_corners(vm.C, vm.boundary, kKeptScaledJacobian, vm.V);
  return vm;
}

} // namespace interlin
