// Seed 003's adaptive refinement of hexahedra (digest §7.2, §11.6): the templates (edge, face,
// full) on a cube, a parallelepiped and a general hexahedron; the closure on random refined-node
// sets of a structured grid (conforming, volume and boundary area kept, nothing inverted); the
// indicator's worked value; the adaptive loop on a front; new boundary nodes on F = 0.
#include "interlin/interflatation/load_implicit.h"
#include "interlin/reconstruction/meshing/boundary_mesh.h"
#include "interlin/reconstruction/meshing/hexahedral_refinement.h"
#include "interlin/reconstruction/meshing/mesh_check.h"
#include "interlin/reconstruction/meshing/volume_mesh.h"
#include "interlin/reconstruction/meshing/volume_quality.h"

#include "car_sliver_pillows.h"
#include "support/test_implicits.h"
#include "valve_thin_wall_children.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <sstream>
#include <vector>

using namespace interlin;

namespace {

constexpr int kHexFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                 {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
constexpr int kHexEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                  {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};

// The unit cube as n^3 hexahedra (VTK order).
void hex_grid(int n, Eigen::MatrixXd& V, Eigen::MatrixXi& C) {
  auto id = [n](int i, int j, int k) { return i + (n + 1) * (j + (n + 1) * k); };
  V.resize((n + 1) * (n + 1) * (n + 1), 3);
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        V.row(id(i, j, k)) << double(i) / n, double(j) / n, double(k) / n;
  C.resize(n * n * n, 8);
  long e = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i, ++e)
        C.row(e) << id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k),
            id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1);
}

// Faces by their sorted node ids -> how many elements use them, and one use's node order.
std::map<std::array<int, 4>, std::pair<int, std::array<int, 4>>>
face_uses(const Eigen::MatrixXi& C) {
  std::map<std::array<int, 4>, std::pair<int, std::array<int, 4>>> uses;
  for (long e = 0; e < C.rows(); ++e)
    for (const auto& f : kHexFaces) {
      const std::array<int, 4> q = {C(e, f[0]), C(e, f[1]), C(e, f[2]), C(e, f[3])};
      std::array<int, 4> key = q;
      std::sort(key.begin(), key.end());
      auto& u = uses[key];
      ++u.first;
      u.second = q;
    }
  return uses;
}

double quad_area(const Eigen::MatrixXd& V, const std::array<int, 4>& q) {
  const Eigen::Vector3d a = V.row(q[0]), b = V.row(q[1]), c = V.row(q[2]), d = V.row(q[3]);
  return 0.5 * (c - a).cross(d - b).norm(); // exact for a planar quadrilateral
}

struct Conformity {
  long overused = 0;    // faces used by more than two elements
  double open_area = 0; // faces used once
};

Conformity conformity(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C) {
  Conformity c;
  for (const auto& [key, use] : face_uses(C)) {
    c.overused += use.first > 2;
    if (use.first == 1)
      c.open_area += quad_area(V, use.second);
  }
  return c;
}

// Faces used once whose nodes do not all lie on one face of the unit cube (a hanging node's
// unmatched faces inside).
long inner_open_faces(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C) {
  long bad = 0;
  for (const auto& [key, use] : face_uses(C)) {
    if (use.first != 1)
      continue;
    bool on_a_side = false;
    for (int axis = 0; axis < 3; ++axis)
      for (double side : {0.0, 1.0}) {
        bool all = true;
        for (int n : key)
          all = all && std::abs(V(n, axis) - side) < 1e-14;
        on_a_side = on_a_side || all;
      }
    bad += !on_a_side;
  }
  return bad;
}

double hex_area(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C) {
  return conformity(V, C).open_area;
}

struct SplitResult {
  Eigen::MatrixXd V;
  Eigen::MatrixXi C;
  RefinementReport report;
};

// One hexahedron P (8 by 3) split with the local vertices in `refined` refined.
SplitResult split_one(const Eigen::MatrixXd& P, const std::vector<int>& refined) {
  SplitResult r{P, Eigen::MatrixXi(1, 8), {}};
  r.C << 0, 1, 2, 3, 4, 5, 6, 7;
  std::vector<char> b(8, 0), flags(8, 0);
  for (int v : refined)
    flags[size_t(v)] = 1;
  Eigen::VectorXd values = Eigen::VectorXd::Zero(8);
  r.report = split_hexahedra(r.V, r.C, b, values, flags);
  return r;
}

