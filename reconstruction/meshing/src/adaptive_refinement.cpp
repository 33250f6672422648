// Seed 003, digest §7.2 (adaptive FRep meshing) and §11.6: indicator and 2-refinement templates
// of tetrahedra.
#include "interlin/reconstruction/meshing/adaptive_refinement.h"

#include "interlin/reconstruction/meshing/project_to_zero.h"
#include "interlin/reconstruction/meshing/volume_mesh.h"

#include "element_limit.h"
#include "place_projected.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <map>
#include <stdexcept>
#include <utility>

namespace interlin {

namespace {

using Tet = std::array<int, 4>;

// Edge midpoints of the refinement, numbered after the existing nodes.
struct Midpoints {
  std::map<std::pair<int, int>, int> index;
  std::vector<std::pair<int, int>> edges; // in order of creation
  int first = 0;

  int of(int a, int b) {
    const std::pair<int, int> key = std::minmax(a, b);
    const auto [it, added] = index.emplace(key, first + int(edges.size()));
    if (added)
      edges.push_back(key);
    return it->second;
  }
};

// The children of tetrahedron t whose refined local vertices are the bits of `code` (digest §7.2
// table: <= 1 unchanged, 2 edge bisected, 3 face split 1 -> 4, 4 eight children with the
// octahedron cut along m02-m13). Orientation is fixed afterwards.
void children(const Tet& t, unsigned code, Midpoints& mid, std::vector<Tet>& out) {
  int refined[4], others[4], nr = 0, no = 0;
  for (int j = 0; j < 4; ++j)
    (code >> j & 1u ? refined[nr++] : others[no++]) = t[size_t(j)];
  if (nr <= 1) {
    out.push_back(t);
  } else if (nr == 2) { // the edge between the two refined vertices is halved
    const int m = mid.of(refined[0], refined[1]);
    for (int r = 0; r < 2; ++r) {
      Tet c = t;
      std::replace(c.begin(), c.end(), refined[r], m);
      out.push_back(c);
    }
  } else if (nr == 3) { // face (a, b, c) split 1 -> 4, each joined to the fourth vertex d
    const int a = refined[0], b = refined[1], c = refined[2], d = others[0];
    const int ab = mid.of(a, b), bc = mid.of(b, c), ca = mid.of(c, a);
    out.push_back({a, ab, ca, d});
    out.push_back({b, bc, ab, d});
    out.push_back({c, ca, bc, d});
    out.push_back({ab, bc, ca, d});
  } else {
    int m[4][4];
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        m[i][j] = m[j][i] = mid.of(t[size_t(i)], t[size_t(j)]);
    for (int i = 0; i < 4; ++i) { // corner tetrahedra
      Tet c = {t[size_t(i)], 0, 0, 0};
      for (int j = 0, k = 1; j < 4; ++j)
        if (j != i)
          c[size_t(k++)] = m[i][j];
      out.push_back(c);
    }
    // The octahedron around its diagonal m02-m13; the ring m01, m12, m23, m03 (consecutive
    // midpoints share a vertex of t).
    const int ring[4] = {m[0][1], m[1][2], m[2][3], m[0][3]};
    for (int k = 0; k < 4; ++k)
      out.push_back({m[0][2], m[1][3], ring[k], ring[(k + 1) % 4]});
  }
}

// The elements after the split: a tetrahedron with k refined vertices has 1, 1, 2, 4 or 8
// children (the templates of `children`).
long tetrahedra_after(const Eigen::MatrixXi& C, const std::vector<char>& refined) {
  constexpr long kChildren[5] = {1, 1, 2, 4, 8};
  long n = 0;
  for (long e = 0; e < C.rows(); ++e) {
    int k = 0;
    for (int j = 0; j < 4; ++j)
      k += refined[size_t(C(e, j))] != 0;
    n += kChildren[k];
  }
  return n;
}

double signed_volume6(const Eigen::MatrixXd& V, const Tet& t) {
  const Eigen::Vector3d p0 = V.row(t[0]).transpose(), a = V.row(t[1]).transpose() - p0,
                        b = V.row(t[2]).transpose() - p0, c = V.row(t[3]).transpose() - p0;
  return a.cross(b).dot(c);
}

// Edges of the boundary facets (the faces used by one element), as sorted pairs.
std::vector<std::pair<int, int>> facet_edges(const Eigen::MatrixXi& C) {
  const Eigen::MatrixXi B = boundary_facets(C);
  std::vector<std::pair<int, int>> e;
  e.reserve(size_t(3 * B.rows()));
  for (long f = 0; f < B.rows(); ++f)
    for (int j = 0; j < 3; ++j)
      e.push_back(std::minmax(B(f, j), B(f, (j + 1) % 3)));
  std::sort(e.begin(), e.end());
  e.erase(std::unique(e.begin(), e.end()), e.end());
  return e;
}

} // namespace

std::vector<char> refined_nodes(const Eigen::MatrixXi& C, const Eigen::VectorXd& indicator,
                                double delta, long nodes, long* flagged) {
  std::vector<char> seed(size_t(nodes), 0), refined(size_t(nodes), 0);
  long count = 0;
  for (long e = 0; e < C.rows(); ++e)
    if (indicator(e) > delta) {
      ++count;
      for (long j = 0; j < C.cols(); ++j)
        seed[size_t(C(e, j))] = 1;
    }
  for (long e = 0; e < C.rows(); ++e) {
    bool touches = false;
    for (long j = 0; j < C.cols(); ++j)
      touches = touches || seed[size_t(C(e, j))];
    if (touches)
      for (long j = 0; j < C.cols(); ++j)
        refined[size_t(C(e, j))] = 1;
  }
  if (flagged != nullptr)
    *flagged = count;
  return refined;
}

Eigen::VectorXd refinement_indicator(const Eigen::MatrixXi& C, const Eigen::VectorXd& values) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(C.rows());
  if (values.size() == 0)
    return out;
  const double range = values.maxCoeff() - values.minCoeff();
  if (!(range > 0))
    return out;
  for (long e = 0; e < C.rows(); ++e) {
    double lo = values(C(e, 0)), hi = lo;
    for (long j = 1; j < C.cols(); ++j)
      lo = std::min(lo, values(C(e, j))), hi = std::max(hi, values(C(e, j)));
    out(e) = (hi - lo) / range; // max |C_i - C_j| over the element's vertex pairs
  }
  return out;
}

