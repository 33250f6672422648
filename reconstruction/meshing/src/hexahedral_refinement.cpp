// Seed 003, digest §7.2 (adaptive FRep meshing): 3-refinement templates of hexahedra, the closure
// of the refined-node set, and the adaptive loop.
#include "interlin/reconstruction/meshing/hexahedral_refinement.h"

#include "interlin/reconstruction/meshing/project_to_zero.h"
#include "interlin/reconstruction/meshing/volume_mesh.h"
#include "interlin/reconstruction/meshing/volume_smoothing.h"

#include "corner_jacobian.h"
#include "element_limit.h"
#include "place_projected.h"
#include "untangle.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <deque>
#include <limits>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

namespace interlin {

namespace {

// Template points are lattice points of the parent's reference cube [0, 1]^3 in units of 1 / kD:
// thirds on its edges and faces (the seed's 4 x 4 x 4 lattice); the face template's inner
// transitions also use sixths.
constexpr int kD = 18;
constexpr int kThird = kD / 3;

using Lattice = std::array<int, 3>;
using Child = std::array<Lattice, 8>;

// The reference cube in VTK order: corners, edges, faces (cyclic, outward).
constexpr int kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                               {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
constexpr int kEdge[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                              {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
constexpr int kFace[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                             {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
constexpr unsigned kAllEdges = 0xFFFu;

Lattice corner_point(int c) {
  return {kD * kCorner[c][0], kD * kCorner[c][1], kD * kCorner[c][2]};
}

// The corner at lattice point p (every coordinate 0 or kD).
int corner_at(const Lattice& p) {
  for (int c = 0; c < 8; ++c)
    if (corner_point(c) == p)
      return c;
  throw std::logic_error("hexahedral refinement: not a corner of the reference cube");
}

// ---- Templates in their reference position --------------------------------------------------

// 27 children: the sub-cubes of the 4 x 4 x 4 lattice.
std::vector<Child> full_template() {
  std::vector<Child> out;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) {
        Child c;
        for (int v = 0; v < 8; ++v)
          c[size_t(v)] = {kThird * (i + kCorner[v][0]), kThird * (j + kCorner[v][1]),
                          kThird * (k + kCorner[v][2])};
        out.push_back(c);
      }
  return out;
}

// Edge 0-1 (x at y = z = 0) trisected at a, b: the cube [1/3, 2/3] x [0, 1/3]^2, one hexahedron on
// each side out to the faces x = 0 and x = 1, and two filling the rest between c, d, g, h and the
// far corners. The faces y = 0 and z = 0 get the seed's 4-quadrilateral transition, the other four
// stay whole.
std::vector<Child> edge_template() {
  const int t = kThird, u = 2 * kThird;
  const Lattice p0 = corner_point(0), p1 = corner_point(1), p2 = corner_point(2),
                p3 = corner_point(3), p4 = corner_point(4), p5 = corner_point(5),
                p6 = corner_point(6), p7 = corner_point(7);
  const Lattice a = {t, 0, 0}, b = {u, 0, 0}, c = {t, t, 0}, d = {u, t, 0}, e = {t, 0, t},
                f = {u, 0, t}, g = {t, t, t}, h = {u, t, t};
  return {{a, b, d, c, e, f, h, g},
          {p0, a, c, p3, p4, e, g, p7},
          {b, p1, p2, d, f, p5, p6, h},
          {c, d, p2, p3, g, h, p6, p7},
          {g, h, p6, p7, e, f, p5, p4}};
}

// The point of quadrilateral q (q[0] at (0, 0), q[1] at (1, 0), q[2] at (1, 1), q[3] at (0, 1))
// at (v, w), bilinear; it must be a lattice point.
Lattice bilinear(const std::array<Lattice, 4>& q, double v, double w) {
  Lattice p;
  for (size_t i = 0; i < 3; ++i) {
    const double x = (1 - v) * (1 - w) * q[0][i] + v * (1 - w) * q[1][i] + v * w * q[2][i] +
                     (1 - v) * w * q[3][i];
    p[i] = int(std::lround(x));
    if (std::abs(x - p[i]) > 1e-9)
      throw std::logic_error("hexahedral refinement: a template point off the lattice");
  }
  return p;
}

// The seed's 2-D transition (one side trisected, 4 quadrilaterals) on both sides u = 0 and u = 1
// of hexahedron q (local axes u = q0 -> q1, v = q0 -> q3, w = q0 -> q4; edges q0-q3 and q1-q2
// trisected), joined across: 4 children. The transition's inner points lie at height lambda[s] of
// side s (1/3 on a face of the parent, where the neighbour's transition must meet them).
void extruded_transition(const Child& q, const std::array<double, 2>& lambda,
                         std::vector<Child>& out) {
  const std::array<std::array<Lattice, 4>, 2> side = {
      std::array<Lattice, 4>{q[0], q[3], q[7], q[4]},
      std::array<Lattice, 4>{q[1], q[2], q[6], q[5]}};
  // Per side: the 2-D transition's quadrilaterals as (v, w) of their corners.
  std::array<std::array<Lattice, 4>, 4> quads[2];
  for (size_t s = 0; s < 2; ++s) {
    const std::array<Lattice, 4>& S = side[s];
    const Lattice e1 = bilinear(S, 1.0 / 3, 0), e2 = bilinear(S, 2.0 / 3, 0);
    const Lattice i1 = bilinear(S, 1.0 / 3, lambda[s]), i2 = bilinear(S, 2.0 / 3, lambda[s]);
    quads[s] = {std::array<Lattice, 4>{S[0], e1, i1, S[3]},
                {e1, e2, i2, i1},
                {e2, S[1], S[2], i2},
                {i1, i2, S[2], S[3]}};
  }
  for (size_t k = 0; k < 4; ++k)
    out.push_back({quads[0][k][0], quads[0][k][1], quads[0][k][2], quads[0][k][3], quads[1][k][0],
                   quads[1][k][1], quads[1][k][2], quads[1][k][3]});
}

// Face 0-1-2-3 (z = 0) split 3 x 3 in two stages (Schneiders' face template): the 2-D transition
// in the xz-plane extruded along y (strips L, M, R over the face and T above them, meeting the
// top face whole), then each strip split across by the same transition extruded along x. 13
// children; the 4 side faces get the 4-quadrilateral transition, the top stays whole.
std::vector<Child> face_template() {
  // Inner transitions, inside the parent, halfway up the strips (1/3 would make 3:1 slabs).
  constexpr double kInner = 0.5, kOnFace = 1.0 / 3;
  const int t = kThird, u = 2 * kThird, D = kD;
  const Lattice a = {t, 0, 0}, b = {u, 0, 0}, a1 = {t, D, 0}, b1 = {u, D, 0}, e = {t, 0, t},
                f = {u, 0, t}, e1 = {t, D, t}, f1 = {u, D, t};
  const Child L = {corner_point(0), a, a1, corner_point(3),
                   corner_point(4), e, e1, corner_point(7)};
  const Child M = {a, b, b1, a1, e, f, f1, e1};
  const Child R = {b, corner_point(1), corner_point(2), b1,
                   f, corner_point(5), corner_point(6), f1};
  const Child T = {
      e, f, f1, e1, corner_point(4), corner_point(5), corner_point(6), corner_point(7)};
  std::vector<Child> out = {T};
  extruded_transition(L, {kOnFace, kInner}, out);
  extruded_transition(M, {kInner, kInner}, out);
  extruded_transition(R, {kInner, kOnFace}, out);
  return out;
}

// ---- The cube's rotations and the 256-entry table --------------------------------------------

// A proper rotation of the reference cube: a signed permutation matrix with determinant 1, and the
// corner each reference corner goes to.
struct Rotation {
  std::array<std::array<int, 3>, 3> R;
  std::array<int, 8> corner;
};

// p rotated about the cube's centre (doubled coordinates stay integers).
Lattice rotate(const Rotation& r, const Lattice& p) {
  Lattice q;
  for (size_t i = 0; i < 3; ++i) {
    int x = 0;
    for (size_t j = 0; j < 3; ++j)
      x += r.R[i][j] * (2 * p[j] - kD);
    q[i] = (x + kD) / 2;
  }
  return q;
}

std::vector<Rotation> cube_rotations() {
  std::vector<Rotation> out;
  std::array<int, 3> axes = {0, 1, 2};
  do {
    for (int signs = 0; signs < 8; ++signs) {
      Rotation r{};
      for (size_t i = 0; i < 3; ++i)
        r.R[i][size_t(axes[i])] = signs >> i & 1 ? -1 : 1;
      const int det = r.R[0][0] * (r.R[1][1] * r.R[2][2] - r.R[1][2] * r.R[2][1]) -
                      r.R[0][1] * (r.R[1][0] * r.R[2][2] - r.R[1][2] * r.R[2][0]) +
                      r.R[0][2] * (r.R[1][0] * r.R[2][1] - r.R[1][1] * r.R[2][0]);
      if (det != 1)
        continue;
      for (int c = 0; c < 8; ++c)
        r.corner[size_t(c)] = corner_at(rotate(r, corner_point(c)));
      out.push_back(r);
    }
  } while (std::next_permutation(axes.begin(), axes.end()));
  return out;
}

unsigned vertex_bits(const int* v, int n) {
  unsigned bits = 0;
  for (int k = 0; k < n; ++k)
    bits |= 1u << v[k];
  return bits;
}

// The edges (bits of kEdge) with both ends among the vertices in `code`.
unsigned refined_edges(unsigned code) {
  unsigned mask = 0;
  for (int k = 0; k < 12; ++k)
    if ((code >> kEdge[k][0] & 1u) && (code >> kEdge[k][1] & 1u))
      mask |= 1u << k;
  return mask;
}

unsigned face_edges(int f) {
  return refined_edges(vertex_bits(kFace[f], 4));
}

// The face whose edges are exactly `edges`, or -1.
int face_with_edges(unsigned edges) {
  for (int f = 0; f < 6; ++f)
    if (face_edges(f) == edges)
      return f;
  return -1;
}

HexTemplate template_of_edges(unsigned edges) {
  if (edges == 0)
    return HexTemplate::none;
  if (std::popcount(edges) == 1)
    return HexTemplate::edge;
  if (edges == kAllEdges)
    return HexTemplate::full;
  return face_with_edges(edges) >= 0 ? HexTemplate::face : HexTemplate::unsupported;
}

// One widening step: the vertices of the face holding every refined edge, else all 8.
unsigned widened(unsigned code) {
  const unsigned edges = refined_edges(code);
  if (template_of_edges(edges) != HexTemplate::unsupported)
    return code;
  for (int f = 0; f < 6; ++f)
    if ((edges & ~face_edges(f)) == 0)
      return code | vertex_bits(kFace[f], 4);
  return 0xFFu;
}

// Per refined-vertex code: the closed code (widened to a fixed point), its template and the
// rotation that carries the template's reference position onto it.
struct TableEntry {
  unsigned closed = 0;
  HexTemplate kind = HexTemplate::none;
  int rotation = 0;
};

struct Templates {
  std::vector<Rotation> rotations = cube_rotations();
  std::vector<Child> edge = edge_template(), face = face_template(), full = full_template();
  std::array<TableEntry, 256> table;

  Templates() {
    for (unsigned code = 0; code < 256; ++code) {
      TableEntry& t = table[code];
      t.closed = code;
      for (unsigned next = widened(code); next != t.closed; next = widened(next))
        t.closed = next;
      const unsigned edges = refined_edges(t.closed);
      t.kind = template_of_edges(edges);
      if (t.kind == HexTemplate::edge)
        t.rotation = rotation_onto(vertex_bits(kEdge[std::countr_zero(edges)], 2), 2);
      else if (t.kind == HexTemplate::face)
        t.rotation = rotation_onto(vertex_bits(kFace[face_with_edges(edges)], 4), 4);
    }
  }

  // A rotation taking the reference corners 0 .. n-1 (edge 0-1, face 0-1-2-3) onto `target`.
  int rotation_onto(unsigned target, int n) const {
    const int reference[4] = {0, 1, 2, 3};
    for (size_t r = 0; r < rotations.size(); ++r) {
      int image[4];
      for (int k = 0; k < n; ++k)
        image[k] = rotations[r].corner[size_t(reference[k])];
      if (vertex_bits(image, n) == target)
        return int(r);
    }
    throw std::logic_error("hexahedral refinement: no rotation onto a template's position");
  }

  const std::vector<Child>& children(HexTemplate kind) const {
    return kind == HexTemplate::edge ? edge : kind == HexTemplate::face ? face : full;
  }
};

const Templates& templates() {
  static const Templates t;
  return t;
}

unsigned code_of(const Eigen::MatrixXi& C, long e, const std::vector<char>& refined) {
  unsigned code = 0;
  for (int j = 0; j < 8; ++j)
    code |= unsigned(refined[size_t(C(e, j))] != 0) << j;
  return code;
}

// ---- New nodes, keyed by where they lie ------------------------------------------------------

// A new node's identity, the same from every element that has it: an edge point by its edge's
// node ids (lower first) and its lattice step from the lower; a face point by the face's lowest
// node, its lower and higher neighbours, the opposite node and its lattice coordinates from the
// lowest towards the two neighbours; an inner point by its element and lattice point.
enum class Where : long { edge, face, inner };
using NodeKey = std::array<long, 7>;

struct NodeKeyHash {
  size_t operator()(const NodeKey& k) const {
    size_t h = 0;
    for (long x : k)
      h = h * 1000003u ^ std::hash<long>()(x);
    return h;
  }
};

// The parent element and lattice point a new node was made from, and where it lies.
struct Origin {
  long element;
  Lattice point;
  NodeKey key;
};

NodeKey edge_key(const Eigen::MatrixXi& C, long e, const Lattice& p, int axis) {
  Lattice lo = p, hi = p;
  lo[size_t(axis)] = 0, hi[size_t(axis)] = kD;
  long a = C(e, corner_at(lo)), b = C(e, corner_at(hi));
  long step = p[size_t(axis)];
  if (a > b)
    std::swap(a, b), step = kD - step;
  return {long(Where::edge), a, b, step, 0, 0, 0};
}

NodeKey face_key(const Eigen::MatrixXi& C, long e, const Lattice& p, int axis) {
  int f = 0;
  while (kCorner[kFace[f][0]][axis] * kD != p[size_t(axis)] ||
         kCorner[kFace[f][2]][axis] * kD != p[size_t(axis)])
    ++f;
  std::array<long, 4> g;
  for (size_t k = 0; k < 4; ++k)
    g[k] = C(e, kFace[f][k]);
  const size_t k = size_t(std::min_element(g.begin(), g.end()) - g.begin());
  size_t s = (k + 1) % 4, t = (k + 3) % 4;
  if (g[s] > g[t])
    std::swap(s, t);
  // Lattice distance from corner k towards corner n (they differ along one axis).
  auto towards = [&](size_t n) {
    const Lattice a = corner_point(kFace[f][k]), b = corner_point(kFace[f][n]);
    long d = 0;
    for (size_t i = 0; i < 3; ++i)
      if (a[i] != b[i])
        d = std::abs(p[i] - a[i]);
    return d;
  };
  return {long(Where::face), g[k], g[s], g[t], g[(k + 2) % 4], towards(s), towards(t)};
}

struct NewNodes {
  long first = 0;
  std::unordered_map<NodeKey, long, NodeKeyHash> index;
  std::vector<Origin> origin; // in order of creation

  // The node at lattice point p of element e: a corner, or a new node made once.
  long at(const Eigen::MatrixXi& C, long e, const Lattice& p) {
    int on_face[3], n_on = 0, free_axis = 0;
    for (int i = 0; i < 3; ++i) {
      const bool on = p[size_t(i)] == 0 || p[size_t(i)] == kD;
      if (on)
        on_face[n_on++] = i;
      else
        free_axis = i;
    }
    if (n_on == 3)
      return C(e, corner_at(p));
    const NodeKey key = n_on == 2   ? edge_key(C, e, p, free_axis)
                        : n_on == 1 ? face_key(C, e, p, on_face[0])
                                    : NodeKey{long(Where::inner), e, p[0], p[1], p[2], 0, 0};
    const auto [it, added] = index.emplace(key, first + long(origin.size()));
    if (added)
      origin.push_back({e, p, key});
    return it->second;
  }
};

// Trilinear weights of the reference cube's corners at lattice point p.
std::array<double, 8> trilinear_weights(const Lattice& p) {
  std::array<double, 8> w;
  for (int c = 0; c < 8; ++c) {
    double x = 1;
    for (size_t i = 0; i < 3; ++i) {
      const double s = double(p[i]) / kD;
      x *= kCorner[c][i] ? s : 1 - s;
    }
    w[size_t(c)] = x;
  }
  return w;
}

// ---- The steps of a pass ---------------------------------------------------------------------

void check_mesh_arguments(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C,
                          const std::vector<char>& boundary, const Eigen::VectorXd& values,
                          const char* who) {
  const std::string name(who);
  if (C.cols() != 8 || V.cols() != 3)
    throw std::invalid_argument(name + ": V must be #V by 3 and C #C by 8");
  if (C.size() > 0 && (C.minCoeff() < 0 || C.maxCoeff() >= V.rows()))
    throw std::invalid_argument(name + ": C refers to a node outside V");
  if (values.size() != V.rows() || !values.allFinite())
    throw std::invalid_argument(name + ": values must be #V finite numbers");
  if (boundary.size() != size_t(V.rows()))
    throw std::invalid_argument(name + ": boundary must have #V flags");
}

// Node -> elements (CSR).
void node_elements(const Eigen::MatrixXi& C, long nodes, std::vector<long>& start,
                   std::vector<long>& elements) {
  start.assign(size_t(nodes + 1), 0);
  for (long i = 0; i < C.size(); ++i)
    ++start[size_t(C.data()[i]) + 1];
  for (size_t v = 0; v < size_t(nodes); ++v)
    start[v + 1] += start[v];
  elements.resize(size_t(C.size()));
  std::vector<long> next(start.begin(), start.end() - 1);
  for (long e = 0; e < C.rows(); ++e)
    for (int j = 0; j < 8; ++j)
      elements[size_t(next[size_t(C(e, j))]++)] = e;
}

// The boundary facets whose nodes are all boundary nodes, and their edges (sorted node ids): where
// a new node goes onto F = 0.
struct BoundaryFaces {
  std::unordered_set<NodeKey, NodeKeyHash> faces, edges;

  BoundaryFaces(const Eigen::MatrixXi& C, const std::vector<char>& boundary) {
    const Eigen::MatrixXi B = boundary_facets(C);
    for (long r = 0; r < B.rows(); ++r) {
      bool on = true;
      for (int j = 0; j < 4; ++j)
        on = on && boundary[size_t(B(r, j))];
      if (!on)
        continue;
      std::array<long, 4> q = {B(r, 0), B(r, 1), B(r, 2), B(r, 3)};
      for (int j = 0; j < 4; ++j) {
        const auto [a, b] = std::minmax(q[size_t(j)], q[size_t((j + 1) % 4)]);
        edges.insert({a, b, 0, 0, 0, 0, 0});
      }
      std::sort(q.begin(), q.end());
      faces.insert({q[0], q[1], q[2], q[3], 0, 0, 0});
    }
  }

  bool holds(const NodeKey& k) const {
    if (k[0] == long(Where::edge))
      return edges.count({k[1], k[2], 0, 0, 0, 0, 0}) > 0;
    if (k[0] != long(Where::face))
      return false;
    std::array<long, 4> q = {k[1], k[2], k[3], k[4]};
    std::sort(q.begin(), q.end());
    return faces.count({q[0], q[1], q[2], q[3], 0, 0, 0}) > 0;
  }
};

// The element's corners as points.
void corners_of(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C, long e, Eigen::Vector3d p[8]) {
  for (int j = 0; j < 8; ++j)
    p[j] = V.row(C(e, j)).transpose();
}

// Valid as volume_quality counts it: every corner and the centre positive.
bool valid_hexahedron(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C, long e,
                      const Eigen::MatrixXi& T) {
  Eigen::Vector3d p[8];
  corners_of(V, C, e, p);
  return !detail::corner_scaled_jacobian(p, T).inverted && detail::centre_jacobian(p) > 0;
}

// The elements folded at a corner or at the centre (not valid_hexahedron).
long count_folded(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C, const Eigen::MatrixXi& T) {
  long n = 0;
  for (long e = 0; e < C.rows(); ++e)
    n += !valid_hexahedron(V, C, e, T);
  return n;
}

// The children of every element by its (closed) code; new nodes recorded in `made`.
std::vector<std::array<int, 8>> children(const Eigen::MatrixXi& C, const std::vector<char>& refined,
                                         NewNodes& made, long& split) {
  const Templates& T = templates();
  std::vector<std::array<int, 8>> out;
  out.reserve(size_t(C.rows()));
  for (long e = 0; e < C.rows(); ++e) {
    const TableEntry& entry = T.table[code_of(C, e, refined)];
    if (entry.kind == HexTemplate::none) {
      out.push_back({C(e, 0), C(e, 1), C(e, 2), C(e, 3), C(e, 4), C(e, 5), C(e, 6), C(e, 7)});
      continue;
    }
    if (entry.kind == HexTemplate::unsupported)
      throw std::logic_error("split_hexahedra: an element without a template after the closure");
    ++split;
    const Rotation& r = T.rotations[size_t(entry.rotation)];
    for (const Child& child : T.children(entry.kind)) {
      std::array<int, 8> h;
      for (size_t v = 0; v < 8; ++v)
        h[v] = int(made.at(C, e, rotate(r, child[v])));
      out.push_back(h);
    }
  }
  return out;
}

// The elements after the split: each hexahedron's template's children (1 when unchanged).
long hexahedra_after(const Eigen::MatrixXi& C, const std::vector<char>& refined) {
  const Templates& T = templates();
  long n = 0;
  for (long e = 0; e < C.rows(); ++e) {
    const HexTemplate kind = T.table[code_of(C, e, refined)].kind;
    n += kind == HexTemplate::none ? 1 : long(T.children(kind).size());
  }
  return n;
}

// The new nodes' positions and values: the trilinear map of their parents (C: the parents).
void append_nodes(const Eigen::MatrixXi& C, const NewNodes& made, Eigen::MatrixXd& V,
                  Eigen::VectorXd& values, std::vector<char>& boundary) {
  const long n0 = V.rows(), added = long(made.origin.size());
  V.conservativeResize(n0 + added, 3);
  values.conservativeResize(n0 + added);
  boundary.resize(size_t(n0 + added), 0);
  for (long k = 0; k < added; ++k) {
    const Origin& o = made.origin[size_t(k)];
    const std::array<double, 8> w = trilinear_weights(o.point);
    Eigen::RowVector3d x = Eigen::RowVector3d::Zero();
    double c = 0;
    for (int j = 0; j < 8; ++j)
      x += w[size_t(j)] * V.row(C(o.element, j)), c += w[size_t(j)] * values(C(o.element, j));
    V.row(n0 + k) = x;
    values(n0 + k) = c;
  }
}

// One max-min step of node n (open_centre_folds): the best of the trial positions, if better.
template <class Worst>
void improve_node(long n, const std::vector<long>& start, const std::vector<long>& elements,
                  const Eigen::MatrixXi& C, const Worst& worst_around, Eigen::MatrixXd& V) {
  const Eigen::RowVector3d at = V.row(n);
  Eigen::RowVector3d mean = Eigen::RowVector3d::Zero();
  double shortest = std::numeric_limits<double>::infinity();
  long count = 0;
  for (long k = start[size_t(n)]; k < start[size_t(n) + 1]; ++k)
    for (int j = 0; j < 8; ++j) {
      const long m = C(elements[size_t(k)], j);
      if (m == n)
        continue;
      mean += V.row(m), ++count;
      shortest = std::min(shortest, (V.row(m) - at).norm());
    }
  const Eigen::RowVector3d towards = (mean / double(count) - at).normalized();
  const Eigen::RowVector3d directions[7] = {towards,
                                            Eigen::RowVector3d::UnitX(),
                                            -Eigen::RowVector3d::UnitX(),
                                            Eigen::RowVector3d::UnitY(),
                                            -Eigen::RowVector3d::UnitY(),
                                            Eigen::RowVector3d::UnitZ(),
                                            -Eigen::RowVector3d::UnitZ()};
  double best = worst_around(n);
  Eigen::RowVector3d best_at = at;
  for (const Eigen::RowVector3d& d : directions)
    for (double s : {0.125, 0.25, 0.5}) {
      V.row(n) = at + s * shortest * d;
      const double w = worst_around(n);
      if (w > best)
        best = w, best_at = V.row(n);
    }
  V.row(n) = best_at;
}

// The smaller of element e's corner and centre scaled Jacobians (volume_quality's figure).
double min_scaled_jacobian(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C, long e,
                           const Eigen::MatrixXi& T) {
  Eigen::Vector3d p[8];
  corners_of(V, C, e, p);
  const std::array<Eigen::Vector3d, 3> x = detail::centre_axes(p);
  const double l = x[0].norm() * x[1].norm() * x[2].norm();
  return std::min(detail::corner_scaled_jacobian(p, T).min_scaled,
                  l > 0 ? x[0].cross(x[1]).dot(x[2]) / l : 0.0);
}

// Elements folded at their centre with every corner convex, which functional (15) does not see:
// each free node of such an element tries steps of 1/8, 1/4 and 1/2 of its shortest edge along
// the axes and towards its element neighbours' mean, keeping the one that most raises the worst
// scaled Jacobian around it (local max-min search), for a few sweeps.
void open_centre_folds(const Eigen::MatrixXi& C, const std::vector<char>& fixed,
                       const Eigen::MatrixXi& T, Eigen::MatrixXd& V) {
  constexpr int kSweeps = 10;
  std::vector<long> start, elements;
  node_elements(C, V.rows(), start, elements);
  auto worst_around = [&](long n) {
    double w = 1;
    for (long k = start[size_t(n)]; k < start[size_t(n) + 1]; ++k)
      w = std::min(w, min_scaled_jacobian(V, C, elements[size_t(k)], T));
    return w;
  };
  for (int sweep = 0; sweep < kSweeps; ++sweep) {
    std::vector<long> nodes; // the free nodes of folded elements
    for (long e = 0; e < C.rows(); ++e)
      if (!valid_hexahedron(V, C, e, T))
        for (int j = 0; j < 8; ++j)
          if (!fixed[size_t(C(e, j))])
            nodes.push_back(C(e, j));
    if (nodes.empty())
      return;
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    for (long n : nodes)
      improve_node(n, start, elements, C, worst_around, V);
  }
}

// Element layers around the nodes whose elements the refinement untangles again (a patch).
constexpr int kPatchRings = 3;

// The elements within `rings` element layers of the seed nodes, renumbered (elements_at):
// `free` flags the nodes reached through them (every element at such a node is in the patch).
struct Patch : detail::SubMesh {
  std::vector<long> local; // mesh node -> patch node, or -1
  std::vector<char> free;
};

Patch patch_around(const Eigen::MatrixXi& C, long nodes, const std::vector<long>& seeds,
                   int rings) {
  std::vector<long> start, elements;
  node_elements(C, nodes, start, elements);
  std::vector<char> reached(size_t(nodes), 0);
  std::vector<long> frontier = seeds;
  for (long n : seeds)
    reached[size_t(n)] = 1;
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<long> next;
    for (long n : frontier)
      for (long k = start[size_t(n)]; k < start[size_t(n) + 1]; ++k)
        for (int j = 0; j < 8; ++j)
          if (!reached[size_t(C(elements[size_t(k)], j))])
            reached[size_t(C(elements[size_t(k)], j))] = 1,
                                                  next.push_back(C(elements[size_t(k)], j));
    frontier = std::move(next);
  }
  Patch p;
  static_cast<detail::SubMesh&>(p) = detail::elements_at(C, reached);
  p.local.assign(size_t(nodes), -1);
  for (size_t k = 0; k < p.node.size(); ++k)
    p.local[size_t(p.node[k])] = long(k), p.free.push_back(reached[size_t(p.node[k])]);
  return p;
}

// Flags (#nodes) the nodes of C's boundary facets.
std::vector<char> facet_nodes(const Eigen::MatrixXi& C, long nodes) {
  std::vector<char> on(size_t(nodes), 0);
  const Eigen::MatrixXi B = boundary_facets(C);
  for (long i = 0; i < B.size(); ++i)
    on[size_t(B.data()[i])] = 1;
  return on;
}

// The nodes of the elements folded at a corner or at the centre.
std::vector<long> folded_nodes(const Eigen::MatrixXi& C, const Eigen::MatrixXi& T,
                               const Eigen::MatrixXd& V) {
  std::vector<long> nodes;
  for (long e = 0; e < C.rows(); ++e)
    if (!valid_hexahedron(V, C, e, T))
      nodes.insert(nodes.end(), C.row(e).begin(), C.row(e).end());
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

// Children folded by a nearly flat parent's trilinear map (pillows at creases: the map folds
// inside though its corners do not) untangled: the free nodes near them move, every node on the
// boundary facets stays. A child whose boundary face is itself folded stays folded so (the valve
// at 0.2): the patch around those is untangled again with the facets' nodes sliding on F = 0. A
// parent whose boundary face is a sliver along a crease (the car at 0.3) has children folded on
// F = 0 whichever way its nodes slide: there the new nodes (from `first_new` on) of the facets
// move off F = 0 too, and the projection holds them where they keep their elements valid.
// Counts rep.folded, rep.still_folded.
void untangle_children(const ImplicitFunction& f, const Eigen::MatrixXi& C, long first_new,
                       Eigen::MatrixXd& V, RefinementReport& rep) {
  const Eigen::MatrixXi T = corner_table(8);
  rep.folded = count_folded(V, C, T);
  if (rep.folded == 0)
    return;
  const std::vector<char> fixed = facet_nodes(C, V.rows());
  detail::untangle_hexahedra(C, fixed, 0, V);
  open_centre_folds(C, fixed, T, V);
  std::vector<long> nodes = folded_nodes(C, T, V);
  if (!nodes.empty() && f.value) {
    const Patch patch = patch_around(C, V.rows(), nodes, kPatchRings);
    Eigen::MatrixXd W = V(patch.node, Eigen::all);
    std::vector<char> held(patch.node.size()), slides(patch.node.size());
    for (size_t k = 0; k < patch.node.size(); ++k) {
      held[k] = fixed[size_t(patch.node[k])] || !patch.free[k];
      slides[k] = fixed[size_t(patch.node[k])] && patch.free[k];
    }
    const SlidingSurface surface = detail::implicit_surface(f, detail::mean_edge(W, patch.C), 0);
    detail::untangle_hexahedra(patch.C, held, surface, slides, 0, W);
    open_centre_folds(patch.C, held, T, W);
    V(patch.node, Eigen::all) = W;
    nodes = folded_nodes(C, T, V);
  }
  if (!nodes.empty()) { // the max-min search alone: functional (15) drifts free facet nodes
    std::vector<char> held = fixed;
    std::fill(held.begin() + first_new, held.end(), 0);
    open_centre_folds(C, held, T, V);
  }
  rep.still_folded = count_folded(V, C, T);
}

// Where the new boundary nodes go on F = 0: node n's projection is P.row(at[n]) (-1: none).
struct Projections {
  std::vector<long> at; // #V
  const Eigen::MatrixXd& P;
  Eigen::RowVector3d of(long n) const { return P.row(at[size_t(n)]); }
};

// Held nodes given a second chance: the full step onto F = 0, then the free nodes (not `fixed`:
// the facets' nodes) of its elements moved by the max-min search (improve_node, a few rounds);
// kept when every element around the moved nodes is valid, else undone. Returns the nodes still
// held.
std::vector<long> release_held(const std::vector<long>& held, const Projections& to,
                               const std::vector<char>& fixed, const Eigen::MatrixXi& C,
                               const Eigen::MatrixXi& T, Eigen::MatrixXd& V) {
  constexpr int kRounds = 5;
  std::vector<long> start, elements, still;
  node_elements(C, V.rows(), start, elements);
  auto worst_around = [&](long n) {
    double w = 1;
    for (long k = start[size_t(n)]; k < start[size_t(n) + 1]; ++k)
      w = std::min(w, min_scaled_jacobian(V, C, elements[size_t(k)], T));
    return w;
  };
  for (long n : held) {
    std::vector<long> nodes = {n}; // n, then the free nodes of its elements
    for (long k = start[size_t(n)]; k < start[size_t(n) + 1]; ++k)
      for (int j = 0; j < 8; ++j)
        if (!fixed[size_t(C(elements[size_t(k)], j))])
          nodes.push_back(C(elements[size_t(k)], j));
    std::sort(nodes.begin() + 1, nodes.end());
    nodes.erase(std::unique(nodes.begin() + 1, nodes.end()), nodes.end());
    Eigen::MatrixXd saved(long(nodes.size()), 3);
    for (size_t i = 0; i < nodes.size(); ++i)
      saved.row(long(i)) = V.row(nodes[i]);
    V.row(n) = to.of(n);
    for (int round = 0; round < kRounds; ++round)
      for (size_t i = 1; i < nodes.size(); ++i)
        if (worst_around(nodes[i]) <= 0)
          improve_node(nodes[i], start, elements, C, worst_around, V);
    bool ok = true;
    for (long m : nodes)
      for (long k = start[size_t(m)]; ok && k < start[size_t(m) + 1]; ++k)
        ok = valid_hexahedron(V, C, elements[size_t(k)], T);
    if (ok)
      continue;
    for (size_t i = 0; i < nodes.size(); ++i)
      V.row(nodes[i]) = saved.row(long(i));
    still.push_back(n);
  }
  return still;
}

// The patch of the mesh V (`saved`) untangled, its nodes' new places in W: its free `held` nodes
// not in `stays` start on F = 0 (`to`), then free nodes move and the facets' nodes on F = 0 slide
// on it (untangle_hexahedra); with `restore`, the nodes of elements still folded then go back
// (restore_folded). Elements folded in W that were valid in V flag their nodes in `bad`; returns
// their number.
long untangle_patch(const SlidingSurface& surface, const std::vector<char>& held,
                    const Projections& to, const Patch& patch, const std::vector<char>& on_facet,
                    const std::vector<char>& on_zero, const std::vector<char>& stays,
                    const Eigen::MatrixXd& saved, bool restore, const Eigen::MatrixXi& T,
                    Eigen::MatrixXd& W, std::vector<char>& bad) {
  const long m = long(patch.node.size());
  const Eigen::MatrixXd before = saved(patch.node, Eigen::all);
  W = before;
  std::vector<char> fixed(size_t(m), 0), slides(size_t(m), 0);
  for (long k = 0; k < m; ++k) {
    const size_t n = size_t(patch.node[size_t(k)]);
    fixed[size_t(k)] = on_facet[n] || !patch.free[size_t(k)];
    slides[size_t(k)] = on_facet[n] && patch.free[size_t(k)] && on_zero[n];
    if (held[n] && patch.free[size_t(k)] && !stays[n])
      W.row(k) = to.of(long(n)), slides[size_t(k)] = 1;
  }
  detail::untangle_hexahedra(patch.C, fixed, surface, slides, 0, W);
  if (restore)
    detail::restore_folded(before, patch.free, patch.C, 0, W);
  long folded = 0;
  for (long e = 0; e < patch.C.rows(); ++e)
    if (!valid_hexahedron(W, patch.C, e, T) && valid_hexahedron(before, patch.C, e, T)) {
      ++folded;
      for (int j = 0; j < 8; ++j)
        bad[size_t(patch.node[size_t(patch.C(e, j))])] = 1;
    }
  return folded;
}

// Nodes still held put onto F = 0 after all (`to`) and the patch of kPatchRings element layers
// around them untangled as the pillows are (untangle_patch; `on_facet`: the facets' nodes). Where
// an element stays folded, the patch is tried again from V with that element's held nodes held (at
// most kTries times, the last putting the folded elements' nodes back instead). Returns the nodes
// short of F = 0.
std::vector<long> untangle_held(const ImplicitFunction& f, const std::vector<long>& held,
                                const Projections& to, const std::vector<char>& on_facet,
                                const std::vector<char>& on_zero, const Eigen::MatrixXi& C,
                                const Eigen::MatrixXi& T, Eigen::MatrixXd& V) {
  constexpr int kTries = 2;
  if (held.empty())
    return held;
  std::vector<char> is_held(size_t(V.rows()), 0), stays(size_t(V.rows()), 0);
  for (long n : held)
    is_held[size_t(n)] = 1;
  const Patch patch = patch_around(C, V.rows(), held, kPatchRings);
  Eigen::MatrixXd W = V(patch.node, Eigen::all);
  const SlidingSurface surface = detail::implicit_surface(f, detail::mean_edge(W, patch.C), 0);
  for (int attempt = 0; attempt < kTries; ++attempt) {
    std::vector<char> bad(size_t(V.rows()), 0);
    const long folded = untangle_patch(surface, is_held, to, patch, on_facet, on_zero, stays, V,
                                       attempt + 1 == kTries, T, W, bad);
    if (folded == 0) {
      std::vector<long> still;
      for (long n : held)
        if (W.row(patch.local[size_t(n)]) == V.row(n)) // not tried, or put back
          still.push_back(n);
      V(patch.node, Eigen::all) = W;
      return still;
    }
    for (size_t n = 0; n < bad.size(); ++n)
      stays[n] = stays[n] || bad[n];
  }
  return held;
}

// New nodes on boundary facets (rows k of made.origin in `project`) onto F = 0: a gradient walk in
// steps of a quarter of a third of the parent's mean edge, then each placed as far as folds none of
// its valid elements (C: the children). Flags the nodes that reached F = 0 or were held short of it
// (rep.projected, rep.held, rep.held_nodes).
void project_new_nodes(const ImplicitFunction& f, const Eigen::MatrixXi& parents,
                       const Eigen::MatrixXi& C, const NewNodes& made,
                       const std::vector<long>& project, Eigen::MatrixXd& V,
                       std::vector<char>& boundary, RefinementReport& rep) {
  Eigen::MatrixXd P(long(project.size()), 3);
  Eigen::VectorXd h(P.rows());
  for (size_t r = 0; r < project.size(); ++r) {
    P.row(long(r)) = V.row(made.first + project[r]);
    h(long(r)) = detail::mean_edge(V, parents, made.origin[size_t(project[r])].element) / 12;
  }
  std::vector<char> moved;
  project_by_gradient_walk(f, P, h, 100, {}, &moved);
  const Eigen::MatrixXi T = corner_table(8);
  const std::vector<long> held = detail::place_projected(
      C, made.first, project, P, moved, V,
      [&C, &T](const Eigen::MatrixXd& W, long e) { return valid_hexahedron(W, C, e, T); });
  for (size_t r = 0; r < project.size(); ++r) {
    boundary[size_t(made.first + project[r])] = moved[r];
    rep.projected += moved[r];
  }
  if (!held.empty()) {
    Projections to{std::vector<long>(size_t(V.rows()), -1), P};
    for (size_t r = 0; r < project.size(); ++r)
      to.at[size_t(made.first + project[r])] = long(r);
    const std::vector<char> on_facet = facet_nodes(C, V.rows());
    rep.held_nodes = untangle_held(f, release_held(held, to, on_facet, C, T, V), to, on_facet,
                                   boundary, C, T, V);
  }
  rep.held = long(rep.held_nodes.size());
}

} // namespace

HexTemplate hex_template(unsigned code) {
  if (code > 0xFFu)
    throw std::invalid_argument("hex_template: a code has 8 bits");
  return template_of_edges(refined_edges(code));
}

long close_refined_nodes(const Eigen::MatrixXi& C, std::vector<char>& refined) {
  if (C.cols() != 8)
    throw std::invalid_argument("close_refined_nodes: C must be #C by 8");
  if (C.size() > 0 && (C.minCoeff() < 0 || size_t(C.maxCoeff()) >= refined.size()))
    throw std::invalid_argument("close_refined_nodes: refined must have a flag per node");
  const Templates& T = templates();
  std::vector<long> start, elements;
  node_elements(C, long(refined.size()), start, elements);
  std::deque<long> queue;
  std::vector<char> queued(size_t(C.rows()), 0);
  for (long e = 0; e < C.rows(); ++e)
    if (code_of(C, e, refined) != 0)
      queue.push_back(e), queued[size_t(e)] = 1;
  long added = 0;
  while (!queue.empty()) { // an element widened puts the elements of its new nodes back
    const long e = queue.front();
    queue.pop_front();
    queued[size_t(e)] = 0;
    const unsigned code = code_of(C, e, refined), closed = T.table[code].closed;
    for (int j = 0; j < 8; ++j) {
      const size_t n = size_t(C(e, j));
      if (!(closed >> j & 1u) || refined[n])
        continue;
      refined[n] = 1, ++added;
      for (long k = start[n]; k < start[n + 1]; ++k)
        if (!queued[size_t(elements[size_t(k)])])
          queue.push_back(elements[size_t(k)]), queued[size_t(elements[size_t(k)])] = 1;
    }
  }
  return added;
}

RefinementReport split_hexahedra(Eigen::MatrixXd& V, Eigen::MatrixXi& C,
                                 std::vector<char>& boundary, Eigen::VectorXd& values,
                                 std::vector<char> refined, const ImplicitFunction& f,
                                 long max_elements) {
  check_mesh_arguments(V, C, boundary, values, "split_hexahedra");
  if (refined.size() != size_t(V.rows()))
    throw std::invalid_argument("split_hexahedra: refined must have #V flags");
  RefinementReport rep;
  rep.widened = close_refined_nodes(C, refined);
  rep.refined_nodes = std::count_if(refined.begin(), refined.end(), [](char r) { return r != 0; });
  detail::check_element_count(hexahedra_after(C, refined), max_elements, "split_hexahedra");
  NewNodes made;
  made.first = V.rows();
  const std::vector<std::array<int, 8>> out = children(C, refined, made, rep.split);
  rep.new_nodes = long(made.origin.size());
  append_nodes(C, made, V, values, boundary);
  std::vector<long> project; // rows of made.origin on boundary facets
  if (f.value) {
    const BoundaryFaces on_surface(C, boundary);
    for (size_t k = 0; k < made.origin.size(); ++k)
      if (on_surface.holds(made.origin[k].key))
        project.push_back(long(k));
  }
  const Eigen::MatrixXi parents = C;
  C.resize(long(out.size()), 8);
  for (size_t e = 0; e < out.size(); ++e)
    for (int j = 0; j < 8; ++j)
      C(long(e), j) = out[e][size_t(j)];
  untangle_children(f, C, made.first, V, rep);
  if (!project.empty())
    project_new_nodes(f, parents, C, made, project, V, boundary, rep);
  if (rep.still_folded > 0) // the projection's untangling may have opened some; it folds none
    rep.still_folded = count_folded(V, C, corner_table(8));
  return rep;
}

RefinementReport refine_hexahedra(Eigen::MatrixXd& V, Eigen::MatrixXi& C,
                                  std::vector<char>& boundary, Eigen::VectorXd& values,
                                  double delta, const ImplicitFunction& f, long max_elements) {
  check_mesh_arguments(V, C, boundary, values, "refine_hexahedra");
  if (!(delta >= 0 && delta < 1))
    throw std::invalid_argument("refine_hexahedra: delta must be in [0, 1)");
  long flagged = 0;
  std::vector<char> refined =
      refined_nodes(C, refinement_indicator(C, values), delta, V.rows(), &flagged);
  if (flagged == 0)
    return {};
  RefinementReport rep =
      split_hexahedra(V, C, boundary, values, std::move(refined), f, max_elements);
  rep.flagged = flagged;
  return rep;
}

std::vector<RefinementReport> adapt_hexahedra(
    Eigen::MatrixXd& V, Eigen::MatrixXi& C, std::vector<char>& boundary,
    const std::function<Eigen::VectorXd(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C)>& field,
    double delta, int iterations, const ImplicitFunction& f, long max_elements) {
  if (iterations < 0)
    throw std::invalid_argument("adapt_hexahedra: iterations must be >= 0");
  std::vector<RefinementReport> reports;
  for (int it = 0; it < iterations; ++it) {
    Eigen::VectorXd values = field(V, C);
    const Eigen::MatrixXd V0 = V;
    const Eigen::MatrixXi C0 = C;
    const std::vector<char> boundary0 = boundary;
    reports.push_back(refine_hexahedra(V, C, boundary, values, delta, f, max_elements));
    if (reports.back().still_folded > 0) { // a valid mesh of fewer passes, not a folded one
      V = V0, C = C0, boundary = boundary0;
      reports.back().undone = true;
      break;
    }
    if (reports.back().flagged == 0)
      break;
  }
  return reports;
}

} // namespace interlin