Eigen::MatrixXd unit_cube() {
  Eigen::MatrixXd P(8, 3);
  P << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
  return P;
}

// A mesh fixture (car_sliver_pillows.h): rows x y z boundary, then 8 node ids per hexahedron.
void read_fixture(const char* text, long nodes, long elements, Eigen::MatrixXd& V,
                  Eigen::MatrixXi& C, std::vector<char>& boundary) {
  std::istringstream in(text);
  V.resize(nodes, 3), C.resize(elements, 8), boundary.assign(size_t(nodes), 0);
  for (long v = 0; v < nodes; ++v) {
    int on = 0;
    in >> V(v, 0) >> V(v, 1) >> V(v, 2) >> on;
    boundary[size_t(v)] = char(on);
  }
  for (long e = 0; e < elements; ++e)
    for (int j = 0; j < 8; ++j)
      in >> C(e, j);
  REQUIRE(in);
  REQUIRE(C.maxCoeff() < nodes);
}

} // namespace

TEST_CASE("hex_template: the 256-entry table", "[volume][adapt][hex]") {
  long edge = 0, face = 0, none = 0;
  for (unsigned code = 0; code < 256; ++code) {
    const HexTemplate t = hex_template(code);
    edge += t == HexTemplate::edge, face += t == HexTemplate::face, none += t == HexTemplate::none;
  }
  // none: the cube's independent vertex sets (1 + 8 + 16 + 8 + 2); edge: an edge alone or with
  // one of the two vertices adjacent to neither end (they are adjacent to each other), 12 x 3;
  // face: exactly a face's 4 vertices.
  CHECK(none == 35);
  CHECK(edge == 36);
  CHECK(face == 6);
  CHECK(hex_template(0xFF) == HexTemplate::full);
  CHECK(hex_template(0x03) == HexTemplate::edge);
  CHECK(hex_template(0x0F) == HexTemplate::face);
  CHECK(hex_template(0x07) == HexTemplate::unsupported); // two edges of a face
  CHECK_THROWS_AS(hex_template(256), std::invalid_argument);
}

TEST_CASE("split_hexahedra: every template on a cube, a parallelepiped and a general hexahedron",
          "[volume][adapt][hex]") {
  Eigen::Matrix3d A; // a shear and stretch: faces stay planar, the map affine
  A << 1.3, 0.4, -0.2, 0.1, 0.8, 0.3, -0.15, 0.2, 1.1;
  const Eigen::MatrixXd cube = unit_cube(), affine = cube * A.transpose();
  Eigen::MatrixXd general = cube; // corners moved by up to 0.25: warped faces
  general.row(1) += Eigen::RowVector3d(0.2, -0.1, 0.05);
  general.row(6) += Eigen::RowVector3d(0.1, 0.25, 0.2);
  general.row(4) += Eigen::RowVector3d(-0.15, 0.05, 0.1);
  general.row(3) += Eigen::RowVector3d(0.05, 0.1, -0.2);
  struct Case {
    std::vector<int> refined;
    long children;
  };
  std::vector<Case> cases;
  for (const auto& e : kHexEdges)
    cases.push_back({{e[0], e[1]}, 5});
  for (const auto& f : kHexFaces)
    cases.push_back({{f[0], f[1], f[2], f[3]}, 13});
  cases.push_back({{0, 1, 2, 3, 4, 5, 6, 7}, 27});
  double min_sj[3] = {1, 1, 1};
  const Eigen::MatrixXd* shapes[3] = {&cube, &affine, &general};
  for (int s = 0; s < 3; ++s) {
    const Eigen::MatrixXd& P = *shapes[s];
    Eigen::MatrixXi one(1, 8);
    one << 0, 1, 2, 3, 4, 5, 6, 7;
    const VolumeQuality parent = volume_quality(P, one, 1);
    for (const Case& c : cases) {
      const SplitResult r = split_one(P, c.refined);
      INFO("shape " << s << ", refined " << c.refined.size() << " from " << c.refined[0] << ","
                    << c.refined[1]);
      REQUIRE(r.C.rows() == c.children);
      CHECK(r.report.widened == 0);
      const VolumeQuality q = volume_quality(r.V, r.C, 1);
      CHECK(q.inverted == 0);
      min_sj[s] = std::min(min_sj[s], q.min_scaled_jacobian);
      const Conformity k = conformity(r.V, r.C);
      CHECK(k.overused == 0);
      if (s < 2) { // affine: the children tile the parent exactly (rounding of ~30 terms)
        CHECK(q.volume == Approx(parent.volume).epsilon(1e-12));
        CHECK(k.open_area == Approx(hex_area(P, one)).epsilon(1e-12));
      } else { // trilinear: transition children are not sub-boxes of the parent's map
        CHECK(q.volume == Approx(parent.volume).epsilon(0.02));
      }
    }
  }
  INFO("min scaled Jacobian: cube " << min_sj[0] << ", parallelepiped " << min_sj[1] << ", general "
                                    << min_sj[2]);
  // The face template's corner children meet both transitions: two corners at 1/sqrt(5) (the 2-D
  // transition's angle) give 1/5 on the cube; measured 0.075 and 0.128 on the others.
  CHECK(min_sj[0] == Approx(0.2).epsilon(1e-12));
  CHECK(min_sj[1] > 0.07);
  CHECK(min_sj[2] > 0.12);
}

