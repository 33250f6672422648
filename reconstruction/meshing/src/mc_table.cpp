// The marching-cubes table from first principles. For each case and sub-case: on every cube face
// the sign changes give one or two segments (two on an ambiguous face, paired by the sub-case
// bit), each directed so that the inside corners lie on its right seen from outside the cube;
// the segments chain into closed loops on the cube surface, and each loop is triangulated as a
// disk. Because every face is decided from its own four values, neighbouring cubes produce the
// same segments on their common face and the surface is closed and 2-manifold.
//
// Loop triangulation: the triangulation of the polygon that maximises its smallest angle (exact
// dynamic programming) with the crossing points at the edge midpoints. A diagonal between two
// points of one cube face (possible only on an ambiguous face, which holds four points) could be
// chosen by the neighbouring cube as well, and the edge would then have four triangles. So each
// ambiguous face is given to exactly one of its two cubes, which alone may cut across it: by the
// face's axis and by whether its corner at the lower ends of the other two axes is inside, both
// of which the two cubes see alike (kFaceOwner). Without such diagonals 116 loops (in 24 cases,
// e.g. two opposite ambiguous faces, one connected and one not) have no triangulation; with them
// every loop of every case and sub-case has one. kFaceOwner is the first assignment, in binary
// order of the six entries, for which that holds (an exhaustive search over the 64 assignments);
// build() re-checks it every time the table is generated.
#include "mc_table.h"
#include "min_angle.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace interlin::detail {

namespace {

Eigen::Vector3d corner_point(int c) {
  return {double(c & 1), double((c >> 1) & 1), double(c >> 2)};
}

// The two axes other than a, increasing.
void other_axes(int a, int& b, int& d) {
  b = a == 0 ? 1 : 0;
  d = a == 2 ? 1 : 2;
}

int corner_of(int a, int ca, int b, int cb, int d, int cd) {
  int xyz[3];
  xyz[a] = ca;
  xyz[b] = cb;
  xyz[d] = cd;
  return xyz[0] + 2 * xyz[1] + 4 * xyz[2];
}

struct Geometry {
  int edge_corner[12][2];
  int face_corner[6][4];
  int face_edge[6][4]; // edge between face_corner[i] and face_corner[i+1]
  int edge_faces[12][2];
  Eigen::Vector3d mid[12];

  Geometry() {
    for (int e = 0; e < 12; ++e) {
      const int a = e / 4, u = e & 1, v = (e >> 1) & 1;
      int b, d;
      other_axes(a, b, d);
      edge_corner[e][0] = corner_of(a, 0, b, u, d, v);
      edge_corner[e][1] = corner_of(a, 1, b, u, d, v);
      mid[e] = 0.5 * (corner_point(edge_corner[e][0]) + corner_point(edge_corner[e][1]));
    }
    const int cyc[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int f = 0; f < 6; ++f) {
      const int a = f / 2, s = f & 1;
      int b, d;
      other_axes(a, b, d);
      for (int i = 0; i < 4; ++i)
        face_corner[f][i] = corner_of(a, s, b, cyc[i][0], d, cyc[i][1]);
      for (int i = 0; i < 4; ++i)
        face_edge[f][i] = edge_between(face_corner[f][i], face_corner[f][(i + 1) % 4]);
    }
    int count[12] = {};
    for (int f = 0; f < 6; ++f)
      for (int i = 0; i < 4; ++i) {
        const int e = face_edge[f][i];
        edge_faces[e][count[e]++] = f;
      }
  }

  int edge_between(int c1, int c2) const {
    for (int e = 0; e < 12; ++e)
      if ((edge_corner[e][0] == c1 && edge_corner[e][1] == c2) ||
          (edge_corner[e][0] == c2 && edge_corner[e][1] == c1))
        return e;
    throw std::logic_error("mc_table: corners are not adjacent");
  }

