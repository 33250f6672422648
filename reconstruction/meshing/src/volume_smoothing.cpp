// Seed 003, digest §6.4: functionals (13)-(15) for tetrahedra and hexahedra, the local algorithm.
#include "interlin/reconstruction/meshing/volume_smoothing.h"

#include "node_colouring.h"
#include "parallel.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace interlin {

namespace {

// Digest §6.4 tables [R, C confirmed; V on the reference elements].
constexpr int kTetCorners[4][3] = {{1, 2, 3}, {3, 2, 0}, {1, 3, 0}, {0, 2, 1}};
constexpr int kHexCorners[8][3] = {{1, 3, 4}, {5, 2, 0}, {6, 3, 1}, {2, 7, 0},
                                   {5, 0, 7}, {6, 1, 4}, {5, 7, 2}, {6, 4, 3}};

using Vec3 = Eigen::Vector3d;

inline Vec3 row(const Eigen::MatrixXd& V, int i) {
  return {V(i, 0), V(i, 1), V(i, 2)};
}

// alpha_j of element e: ((p_a - p_j) x (p_b - p_j)) . (p_c - p_j), (a, b, c) row j of T.
double corner_alpha(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C, const Eigen::MatrixXi& T,
                    long e, int j) {
  const Vec3 p = row(V, C(e, j));
  const Vec3 u = row(V, C(e, T(j, 0))) - p, v = row(V, C(e, T(j, 1))) - p,
             w = row(V, C(e, T(j, 2))) - p;
  return u.cross(v).dot(w);
}

// A corner term that depends on a node: element, local corner j, and which of (p_j, p_a, p_b,
// p_c) the node is.
struct Involvement {
  int element, corner, role;
};

// The corner terms of node v (the corners of its elements that involve it).
void node_terms(const Eigen::MatrixXi& C, const Eigen::MatrixXi& T, const detail::NodeElements& ne,
                int v, std::vector<Involvement>& out) {
  out.clear();
  for (long k = ne.start[size_t(v)]; k < ne.start[size_t(v) + 1]; ++k) {
    const int e = ne.at[size_t(k)];
    for (int j = 0; j < int(T.rows()); ++j) {
      const int who[4] = {C(e, j), C(e, T(j, 0)), C(e, T(j, 1)), C(e, T(j, 2))};
      for (int r = 0; r < 4; ++r)
        if (who[r] == v)
          out.push_back({e, j, r});
    }
  }
}

// alpha of one corner and its gradient with respect to the vertex in `role`; `lengths`, when
// given, is set to the product of the corner's three edge lengths (alpha / lengths is the corner's
// scaled Jacobian).
double alpha_and_gradient(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C,
                          const Eigen::MatrixXi& T, const Involvement& in, Vec3& grad,
                          double* lengths = nullptr) {
  const Vec3 p0 = row(V, C(in.element, in.corner));
  const Vec3 u = row(V, C(in.element, T(in.corner, 0))) - p0,
             v = row(V, C(in.element, T(in.corner, 1))) - p0,
             w = row(V, C(in.element, T(in.corner, 2))) - p0;
  const Vec3 vw = v.cross(w), wu = w.cross(u), uv = u.cross(v);
  switch (in.role) {
  case 0:
    grad = -(vw + wu + uv);
    break;
  case 1:
    grad = vw;
    break;
  case 2:
    grad = wu;
    break;
  default:
    grad = uv;
  }
  if (lengths)
    *lengths = u.norm() * v.norm() * w.norm();
  return u.dot(vw);
}

// The local functional of one node as a function of its displacement d: every alpha_k is affine
// in the node's position, alpha_k(x0 + d) = a_k + g_k . d, so the terms are set up once per visit.
struct LocalFunctional {
  std::vector<double> a;
  std::vector<Vec3> g;
  std::vector<double> floor; // alpha_k may not fall below floor[k] (empty: no floors)
  double t = 1;