TEST_CASE("split_hexahedra: random refined nodes on a grid close to a conforming mesh",
          "[volume][adapt][hex]") {
  Eigen::MatrixXd V0;
  Eigen::MatrixXi C0;
  hex_grid(4, V0, C0);
  std::mt19937 rng(14);
  for (double p : {0.05, 0.15, 0.3}) {
    for (int trial = 0; trial < 4; ++trial) {
      Eigen::MatrixXd V = V0;
      Eigen::MatrixXi C = C0;
      for (int pass = 0; pass < 2; ++pass) { // the second on the refined, unstructured mesh
        std::bernoulli_distribution pick(p);
        std::vector<char> refined(size_t(V.rows()));
        for (char& r : refined)
          r = pick(rng);
        std::vector<char> b(size_t(V.rows()), 0);
        Eigen::VectorXd values = V.col(0);
        const long nodes = V.rows();
        const RefinementReport rep = split_hexahedra(V, C, b, values, refined);
        INFO("p " << p << ", trial " << trial << ", pass " << pass << ": " << C.rows()
                  << " elements, widened " << rep.widened);
        CHECK(V.rows() == nodes + rep.new_nodes);
        const Conformity k = conformity(V, C);
        CHECK(k.overused == 0);
        CHECK(inner_open_faces(V, C) == 0);             // every inner face used exactly twice
        CHECK(k.open_area == Approx(6).epsilon(1e-12)); // the boundary: sums of ~1e3 planar quads
        const VolumeQuality q = volume_quality(V, C, 1);
        CHECK(q.inverted == 0);
        CHECK(q.volume == Approx(1).epsilon(1e-12));
        CHECK((values - V.col(0)).cwiseAbs().maxCoeff() < 1e-14); // trilinear values of x
      }
    }
  }
}

TEST_CASE("refine_hexahedra: the digest's worked indicator", "[volume][adapt][hex]") {
  // §11.6 as for tetrahedra: hexahedron A with values spanning 0 .. 0.5 (indicator 0.5), B with
  // 0.6 .. 1 (0.4); the global range is 1. A refined at delta 0.2 and 0.45 (all its vertices
  // refined: 27 children), B only at 0.2, neither at 0.6.
  Eigen::MatrixXd V(16, 3);
  V.topRows(8) = unit_cube();
  V.bottomRows(8) = unit_cube().rowwise() + Eigen::RowVector3d(5, 0, 0);
  Eigen::MatrixXi C(2, 8);
  C << 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15;
  Eigen::VectorXd v(16);
  v << 0, 0.1, 0.5, 0.3, 0.2, 0.2, 0.4, 0.1, 0.6, 0.7, 0.8, 1, 0.9, 0.7, 0.6, 0.65;
  const struct {
    double delta;
    long flagged, elements;
  } rows[] = {{0.2, 2, 54}, {0.45, 1, 28}, {0.6, 0, 2}};
  for (const auto& row : rows) {
    Eigen::MatrixXd W = V;
    Eigen::MatrixXi D = C;
    Eigen::VectorXd w = v;
    std::vector<char> b(16, 0);
    const RefinementReport r = refine_hexahedra(W, D, b, w, row.delta);
    INFO("delta " << row.delta);
    CHECK(r.flagged == row.flagged);
    CHECK(D.rows() == row.elements);
    CHECK(W.rows() == 16 + 56 * row.flagged); // 64 - 8 lattice points per refined hexahedron
    CHECK(volume_quality(W, D, 1).volume == Approx(2).epsilon(1e-14));
  }
}

