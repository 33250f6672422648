// Seed 003, digest §5.3: functional (12) minimised by coordinate descent with re-projection.
#include "interlin/reconstruction/meshing/surface_smoothing.h"

#include "interlin/reconstruction/meshing/project_to_zero.h"

#include "min_angle.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace interlin {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kWalkSteps = 100; // gradient-walk steps before a point counts as not projectable

// Normal of the triangle (a, b, c), not normalised.
Eigen::Vector3d normal(const Eigen::RowVector3d& a, const Eigen::RowVector3d& b,
                       const Eigen::RowVector3d& c) {
  return (b - a).transpose().cross((c - a).transpose());
}

struct Topology {
  std::vector<std::vector<int>> nbr;   // adjacent vertices
  std::vector<std::vector<int>> faces; // incident faces
};

Topology topology(long nv, const Eigen::MatrixXi& F) {
  Topology t;
  t.nbr.resize(size_t(nv));
  t.faces.resize(size_t(nv));
  for (int f = 0; f < int(F.rows()); ++f)
    for (int j = 0; j < 3; ++j) {
      const int a = F(f, j);
      t.faces[size_t(a)].push_back(f);
      t.nbr[size_t(a)].push_back(F(f, (j + 1) % 3));
      t.nbr[size_t(a)].push_back(F(f, (j + 2) % 3));
    }
  for (auto& l : t.nbr) {
    std::sort(l.begin(), l.end());
    l.erase(std::unique(l.begin(), l.end()), l.end());
  }
  return t;
}

// Projects the points P onto F = 0 by the gradient walk with steps h; ok[r] tells success.
void walk(const ImplicitFunction& f, Eigen::MatrixXd& P, const Eigen::VectorXd& h, int threads,
          std::vector<char>& ok) {
  RootOptions ro;
  ro.threads = threads;
  project_by_gradient_walk(f, P, h, kWalkSteps, ro, &ok);
}

// The two other vertices of face q seen from vertex v.
std::pair<int, int> others(const Eigen::MatrixXi& F, int q, int v) {
  const int j = F(q, 0) == v ? 0 : F(q, 1) == v ? 1 : 2;
  return {F(q, (j + 1) % 3), F(q, (j + 2) % 3)};
}

// Whether vertex v may move to x: no face at v turns over, no face at or above `angle_floor`
// (radians) falls below it, and the star's smallest angle, if below the floor, does not shrink.
// So the faces below the floor never grow in number and the smallest angle never falls, while
// the vertices of existing slivers stay free to move.
bool star_stays_sound(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Topology& t, int v,
                      const Eigen::RowVector3d& x, double angle_floor) {
  double min_now = M_PI, min_then = M_PI;
  for (int q : t.faces[size_t(v)]) {
    const auto [b, c] = others(F, q, v);
    const Eigen::RowVector3d pv = V.row(v), pb = V.row(b), pc = V.row(c);
    if (normal(pv, pb, pc).dot(normal(x, pb, pc)) <= 0)
      return false;
    const double now = detail::min_angle(pv.transpose(), pb.transpose(), pc.transpose());
    const double then = detail::min_angle(x.transpose(), pb.transpose(), pc.transpose());
    if (now >= angle_floor && then < angle_floor)
      return false;
    min_now = std::min(min_now, now);
    min_then = std::min(min_then, then);
  }
  return min_then >= std::min(min_now, angle_floor);
}