  // log sum_k exp(-t alpha_k(x0 + d)) (log-sum-exp: no overflow for badly inverted corners);
  // with G and H, the gradient and Hessian of the sum divided by its largest term (the Newton
  // step does not depend on that scale), and that scaled sum.
  double operator()(const Vec3& d, Vec3* G = nullptr, Eigen::Matrix3d* H = nullptr,
                    double* scaled_sum = nullptr) const {
    thread_local std::vector<double> e;
    e.resize(a.size());
    double top = -INFINITY;
    for (size_t k = 0; k < a.size(); ++k) {
      e[k] = -t * (a[k] + g[k].dot(d));
      top = std::max(top, e[k]);
    }
    double sum = 0;
    if (G)
      G->setZero();
    if (H)
      H->setZero();
    for (size_t k = 0; k < a.size(); ++k) {
      const double w = std::exp(e[k] - top);
      sum += w;
      if (G)
        *G -= t * w * g[k];
      if (H)
        *H += t * t * w * g[k] * g[k].transpose(); // alpha is affine: no second-order term
    }
    if (scaled_sum)
      *scaled_sum = sum;
    return top + std::log(sum);
  }

  // Corners with alpha <= 0 at displacement d.
  long folded(const Vec3& d) const {
    long n = 0;
    for (size_t k = 0; k < a.size(); ++k)
      n += !(a[k] + g[k].dot(d) > 0);
    return n;
  }