TEST_CASE("adapt_hexahedra: refinement at a front, counts monotone in delta",
          "[volume][adapt][hex]") {
  Eigen::MatrixXd V0;
  Eigen::MatrixXi C0;
  hex_grid(8, V0, C0);
  auto field = [](const Eigen::MatrixXd& V, const Eigen::MatrixXi&) { // a front at x = 0.4
    return Eigen::VectorXd(((V.col(0).array() - 0.4) / 0.05).tanh());
  };
  long previous = -1;
  for (double delta : {0.9, 0.5, 0.2, 0.05}) {
    Eigen::MatrixXd V = V0;
    Eigen::MatrixXi C = C0;
    std::vector<char> b(size_t(V.rows()), 0);
    const std::vector<RefinementReport> reps = adapt_hexahedra(V, C, b, field, delta, 2);
    INFO("delta " << delta << ": " << C.rows() << " elements after " << reps.size()
                  << " passes, widened " << reps[0].widened);
    CHECK(C.rows() >= previous); // a smaller delta refines at least as much
    previous = C.rows();
    const Conformity k = conformity(V, C);
    CHECK(k.overused == 0);
    CHECK(inner_open_faces(V, C) == 0);
    CHECK(k.open_area == Approx(6).epsilon(1e-12));
    const VolumeQuality q = volume_quality(V, C, 1);
    CHECK(q.inverted == 0);
    INFO("volume - 1 = " << q.volume - 1);
    CHECK(q.volume == Approx(1).epsilon(1e-11)); // rounding of sums over ~1e5 elements
    // Elements far from the front (every vertex beyond 3 coarse cells: a flagged cell next to it,
    // the cells sharing its vertices refined whole, their neighbours' transitions) stay whole.
    const double h0 = 1.0 / 8;
    long far_small = 0;
    for (long e = 0; e < C.rows(); ++e) {
      double lo = 1, hi = 0;
      for (int j = 0; j < 8; ++j)
        lo = std::min(lo, V(C(e, j), 0)), hi = std::max(hi, V(C(e, j), 0));
      if ((lo > 0.4 + 3 * h0 || hi < 0.4 - 3 * h0) && hi - lo < h0 - 1e-12)
        ++far_small;
    }
    CHECK(far_small == 0);
    if (delta <= 0.5) // the front resolved: the largest indicator falls
      CHECK(refinement_indicator(C, field(V, C)).maxCoeff() <
            refinement_indicator(C0, field(V0, C0)).maxCoeff());
  }
}

TEST_CASE("refine_hexahedra: new boundary nodes go onto F = 0 (sphere, default hexahedra)",
          "[volume][adapt][hex]") {
  const ImplicitFunction f = test::sphere(1.0);
  VolumeMeshOptions o;
  o.elements = VolumeElements::hexahedra;
  o.resolution = 10;
  o.threads = 1;
  VolumeMesh m = volume_mesh(f, o);
  const double exact = 4 * 3.14159265358979323846 / 3;
  const double before = std::abs(volume_quality(m.V, m.C, 1).volume - exact);
  const long n0 = m.V.rows();
  auto field = [](const Eigen::MatrixXd& V, const Eigen::MatrixXi&) {
    return Eigen::VectorXd(V.col(0));
  };
  const std::vector<RefinementReport> reps = adapt_hexahedra(m.V, m.C, m.boundary, field, 0, 1, f);
  REQUIRE(reps.size() == 1);
  INFO("projected " << reps[0].projected << ", held " << reps[0].held);
  CHECK(reps[0].projected > 0);
  CHECK(reps[0].held < 0.01 * reps[0].projected);
  CHECK(conformity(m.V, m.C).overused == 0);
  const VolumeQuality q = volume_quality(m.V, m.C, 1);
  CHECK(q.inverted == 0);
  CHECK(std::abs(q.volume - exact) < 0.5 * before); // thirds of the facets on the sphere
  // New boundary nodes: on F = 0 unless held short.
  Eigen::VectorXd F(m.V.rows() - n0);
  f.value(m.V.bottomRows(F.size()), F);
  long off = 0;
  for (long k = 0; k < F.size(); ++k)
    off += m.boundary[size_t(n0 + k)] && std::abs(F(k)) > 1e-9;
  CHECK(off == 0);
  const Eigen::MatrixXi B = boundary_facets(m.C);
  long unflagged = 0;
  for (long i = 0; i < B.size(); ++i)
    unflagged += !m.boundary[size_t(B.data()[i])];
  CHECK(unflagged <= 4 * reps[0].held); // only held nodes leave the boundary
}