RefinementReport refine_tetrahedra(Eigen::MatrixXd& V, Eigen::MatrixXi& C,
                                   std::vector<char>& boundary, Eigen::VectorXd& values,
                                   double delta, const ImplicitFunction& f, long max_elements) {
  if (C.cols() != 4 || V.cols() != 3)
    throw std::invalid_argument("refine_tetrahedra: V must be #V by 3 and C #C by 4");
  if (values.size() != V.rows() || !values.allFinite())
    throw std::invalid_argument("refine_tetrahedra: values must be #V finite numbers");
  if (boundary.size() != size_t(V.rows()))
    throw std::invalid_argument("refine_tetrahedra: boundary must have #V flags");
  if (!(delta >= 0 && delta < 1))
    throw std::invalid_argument("refine_tetrahedra: delta must be in [0, 1)");
  RefinementReport rep;
  const std::vector<char> refined =
      refined_nodes(C, refinement_indicator(C, values), delta, V.rows(), &rep.flagged);
  rep.refined_nodes = std::count(refined.begin(), refined.end(), char(1));
  if (rep.flagged == 0)
    return rep;
  detail::check_element_count(tetrahedra_after(C, refined), max_elements, "refine_tetrahedra");
  const std::vector<std::pair<int, int>> on_surface = facet_edges(C);

  Midpoints mid;
  mid.first = int(V.rows());
  std::vector<Tet> out;
  out.reserve(size_t(C.rows()));
  for (long e = 0; e < C.rows(); ++e) {
    const Tet t = {C(e, 0), C(e, 1), C(e, 2), C(e, 3)};
    unsigned code = 0;
    for (int j = 0; j < 4; ++j)
      code |= unsigned(refined[size_t(t[size_t(j)])]) << j;
    const size_t before = out.size();
    children(t, code, mid, out);
    rep.split += out.size() - before > 1;
  }

  const long n0 = V.rows(), added = long(mid.edges.size());
  rep.new_nodes = added;
  V.conservativeResize(n0 + added, 3);
  values.conservativeResize(n0 + added);
  boundary.resize(size_t(n0 + added), 0);
  std::vector<long> project;
  for (long k = 0; k < added; ++k) {
    const auto [a, b] = mid.edges[size_t(k)];
    V.row(n0 + k) = 0.5 * (V.row(a) + V.row(b));
    values(n0 + k) = 0.5 * (values(a) + values(b));
    if (f.value && boundary[size_t(a)] && boundary[size_t(b)] &&
        std::binary_search(on_surface.begin(), on_surface.end(), mid.edges[size_t(k)]))
      project.push_back(k);
  }
  // Children re-oriented positive (digest §7.2 [C]) with the midpoints still on their edges: a
  // projection that folds an element shows as inverted instead of being turned over.
  C.resize(long(out.size()), 4);
  for (size_t e = 0; e < out.size(); ++e) {
    Tet t = out[e];
    if (signed_volume6(V, t) < 0)
      std::swap(t[2], t[3]);
    for (int j = 0; j < 4; ++j)
      C(long(e), j) = t[size_t(j)];
  }
  if (!project.empty()) { // onto F = 0 along the gradient, steps of a quarter of the edge
    Eigen::MatrixXd P(long(project.size()), 3);
    Eigen::VectorXd h(P.rows());
    for (size_t r = 0; r < project.size(); ++r) {
      const auto [a, b] = mid.edges[size_t(project[r])];
      P.row(long(r)) = V.row(n0 + project[r]);
      h(long(r)) = 0.25 * (V.row(a) - V.row(b)).norm();
    }
    std::vector<char> moved;
    project_by_gradient_walk(f, P, h, 100, {}, &moved);
    rep.held_nodes = detail::place_projected(
        C, n0, project, P, moved, V, [&C](const Eigen::MatrixXd& W, long e) {
          return signed_volume6(W, {C(e, 0), C(e, 1), C(e, 2), C(e, 3)}) > 0;
        });
    rep.held = long(rep.held_nodes.size());
    for (size_t r = 0; r < project.size(); ++r) {
      boundary[size_t(n0 + project[r])] = moved[r];
      rep.projected += moved[r];
    }
  }
  return rep;
}

std::vector<RefinementReport> adapt_tetrahedra(
    Eigen::MatrixXd& V, Eigen::MatrixXi& C, std::vector<char>& boundary,
    const std::function<Eigen::VectorXd(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C)>& field,
    double delta, int iterations, const ImplicitFunction& f, long max_elements) {
  if (iterations < 0)
    throw std::invalid_argument("adapt_tetrahedra: iterations must be >= 0");
  std::vector<RefinementReport> reports;
  for (int it = 0; it < iterations; ++it) {
    Eigen::VectorXd values = field(V, C);
    reports.push_back(refine_tetrahedra(V, C, boundary, values, delta, f, max_elements));
    if (reports.back().flagged == 0)
      break;
  }
  return reports;
}

} // namespace interlin