  // The face holding both edges, or -1.
  int common_face(int e1, int e2) const {
    for (int x : edge_faces[e1])
      for (int y : edge_faces[e2])
        if (x == y)
          return x;
    return -1;
  }
};

// kFaceOwner[a][c]: the side s (face 2a + s of the owning cube) of an ambiguous face along axis a
// whose corner at (0, 0) in the other two coordinates is inside (c = 1) or not (c = 0).
constexpr int kFaceOwner[3][2] = {{0, 1}, {1, 0}, {0, 0}};

// Max-min-angle triangulation of the loop (cube edges in order) cutting across no face f with
// may_cut[f] false. Appends triangles (i, k, j) in loop order, i < k < j.
void triangulate_loop(const Geometry& g, const std::vector<int>& loop, std::vector<int>& tris,
                      const bool may_cut[6]) {
  const int n = int(loop.size());
  if (n < 3)
    throw std::logic_error("mc_table: loop with fewer than 3 points");
  auto allowed = [&](int i, int j) {
    if (j == i + 1 || (i == 0 && j == n - 1))
      return true;
    const int f = g.common_face(loop[size_t(i)], loop[size_t(j)]);
    return f < 0 || may_cut[f];
  };
  std::vector<double> best(size_t(n * n), -1.0);
  std::vector<int> split(size_t(n * n), -1);
  for (int i = 0; i + 1 < n; ++i)
    best[size_t(i * n + i + 1)] = M_PI; // a polygon edge: no triangle, no constraint
  for (int len = 2; len < n; ++len)
    for (int i = 0; i + len < n; ++i) {
      const int j = i + len;
      if (!allowed(i, j))
        continue;
      for (int k = i + 1; k < j; ++k) {
        const double l = best[size_t(i * n + k)], r = best[size_t(k * n + j)];
        if (l < 0 || r < 0)
          continue;
        const double q = std::min(
            {l, r,
             min_angle(g.mid[loop[size_t(i)]], g.mid[loop[size_t(k)]], g.mid[loop[size_t(j)]])});
        if (q > best[size_t(i * n + j)]) {
          best[size_t(i * n + j)] = q;
          split[size_t(i * n + j)] = k;
        }
      }
    }
  if (best[size_t(n - 1)] < 0)
    throw std::logic_error("mc_table: no admissible loop triangulation");
  std::vector<std::pair<int, int>> stack{{0, n - 1}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (j - i < 2)
      continue;
    const int k = split[size_t(i * n + j)];
    tris.insert(tris.end(), {loop[size_t(i)], loop[size_t(k)], loop[size_t(j)]});
    stack.push_back({i, k});
    stack.push_back({k, j});
  }
}

// Triangles of one case and sub-case (cube edges, 3 per triangle).
std::vector<int> triangulate_case(const Geometry& g, int code, int sub, std::uint8_t ambiguous) {
  auto inside = [&](int c) { return ((code >> c) & 1) != 0; };
  int next[12];
  std::fill(next, next + 12, -1);
  auto add_segment = [&](int e1, int e2, int test_corner, int f) {
    // Inside corners on the right of the directed segment seen from outside the cube.
    const Eigen::Vector3d n = (f & 1 ? 1.0 : -1.0) * Eigen::Vector3d::Unit(f / 2);
    const double side = (g.mid[e2] - g.mid[e1]).cross(corner_point(test_corner) - g.mid[e1]).dot(n);
    const bool left = side > 0;
    const int from = left != inside(test_corner) ? e1 : e2, to = from == e1 ? e2 : e1;
    if (next[from] >= 0)
      throw std::logic_error("mc_table: two segments leave one edge");
    next[from] = to;
  };
  int bit = 0;
  for (int f = 0; f < 6; ++f) {
    const int* q = g.face_corner[f];
    const int* fe = g.face_edge[f];
    std::vector<int> cross;
    for (int i = 0; i < 4; ++i)
      if (inside(q[i]) != inside(q[(i + 1) % 4]))
        cross.push_back(i);
    if (cross.size() == 2) {
      const int i = cross[0], j = cross[1];
      // Adjacent crossing edges cut off their common corner; opposite ones halve the face.
      const int test = j == i + 1 ? q[j] : q[0]; // q[0] also serves the edge pair (3, 0)
      add_segment(fe[i], fe[j], test, f);
    } else if (cross.size() == 4) {
      if (!((ambiguous >> f) & 1))
        throw std::logic_error("mc_table: unexpected ambiguous face");
      const bool connected = ((sub >> bit++) & 1) != 0;
      // Connected inside corners: the segments cut off the outside corners, else the inside.
      for (int k = 0; k < 4; ++k)
        if (inside(q[k]) != connected)
          add_segment(fe[(k + 3) % 4], fe[k], q[k], f);
    }
  }
  bool may_cut[6];
  for (int f = 0; f < 6; ++f)
    may_cut[f] =
        ((ambiguous >> f) & 1) && kFaceOwner[f / 2][inside(g.face_corner[f][0])] == (f & 1);
  std::vector<int> tris;
  bool used[12] = {};
  for (int e = 0; e < 12; ++e) {
    if (next[e] < 0 || used[e])
      continue;
    std::vector<int> loop;
    for (int x = e; !used[x]; x = next[x]) {
      if (next[x] < 0)
        throw std::logic_error("mc_table: open loop");
      used[x] = true;
      loop.push_back(x);
    }
    triangulate_loop(g, loop, tris, may_cut);
  }
  return tris;
}

McTable build() {
  const Geometry g;
  McTable t;
  for (int f = 0; f < 6; ++f)
    for (int i = 0; i < 4; ++i)
      t.face_corner[f][i] = g.face_corner[f][i];
  for (int e = 0; e < 12; ++e)
    for (int i = 0; i < 2; ++i)
      t.edge_corner[e][i] = g.edge_corner[e][i];
  t.start.push_back(0);
  for (int code = 0; code < 256; ++code) {
    std::uint8_t amb = 0;
    int bits = 0;
    for (int f = 0; f < 6; ++f) {
      const int* q = g.face_corner[f];
      const bool a = (code >> q[0]) & 1, b = (code >> q[1]) & 1, c = (code >> q[2]) & 1,
                 d = (code >> q[3]) & 1;
      if (a == c && b == d && a != b) {
        amb = std::uint8_t(amb | (1 << f));
        ++bits;
      }
    }
    t.ambiguous[code] = amb;
    t.first[code] = std::uint32_t(t.start.size() - 1);
    for (int sub = 0; sub < (1 << bits); ++sub) {
      const std::vector<int> tris = triangulate_case(g, code, sub, amb);
      for (int e : tris)
        t.edges.push_back(std::uint8_t(e));
      t.start.push_back(std::uint32_t(t.edges.size() / 3));
      t.max_triangles = std::max(t.max_triangles, int(tris.size() / 3));
    }
  }
  return t;
}

} // namespace

const McTable& mc_table() {
  static const McTable table = build();
  return table;
}

} // namespace interlin::detail