TEST_CASE("adapt_hexahedra: body (11), default hexahedra, two passes at a peak near the boundary",
          "[volume][adapt][hex]") {
  // A field peaking at (0.75, 0.75, 0), inside the body a quarter from its face x = 1: the passes
  // refine around it (locally: the far part of the mesh stays), new boundary nodes go onto F = 0
  // as far as no element folds, and the volume moves towards body (11)'s 3.868844.
  const ImplicitFunction f = test::body11_function();
  VolumeMeshOptions o;
  o.elements = VolumeElements::hexahedra;
  o.resolution = 16;
  o.threads = 1;
  VolumeMesh m = volume_mesh(f, o);
  // Elements with every vertex more than 1 (8 cells) from the peak.
  auto far_elements = [](const Eigen::MatrixXd& V, const Eigen::MatrixXi& C) {
    long far = 0;
    for (long e = 0; e < C.rows(); ++e) {
      bool all = true;
      for (int j = 0; j < 8; ++j)
        all = all && (V.row(C(e, j)) - Eigen::RowVector3d(0.75, 0.75, 0)).norm() > 1;
      far += all;
    }
    return far;
  };
  const long elements0 = m.C.rows(), n0 = m.V.rows(), far0 = far_elements(m.V, m.C);
  const double exact = 3.868844, before = volume_quality(m.V, m.C, 1).volume;
  auto peak = [](const Eigen::MatrixXd& V, const Eigen::MatrixXi&) {
    const Eigen::ArrayXd r2 = (V.col(0).array() - 0.75).square() +
                              (V.col(1).array() - 0.75).square() + V.col(2).array().square();
    return Eigen::VectorXd(1 / (0.05 + r2));
  };
  const std::vector<RefinementReport> reps = adapt_hexahedra(m.V, m.C, m.boundary, peak, 0.2, 2, f);
  REQUIRE(reps.size() == 2);
  long projected = 0, held = 0;
  for (const RefinementReport& r : reps)
    projected += r.projected, held += r.held;
  INFO(elements0 << " -> " << m.C.rows() << " elements (" << far0 << " far from the peak, then "
                 << far_elements(m.V, m.C) << "); projected " << projected << ", held " << held
                 << "; widened " << reps[0].widened << ", " << reps[1].widened);
  CHECK(m.C.rows() > 2 * elements0);
  CHECK(far_elements(m.V, m.C) == far0); // local: the elements away from the peak stay whole
  CHECK(projected > 100);
  CHECK(held <= projected / 100);
  CHECK(conformity(m.V, m.C).overused == 0);
  const Eigen::MatrixXi B = boundary_facets(m.C);
  CHECK(check_mesh(m.V, triangulate_quads(m.V, B)).boundary_edges == 0); // closed
  const VolumeQuality q = volume_quality(m.V, m.C, 1);
  CHECK(q.inverted == 0);
  CHECK(std::abs(q.volume - exact) < std::abs(before - exact));
  // New boundary nodes on F = 0 (to the root finder's tolerance) but those held short.
  Eigen::VectorXd F(m.V.rows() - n0);
  f.value(m.V.bottomRows(F.size()), F);
  long off = 0;
  for (long k = 0; k < F.size(); ++k)
    off += m.boundary[size_t(n0 + k)] && std::abs(F(k)) > 1e-9;
  CHECK(off <= held);
}