  // Whether every corner keeps its floor at displacement d.
  bool keeps_floors(const Vec3& d) const {
    for (size_t k = 0; k < floor.size(); ++k)
      if (a[k] + g[k].dot(d) < floor[k])
        return false;
    return true;
  }
};

// Newton iterations with backtracking on one node's convex local functional; returns the distance
// the node moved. With keep > 0 a step must also keep each unfolded corner's alpha at least
// min(its alpha at the visit, keep x its edge-length product): a poor corner (scaled Jacobian
// below keep) gets no poorer, a good one no poorer than keep.
double minimise_node(Eigen::MatrixXd& V, const Eigen::MatrixXi& C, const Eigen::MatrixXi& T,
                     const std::vector<Involvement>& terms, double t, double keep, int node,
                     int steps) {
  thread_local LocalFunctional L;
  L.t = t;
  L.a.resize(terms.size());
  L.g.resize(terms.size());
  L.floor.assign(keep > 0 ? terms.size() : 0, -INFINITY); // folded corners: the fold count
  for (size_t k = 0; k < terms.size(); ++k) {
    double lengths = 0;
    L.a[k] = alpha_and_gradient(V, C, T, terms[k], L.g[k], &lengths);
    if (keep > 0 && L.a[k] > 0)
      L.floor[k] = std::min(L.a[k], keep * lengths);
  }
  Vec3 x = Vec3::Zero(), G;
  Eigen::Matrix3d H;
  double sum = 0;
  double E = L(x, &G, &H, &sum);
  for (int it = 0; it < steps; ++it) {
    // A tiny ridge keeps H invertible when all the corner gradients are coplanar.
    const double ridge = 1e-12 * H.trace() + 1e-300;
    const Vec3 d = -(H + ridge * Eigen::Matrix3d::Identity()).ldlt().solve(G);
    // Converged when the Newton decrement (the predicted relative decrease) is below 1e-12.
    if (!d.allFinite() || -0.5 * G.dot(d) < 1e-12 * sum)
      break;
    double s = 1;
    bool accepted = false;
    // exp(-t alpha) barely penalises a corner of an element much smaller than the mean turning
    // over (t alpha ~ 0 either way): a step must not fold more corners than there are.
    const long folded = L.folded(x);
    for (int b = 0; b < 30 && !accepted; ++b, s *= 0.5) {
      const double Ey = L(x + s * d);
      if (Ey < E && L.folded(x + s * d) <= folded && L.keeps_floors(x + s * d)) {
        x += s * d;
        E = Ey;
        accepted = true;
      }
    }
    if (!accepted)
      break;
    L(x, &G, &H, &sum);
  }
  V.row(node) += x.transpose();
  return x.norm();
}

struct EnergyCount {
  double mean = 0; // sum exp(-t alpha) / corners
  long inverted = 0;
};

// Elements per task of the loops over all elements; partial sums are added in task order, so the
// result does not depend on the number of threads.
constexpr long kElementChunk = 8192;

EnergyCount energy(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C, double t, int threads) {
  const long tasks = detail::chunk_count(C.rows(), kElementChunk);
  std::vector<double> sum(size_t(tasks), 0);
  std::vector<long> inverted(size_t(tasks), 0);
  const Eigen::MatrixXi T = corner_table(int(C.cols()));
  detail::parallel_chunks(C.rows(), kElementChunk, threads, [&](long task, long e0, long e1) {
    for (long e = e0; e < e1; ++e) {
      bool bad = false;
      for (int j = 0; j < int(C.cols()); ++j) {
        const double a = corner_alpha(V, C, T, e, j);
        sum[size_t(task)] += std::exp(std::min(-t * a, 700.0));
        bad = bad || !(a > 0);
      }
      inverted[size_t(task)] += bad;
    }
  });
  EnergyCount r;
  double total = 0;
  for (long task = 0; task < tasks; ++task)
    total += sum[size_t(task)], r.inverted += inverted[size_t(task)];
  r.mean = C.size() > 0 ? total / double(C.size()) : 0;
  return r;
}

// Minimises each node's functional L[k] over the surface, all nodes in lock-step (they share no
// element, so their functionals are independent): per round, the normals at the current points in
// one batch and a Newton step per node projected onto its tangent plane, at most `reach` long;
// then backtracking, every pending trial point projected onto the surface in one batch and
// accepted when the projection moved it by less than reach / 4 (not onto another part of the
// surface) and its L decreases. Returns the number of nodes moved.
long slide_nodes(Eigen::MatrixXd& V, const std::vector<int>& nodes,
                 const std::vector<LocalFunctional>& L, const SlidingSurface& surface,
                 double reach) {
  constexpr int kRounds = 5, kHalvings = 12;
  const long n = long(nodes.size());
  std::vector<Vec3> x(size_t(n), Vec3::Zero()), d(static_cast<size_t>(n)),
      G(static_cast<size_t>(n));
  std::vector<Eigen::Matrix3d> H(static_cast<size_t>(n));
  std::vector<double> E(static_cast<size_t>(n)), step(static_cast<size_t>(n));
  std::vector<char> active(size_t(n), 1);
  for (long k = 0; k < n; ++k)
    E[size_t(k)] = L[size_t(k)](x[size_t(k)], &G[size_t(k)], &H[size_t(k)]);
  auto point = [&](long k, const Vec3& dx) { return Vec3(row(V, nodes[size_t(k)]) + dx); };
  for (int round = 0; round < kRounds; ++round) {
    std::vector<long> live;
    for (long k = 0; k < n; ++k)
      if (active[size_t(k)])
        live.push_back(k);
    if (live.empty())
      break;
    Eigen::MatrixXd P(long(live.size()), 3);
    for (size_t r = 0; r < live.size(); ++r)
      P.row(long(r)) = point(live[r], x[size_t(live[r])]).transpose();
    const Eigen::MatrixXd N = surface.normals(P);
    std::vector<long> pending;
    for (size_t r = 0; r < live.size(); ++r) {
      const long k = live[r];
      const Vec3 nk = N.row(long(r)).transpose();
      const double ridge = 1e-12 * H[size_t(k)].trace() + 1e-300;
      Vec3 dk = -(H[size_t(k)] + ridge * Eigen::Matrix3d::Identity()).ldlt().solve(G[size_t(k)]);
      dk -= dk.dot(nk) * nk;
      if (dk.norm() > reach)
        dk *= reach / dk.norm();
      active[size_t(k)] = nk.norm() > 0 && dk.allFinite() && dk.norm() > 0;
      if (active[size_t(k)]) {
        d[size_t(k)] = dk;
        step[size_t(k)] = 1;
        pending.push_back(k);
      }
    }
    for (int b = 0; b < kHalvings && !pending.empty(); ++b) {
      Eigen::MatrixXd Q(long(pending.size()), 3);
      for (size_t r = 0; r < pending.size(); ++r) {
        const long k = pending[r];
        Q.row(long(r)) = point(k, x[size_t(k)] + step[size_t(k)] * d[size_t(k)]).transpose();
      }
      const Eigen::MatrixXd trial = Q;
      const std::vector<char> ok = surface.project(Q);
      std::vector<long> still;
      for (size_t r = 0; r < pending.size(); ++r) {
        const long k = pending[r];
        const Vec3 y = Q.row(long(r)).transpose() - row(V, nodes[size_t(k)]);
        const bool near = (Q.row(long(r)) - trial.row(long(r))).norm() < 0.25 * reach;
        const double Ey = ok[r] && near ? L[size_t(k)](y) : INFINITY;
        if (Ey < E[size_t(k)]) {
          x[size_t(k)] = y;
          E[size_t(k)] = L[size_t(k)](y, &G[size_t(k)], &H[size_t(k)]);
        } else {
          step[size_t(k)] *= 0.5;
          still.push_back(k);
        }
      }
      pending.swap(still);
    }
    for (long k : pending) // no decrease along this direction: done
      active[size_t(k)] = 0;
  }
  long moved = 0;
  for (long k = 0; k < n; ++k)
    if (x[size_t(k)].norm() > 0) {
      V.row(nodes[size_t(k)]) += x[size_t(k)].transpose();
      ++moved;
    }
  return moved;
}

// Corner alpha of facet corners in the tangent planes: alpha(f, j) for corner j of facet f.
Eigen::MatrixXd surface_alphas(const Eigen::MatrixXd& V, const Eigen::MatrixXi& B,
                               const Eigen::MatrixXd& N) {
  const int k = int(B.cols());
  Eigen::MatrixXd A(B.rows(), k);
  for (long f = 0; f < B.rows(); ++f)
    for (int j = 0; j < k; ++j) {
      const Vec3 p = row(V, B(f, j));
      const Vec3 u = row(V, B(f, (j + 1) % k)) - p, w = row(V, B(f, (j + k - 1) % k)) - p;
      A(f, j) = u.cross(w).dot(row(N, B(f, j)));
    }
  return A;
}

} // namespace