// E_v(X) for every (v, X) of the batch (functional (12)); +inf when a centroid does not project
// or the star would not stay sound (star_stays_sound with `angle_floor`).
Eigen::VectorXd energies(const ImplicitFunction& f, const Eigen::MatrixXd& V,
                         const Eigen::MatrixXi& F, const Topology& t, const std::vector<int>& who,
                         const Eigen::MatrixXd& X, double kappa, double angle_floor, int threads) {
  const long n = long(who.size());
  long m = 0;
  for (int v : who)
    m += long(t.faces[size_t(v)].size());
  Eigen::MatrixXd C(m, 3);
  Eigen::VectorXd h(m);
  Eigen::VectorXd E = Eigen::VectorXd::Zero(n);
  for (long r = 0, row = 0; r < n; ++r) {
    const int v = who[size_t(r)];
    const Eigen::RowVector3d x = X.row(r);
    if (!star_stays_sound(V, F, t, v, x, angle_floor))
      E(r) = kInf;
    for (int q : t.faces[size_t(v)]) {
      const auto [b, c] = others(F, q, v);
      const Eigen::RowVector3d pb = V.row(b), pc = V.row(c);
      E(r) += kappa * ((pb - x).squaredNorm() + (pc - x).squaredNorm());
      C.row(row) = (x + pb + pc) / 3;
      h(row) = std::max(0.25 * std::min((pb - x).norm(), (pc - x).norm()), 1e-300);
      ++row;
    }
  }
  Eigen::MatrixXd P = C;
  std::vector<char> ok;
  walk(f, P, h, threads, ok);
  for (long r = 0, row = 0; r < n; ++r)
    for (size_t k = 0; k < t.faces[size_t(who[size_t(r)])].size(); ++k, ++row)
      E(r) += ok[size_t(row)] ? (1 - kappa) * (P.row(row) - C.row(row)).squaredNorm() : kInf;
  return E;
}

// Sum over all faces of |C_q - proj(C_q)|^2.
double fit(const ImplicitFunction& f, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
           int threads) {
  Eigen::MatrixXd C(F.rows(), 3);
  Eigen::VectorXd h(F.rows());
  for (long q = 0; q < F.rows(); ++q) {
    const Eigen::RowVector3d a = V.row(F(q, 0)), b = V.row(F(q, 1)), c = V.row(F(q, 2));
    C.row(q) = (a + b + c) / 3;
    h(q) = std::max(0.25 * std::min({(a - b).norm(), (b - c).norm(), (c - a).norm()}), 1e-300);
  }
  Eigen::MatrixXd P = C;
  std::vector<char> ok;
  walk(f, P, h, threads, ok);
  double s = 0;
  for (long q = 0; q < F.rows(); ++q)
    s += ok[size_t(q)] ? (P.row(q) - C.row(q)).squaredNorm() : 0.0;
  return s;
}

} // namespace