TEST_CASE("refine_hexahedra: the impeller's and the valve's default hexahedra, one pass on F",
          "[volume][adapt][hex][heavy]") {
  // The pillow layer is nearly flat at creases (min scaled Jacobian 2e-13): the trilinear map of
  // such a parent folds some children (at their corners, or only at their centres), which the
  // untangling opens; on the valve one child's boundary face is folded too and opens only with
  // that face sliding on F = 0 (before: 1 left inverted). Boundary nodes whose full projection
  // would fold a thin child are untangled around on F = 0, the rest held short: measured 11 % at
  // cell 0.5, whose pillows are flattest (before: 15 %), 0.01 % at 0.25 (2 %), valve 0.2 % (0.9 %).
  const struct {
    const char* model;
    double cell, held, volume;
  } rows[] = {{"impeller", 0.5, 0.13, 0},
              {"impeller", 0.25, 0.001, 1233.5}, // Monte Carlo (docs/benchmarks.md)
              {"valve", 0.2, 0.005, 0}};
  for (const auto& row : rows) {
    const ImplicitFunction f =
        load_implicit(std::string(INTERLIN_DATA_DIR) + "/models/" + row.model + ".rf");
    VolumeMeshOptions o;
    o.elements = VolumeElements::hexahedra;
    o.cell = row.cell;
    VolumeMesh m = volume_mesh(f, o);
    const long elements0 = m.C.rows();
    Eigen::VectorXd values(m.V.rows());
    f.value(m.V, values);
    const RefinementReport r = refine_hexahedra(m.V, m.C, m.boundary, values, 0.2, f);
    INFO(row.model << " at cell " << row.cell << ": " << elements0 << " -> " << m.C.rows()
                   << "; folded " << r.folded << " (" << r.still_folded << " left); projected "
                   << r.projected << ", held " << r.held);
    CHECK(m.C.rows() > 3 * elements0);
    CHECK(r.folded > 0);
    CHECK(r.still_folded == 0);
    CHECK(r.held < row.held * r.projected);
    const VolumeQuality q = volume_quality(m.V, m.C);
    CHECK(q.inverted == 0);
    if (row.volume > 0) // the unrefined impeller at 0.5 already leaves out 5 %
      CHECK(q.volume == Approx(row.volume).epsilon(0.001));
  }
}

TEST_CASE("split_hexahedra: pillows with sliver boundary faces (the car at cell 0.3)",
          "[volume][adapt][hex]") {
  // Children on a sliver face fold on F = 0 whichever way the facets' nodes slide (6 stayed
  // folded); the new nodes of those facets then leave F = 0 for the max-min search, and the
  // projection holds them where their elements stay valid.
  Eigen::MatrixXd V;
  Eigen::MatrixXi C;
  std::vector<char> boundary;
  read_fixture(test::kCarSliverPillows, 92, 38, V, C, boundary);
  const double volume0 = volume_quality(V, C).volume;
  const ImplicitFunction f = load_implicit(std::string(INTERLIN_DATA_DIR) + "/models/car.rf");
  Eigen::VectorXd values = V.col(0);
  const long nodes0 = V.rows();
  const RefinementReport r = split_hexahedra(V, C, boundary, values, std::vector<char>(92, 1), f);
  INFO("folded " << r.folded << " (" << r.still_folded << " left); projected " << r.projected
                 << ", held " << r.held);
  CHECK(C.rows() == 38 * 27);
  CHECK(r.folded > 0);
  CHECK(r.still_folded == 0);
  const VolumeQuality q = volume_quality(V, C);
  CHECK(q.inverted == 0);
  CHECK(q.min_scaled_jacobian > 0);
  // Measured: 23 of 136 held (the slivers' new facet nodes), the volume 0.750595 -> 0.750603.
  CHECK(r.held <= r.projected / 4);
  CHECK(q.volume == Approx(volume0).epsilon(1e-3));
  Eigen::VectorXd F(V.rows() - nodes0);
  f.value(V.bottomRows(F.size()), F);
  long on_zero = 0; // the new boundary nodes not held are on F = 0
  for (long k = 0; k < F.size(); ++k)
    on_zero += boundary[size_t(nodes0 + k)] && std::abs(F(k)) < 1e-9;
  CHECK(on_zero >= r.projected - r.held);
}