long untangle_surface(Eigen::MatrixXd& V, const Eigen::MatrixXi& B, const SlidingSurface& surface,
                      double flat, int rounds) {
  if (!surface.normals || !surface.project || !(flat >= 0) || (B.cols() != 3 && B.cols() != 4))
    throw std::invalid_argument("untangle_surface: B #B by 3 or 4, a surface, flat >= 0");
  if (B.size() > 0 && (B.minCoeff() < 0 || B.maxCoeff() >= V.rows()))
    throw std::invalid_argument("untangle_surface: facet index out of range");
  const int k = int(B.cols());
  const detail::NodeElements nf(B, V.rows());
  // Normals at the facets' nodes, in one batch.
  std::vector<int> nodes(B.data(), B.data() + B.size());
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(V.rows(), 3);
  auto normals = [&] {
    Eigen::MatrixXd P(long(nodes.size()), 3);
    for (size_t r = 0; r < nodes.size(); ++r)
      P.row(long(r)) = V.row(nodes[r]);
    const Eigen::MatrixXd D = surface.normals(P);
    for (size_t r = 0; r < nodes.size(); ++r)
      N.row(nodes[r]) = D.row(long(r));
  };
  normals();
  Eigen::MatrixXd A = surface_alphas(V, B, N);
  const double mean = A.cwiseAbs().mean();
  if (!(mean > 0))
    return 0;
  for (int r = 0; r < rounds; ++r) {
    std::vector<char> candidate(size_t(V.rows()), 0);
    bool any = false;
    for (long f = 0; f < B.rows(); ++f)
      if (A.row(f).minCoeff() <= flat * mean)
        for (int j = 0; j < k; ++j)
          candidate[size_t(B(f, j))] = any = true;
    if (!any)
      break;
    long moved = 0;
    for (const std::vector<int>& cls : detail::colour_nodes(B, candidate, nf)) {
      std::vector<LocalFunctional> Ls(cls.size());
      for (size_t c = 0; c < cls.size(); ++c) {
        const int v = cls[c];
        LocalFunctional& L = Ls[c];
        L.t = 1 / mean;
        // Terms: every corner of v's facets that involves v (as p, next or prev).
        for (long q = nf.start[size_t(v)]; q < nf.start[size_t(v) + 1]; ++q) {
          const int f = nf.at[size_t(q)];
          for (int j = 0; j < k; ++j) {
            const int p = B(f, j), nx = B(f, (j + 1) % k), pv = B(f, (j + k - 1) % k);
            if (p != v && nx != v && pv != v)
              continue;
            const Vec3 n = row(N, p), u = row(V, nx) - row(V, p), w = row(V, pv) - row(V, p);
            L.a.push_back(u.cross(w).dot(n));
            // d/du det[u, w, n] = w x n, d/dw = n x u; u = next - p, w = prev - p.
            L.g.push_back(p == v    ? Vec3(-w.cross(n) - n.cross(u))
                          : nx == v ? w.cross(n)
                                    : n.cross(u));
          }
        }
      }
      moved += slide_nodes(V, cls, Ls, surface, 0.5 * std::sqrt(mean));
    }
    normals();
    A = surface_alphas(V, B, N);
    if (moved == 0)
      break;
  }
  long folded = 0;
  for (long f = 0; f < B.rows(); ++f)
    folded += A.row(f).minCoeff() <= 0;
  return folded;
}