SurfaceSmoothingReport smooth_on_surface(const ImplicitFunction& f, Eigen::MatrixXd& V,
                                         const Eigen::MatrixXi& F,
                                         const SurfaceSmoothingOptions& o) {
  if (!f.value)
    throw std::invalid_argument("smooth_on_surface: the implicit function has no value");
  if (V.cols() != 3 || F.cols() != 3)
    throw std::invalid_argument("smooth_on_surface: V and F must have 3 columns");
  if (!(o.kappa > 0 && o.kappa < 1) || o.iterations < 0)
    throw std::invalid_argument("smooth_on_surface: kappa must be in (0, 1), iterations >= 0");
  const long nv = V.rows();
  for (long q = 0; q < F.rows(); ++q)
    for (int j = 0; j < 3; ++j)
      if (F(q, j) < 0 || F(q, j) >= nv)
        throw std::invalid_argument("smooth_on_surface: face " + std::to_string(q) +
                                    " has an index out of range");
  const Topology t = topology(nv, F);
  const double angle_floor = o.min_angle_deg * M_PI / 180;
  // Greedy colouring: a colour class holds no two adjacent vertices.
  std::vector<int> colour(size_t(nv), -1);
  int colours = 0;
  for (long v = 0; v < nv; ++v) {
    std::vector<char> used(size_t(colours + 1), 0);
    for (int w : t.nbr[size_t(v)])
      if (colour[size_t(w)] >= 0)
        used[size_t(colour[size_t(w)])] = 1;
    int c = 0;
    while (used[size_t(c)])
      ++c;
    colour[size_t(v)] = c;
    colours = std::max(colours, c + 1);
  }
  std::vector<std::vector<int>> classes(static_cast<size_t>(colours));
  for (long v = 0; v < nv; ++v)
    if (!t.faces[size_t(v)].empty())
      classes[size_t(colour[size_t(v)])].push_back(int(v));

  SurfaceSmoothingReport report;
  report.fit.push_back(fit(f, V, F, o.threads));
  for (int it = 0; it < o.iterations; ++it) {
    if (o.laplacian && it == 0) {
      Eigen::MatrixXd P(nv, 3);
      Eigen::VectorXd h(nv);
      for (long v = 0; v < nv; ++v) {
        const auto& nb = t.nbr[size_t(v)];
        if (nb.empty()) {
          P.row(v) = V.row(v);
          h(v) = 1;
          continue;
        }
        Eigen::RowVector3d s = Eigen::RowVector3d::Zero();
        double len = 0;
        for (int w : nb) {
          s += V.row(w);
          len += (V.row(w) - V.row(v)).norm();
        }
        P.row(v) = s / double(nb.size());
        h(v) = std::max(0.1 * len / double(nb.size()), 1e-300);
      }
      std::vector<char> ok;
      walk(f, P, h, o.threads, ok);
      // Keep a vertex where it was if its projection failed or a face would turn over. No angle
      // floor here: the pass moves all vertices at once, and judged against half-moved
      // neighbours the floor froze the slivers' vertices (body (11) at 20 cells: fit 2x).
      for (long v = 0; v < nv; ++v)
        if (ok[size_t(v)] && star_stays_sound(V, F, t, int(v), P.row(v), 0.0))
          V.row(v) = P.row(v);
    }
    for (const std::vector<int>& cls : classes) {
      const long n = long(cls.size());
      if (n == 0)
        continue;
      // Targets of each vertex: its neighbours and the midpoints of its opposite edges.
      std::vector<std::vector<Eigen::RowVector3d>> targets(static_cast<size_t>(n));
      for (long r = 0; r < n; ++r) {
        const int v = cls[size_t(r)];
        for (int w : t.nbr[size_t(v)])
          targets[size_t(r)].push_back(V.row(w));
        for (int q : t.faces[size_t(v)]) {
          const auto [b, c] = others(F, q, v);
          targets[size_t(r)].push_back(0.5 * (V.row(b) + V.row(c)));
        }
      }
      Eigen::MatrixXd X(n, 3);
      for (long r = 0; r < n; ++r)
        X.row(r) = V.row(cls[size_t(r)]);
      Eigen::VectorXd E = energies(f, V, F, t, cls, X, o.kappa, angle_floor, o.threads);
      std::vector<size_t> target(size_t(n), 0);
      std::vector<double> step(size_t(n), 0.1);
      std::vector<int> tries(size_t(n), 0);
      for (;;) {
        std::vector<int> who;
        std::vector<long> row;
        for (long r = 0; r < n; ++r) {
          // Next target when the step is spent (s < 0.001) or 10 trials were made.
          while (target[size_t(r)] < targets[size_t(r)].size() &&
                 (step[size_t(r)] < 1e-3 || tries[size_t(r)] >= 10)) {
            ++target[size_t(r)];
            step[size_t(r)] = 0.1;
            tries[size_t(r)] = 0;
          }
          if (target[size_t(r)] < targets[size_t(r)].size()) {
            who.push_back(cls[size_t(r)]);
            row.push_back(r);
          }
        }
        if (who.empty())
          break;
        const long m = long(who.size());
        Eigen::MatrixXd T(m, 3);
        Eigen::VectorXd h(m);
        for (long a = 0; a < m; ++a) {
          const long r = row[size_t(a)];
          const Eigen::RowVector3d x = V.row(who[size_t(a)]);
          const Eigen::RowVector3d p = targets[size_t(r)][target[size_t(r)]];
          T.row(a) = x + step[size_t(r)] * (p - x);
          h(a) = std::max(0.25 * (p - x).norm(), 1e-300);
        }
        std::vector<char> ok;
        walk(f, T, h, o.threads, ok);
        const Eigen::VectorXd Et = energies(f, V, F, t, who, T, o.kappa, angle_floor, o.threads);
        for (long a = 0; a < m; ++a) {
          const long r = row[size_t(a)];
          ++tries[size_t(r)];
          if (ok[size_t(a)] && Et(a) < E(r)) {
            V.row(who[size_t(a)]) = T.row(a);
            E(r) = Et(a);
            ++report.moves;
          } else {
            step[size_t(r)] /= 10;
          }
        }
      }
    }
    report.fit.push_back(fit(f, V, F, o.threads));
  }
  return report;
}

} // namespace interlin