TEST_CASE("adapt_hexahedra: a pass that leaves children folded is undone", "[volume][adapt][hex]") {
  // Children in a wall thinner than the cell (the valve at 0.4, pass 2): 6 stay folded through
  // every untangling, so the loop keeps the mesh it had (before: returned folded, and the CLI
  // refused the whole run).
  Eigen::MatrixXd V;
  Eigen::MatrixXi C;
  std::vector<char> boundary;
  read_fixture(test::kValveThinWallChildren, 99, 42, V, C, boundary);
  const ImplicitFunction f = load_implicit(std::string(INTERLIN_DATA_DIR) + "/models/valve.rf");
  const auto F = [&f](const Eigen::MatrixXd& W, const Eigen::MatrixXi&) {
    Eigen::VectorXd v(W.rows());
    f.value(W, v);
    return v;
  };
  {
    Eigen::MatrixXd W = V;
    Eigen::MatrixXi D = C;
    std::vector<char> b = boundary;
    Eigen::VectorXd values = F(W, D);
    const RefinementReport r = refine_hexahedra(W, D, b, values, 0, f);
    INFO("folded " << r.folded << ", " << r.still_folded << " left");
    CHECK(r.still_folded > 0); // measured 4 of 37 (6 before the projection)
    CHECK(!r.undone);
    CHECK(volume_quality(W, D).inverted == r.still_folded);
  }
  const Eigen::MatrixXd V0 = V;
  const Eigen::MatrixXi C0 = C;
  const std::vector<char> boundary0 = boundary;
  const std::vector<RefinementReport> passes = adapt_hexahedra(V, C, boundary, F, 0, 2, f);
  REQUIRE(passes.size() == 1);
  CHECK(passes[0].undone);
  CHECK(passes[0].still_folded > 0);
  CHECK(V == V0);
  CHECK(C == C0);
  CHECK(boundary == boundary0);
  CHECK(volume_quality(V, C).inverted == 0);
}

TEST_CASE("split_hexahedra: bad arguments", "[volume][adapt][hex]") {
  Eigen::MatrixXd V = unit_cube();
  Eigen::MatrixXi C(1, 8);
  C << 0, 1, 2, 3, 4, 5, 6, 7;
  std::vector<char> b(8, 0);
  Eigen::VectorXd ok = V.col(0), wrong(3);
  CHECK_THROWS_AS(refine_hexahedra(V, C, b, wrong, 0.2), std::invalid_argument);
  CHECK_THROWS_AS(refine_hexahedra(V, C, b, ok, 1.0), std::invalid_argument);
  CHECK_THROWS_AS(split_hexahedra(V, C, b, ok, std::vector<char>(3, 1)), std::invalid_argument);
  Eigen::MatrixXi tets(1, 4);
  tets << 0, 1, 2, 3;
  CHECK_THROWS_AS(refine_hexahedra(V, tets, b, ok, 0.2), std::invalid_argument);
}

TEST_CASE("split_hexahedra, refine_tetrahedra: a pass beyond max_elements changes nothing",
          "[volume][adapt][hex]") {
  // 8 hexahedra, every node refined: 8 x 27 = 216 children; the limit is checked first
  Eigen::MatrixXd V;
  Eigen::MatrixXi C;
  hex_grid(2, V, C);
  const Eigen::MatrixXd V0 = V;
  const Eigen::MatrixXi C0 = C;
  std::vector<char> b(size_t(V.rows()), 0);
  Eigen::VectorXd values = V.col(0);
  const std::vector<char> all(size_t(V.rows()), 1);
  CHECK_THROWS_WITH(split_hexahedra(V, C, b, values, all, {}, 215),
                    Catch::Contains("would make 216 elements, more than the limit of 215"));
  CHECK(V == V0);
  CHECK(C == C0);
  CHECK(split_hexahedra(V, C, b, values, all, {}, 216).split == 8);
  CHECK(C.rows() == 216);
  // one Kuhn cube (6 tetrahedra), indicator everywhere (delta 0): 6 x 8 = 48 children
  Eigen::MatrixXd T(8, 3);
  T << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
  Eigen::MatrixXi K(6, 4);
  K << 0, 1, 2, 6, 0, 2, 3, 6, 0, 3, 7, 6, 0, 7, 4, 6, 0, 4, 5, 6, 0, 5, 1, 6;
  std::vector<char> tb(8, 0);
  Eigen::VectorXd tv = T.col(0);
  CHECK_THROWS_AS(refine_tetrahedra(T, K, tb, tv, 0.0, {}, 47), std::length_error);
  CHECK(K.rows() == 6);
  CHECK(refine_tetrahedra(T, K, tb, tv, 0.0, {}, 48).split == 6);
  CHECK(K.rows() == 48);
}