Eigen::MatrixXi corner_table(int corners_per_element) {
  if (corners_per_element != 4 && corners_per_element != 8)
    throw std::invalid_argument("corner_table: elements have 4 or 8 corners, not " +
                                std::to_string(corners_per_element));
  Eigen::MatrixXi T(corners_per_element, 3);
  for (int j = 0; j < corners_per_element; ++j)
    for (int k = 0; k < 3; ++k)
      T(j, k) = corners_per_element == 4 ? kTetCorners[j][k] : kHexCorners[j][k];
  return T;
}

Eigen::MatrixXd corner_alphas(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C, int threads) {
  const Eigen::MatrixXi T = corner_table(int(C.cols()));
  Eigen::MatrixXd A(C.rows(), C.cols());
  detail::parallel_chunks(C.rows(), kElementChunk, threads, [&](long, long e0, long e1) {
    for (long e = e0; e < e1; ++e)
      for (int j = 0; j < int(C.cols()); ++j)
        A(e, j) = corner_alpha(V, C, T, e, j);
  });
  return A;
}

VolumeSmoothingReport smooth_volume(Eigen::MatrixXd& V, const Eigen::MatrixXi& C,
                                    const std::vector<char>& fixed,
                                    const VolumeSmoothingOptions& o) {
  if (o.sweeps < 0 || !(o.t >= 0) || o.newton_steps < 1)
    throw std::invalid_argument("smooth_volume: sweeps >= 0, t >= 0 and newton_steps >= 1");
  if (V.cols() != 3 || (C.cols() != 4 && C.cols() != 8))
    throw std::invalid_argument("smooth_volume: V must be #V by 3 and C #C by 4 or #C by 8");
  if (!fixed.empty() && long(fixed.size()) != V.rows())
    throw std::invalid_argument("smooth_volume: fixed must have one flag per node");
  if (C.size() > 0 && (C.minCoeff() < 0 || C.maxCoeff() >= V.rows()))
    throw std::invalid_argument("smooth_volume: element index out of range");
  const Eigen::MatrixXi T = corner_table(int(C.cols()));
  VolumeSmoothingReport rep;
  if (C.rows() == 0)
    return rep;
  // t = 1 / mean alpha (digest §6.4 [A]); the mean of |alpha| if the mesh is inverted on average.
  const Eigen::MatrixXd A = corner_alphas(V, C, o.threads);
  const double mean = A.mean() > 0 ? A.mean() : A.cwiseAbs().mean();
  rep.t = o.t > 0 ? o.t : mean > 0 ? 1 / mean : 1;
  EnergyCount ec = energy(V, C, rep.t, o.threads);
  rep.energy.push_back(ec.mean);
  rep.inverted.push_back(ec.inverted);
  if (o.sweeps == 0)
    return rep;
  const detail::NodeElements ne(C, V.rows());
  std::vector<char> is_free(size_t(V.rows()), 1);
  for (long v = 0; v < V.rows(); ++v)
    is_free[size_t(v)] =
        (fixed.empty() || !fixed[size_t(v)]) && ne.start[size_t(v) + 1] > ne.start[size_t(v)];
  const std::vector<std::vector<int>> classes = detail::colour_nodes(C, is_free, ne);
  const int threads = detail::resolve_threads(o.threads);
  constexpr long kChunk = 256; // nodes per task
  // Active nodes: all free nodes in the first sweep, then the free nodes of elements at a node
  // that moved by more than 1e-3 of the mean edge length (smaller moves change the neighbours'
  // minima by less still: the relaxation is local to the distorted layer).
  const double still = 1e-3 * std::cbrt(mean);
  std::vector<char> active = is_free;
  for (int s = 0; s < o.sweeps; ++s) {
    std::vector<char> moved_far(size_t(V.rows()), 0);
    long moves = 0;
    for (const std::vector<int>& cls : classes) {
      const long n = long(cls.size());
      std::vector<long> moved(size_t(detail::chunk_count(n, kChunk)), 0);
      detail::parallel_chunks(n, kChunk, threads, [&](long task, long r0, long r1) {
        std::vector<Involvement> terms;
        for (long r = r0; r < r1; ++r) {
          const int v = cls[size_t(r)];
          if (!active[size_t(v)])
            continue;
          node_terms(C, T, ne, v, terms);
          const double d = minimise_node(V, C, T, terms, rep.t, o.keep, v, o.newton_steps);
          moved[size_t(task)] += d > 0;
          moved_far[size_t(v)] = d > still;
        }
      });
      for (long m : moved)
        moves += m;
    }
    rep.moves += moves;
    ec = energy(V, C, rep.t, o.threads);
    rep.energy.push_back(ec.mean);
    rep.inverted.push_back(ec.inverted);
    std::fill(active.begin(), active.end(), 0);
    for (long v = 0; v < V.rows(); ++v)
      if (moved_far[size_t(v)])
        for (long k = ne.start[size_t(v)]; k < ne.start[size_t(v) + 1]; ++k)
          for (long j = 0; j < C.cols(); ++j) {
            const int w = C(ne.at[size_t(k)], j);
            active[size_t(w)] = is_free[size_t(w)];
          }
    if (moves == 0)
      break;
  }
  return rep;
}

long slide_boundary_nodes(Eigen::MatrixXd& V, const Eigen::MatrixXi& C,
                          const std::vector<char>& fixed, const SlidingSurface& surface, double t,
                          double flat, int threads) {
  if (!(t > 0) || !(flat >= 0) || long(fixed.size()) != V.rows())
    throw std::invalid_argument("slide_boundary_nodes: t > 0, flat >= 0, one flag per node");
  if (!surface.normals || !surface.project)
    throw std::invalid_argument("slide_boundary_nodes: the surface needs normals and project");
  const Eigen::MatrixXi T = corner_table(int(C.cols()));
  const Eigen::MatrixXd A = corner_alphas(V, C, threads);
  const double limit = flat * A.cwiseAbs().mean();
  std::vector<char> candidate(size_t(V.rows()), 0);
  for (long e = 0; e < C.rows(); ++e)
    if (A.row(e).minCoeff() <= limit)
      for (long j = 0; j < C.cols(); ++j)
        candidate[size_t(C(e, j))] = fixed[size_t(C(e, j))];
  const detail::NodeElements ne(C, V.rows());
  std::vector<Involvement> terms;
  long moved = 0;
  for (const std::vector<int>& cls : detail::colour_nodes(C, candidate, ne)) {
    std::vector<LocalFunctional> Ls(cls.size());
    for (size_t c = 0; c < cls.size(); ++c) {
      node_terms(C, T, ne, cls[c], terms);
      LocalFunctional& L = Ls[c];
      L.t = t;
      L.a.resize(terms.size());
      L.g.resize(terms.size());
      for (size_t k = 0; k < terms.size(); ++k)
        L.a[k] = alpha_and_gradient(V, C, T, terms[k], L.g[k]);
    }
    moved += slide_nodes(V, cls, Ls, surface, 0.5 * std::cbrt(1 / t));
  }
  return moved;
}

} // namespace interlin
