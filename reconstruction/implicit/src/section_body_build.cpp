// Sections -> section-body model (reconstruction/implicit/section_body_build.h).
#include "interlin/reconstruction/implicit/section_body_build.h"

#include "interlin/interflatation/operators/cubic_grid.h"
#include "interlin/reconstruction/implicit/body_projection.h"
#include "interlin/reconstruction/meshing/parallel_for.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <stdexcept>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::Vector3d;

namespace {

// The cap edges of one end: the ends of the end section's longest chord, moved to the nose tips
// (profile_edges), as loft parameters, sorted.
Eigen::Vector2d cap_edges(const LoftResult& L, size_t k) {
  const auto [a, b] = profile_edges(L.sections[k].points);
  const double ua = L.point_u[k](a), ub = L.point_u[k](b);
  return {std::min(ua, ub), std::max(ua, ub)};
}

// The grid cells and their geometry.
struct Cells {
  NodeGrid grid;
  Eigen::Array3i m; // cells per axis
  long count() const { return static_cast<long>(m(0)) * m(1) * m(2); }
  long node(int i, int j, int k) const {
    return i + grid.n(0) * (j + static_cast<long>(grid.n(1)) * k);
  }
  // Node index of corner q (bits: +i, +j, +k) of a cell.
  long corner_node(long cell, int q) const {
    const long i = cell % m(0), j = (cell / m(0)) % m(1),
               k = cell / (static_cast<long>(m(0)) * m(1));
    return node(int(i + (q & 1)), int(j + ((q >> 1) & 1)), int(k + (q >> 2)));
  }
  Vector3d corner(long cell) const {
    const long i = cell % m(0), j = (cell / m(0)) % m(1),
               k = cell / (static_cast<long>(m(0)) * m(1));
    return grid.origin + grid.h * Vector3d(double(i), double(j), double(k));
  }
  long cell_of(const Vector3d& p) const {
    long c[3];
    for (int a = 0; a < 3; ++a) {
      const double t = std::floor((p(a) - grid.origin(a)) / grid.h);
      if (!(t >= 0 && t < m(a)))
        return -1;
      c[a] = static_cast<long>(t);
    }
    return c[0] + m(0) * (c[1] + static_cast<long>(m(1)) * c[2]);
  }
};

// Random points in the given cells (`per_cell` each, deterministic per cell and round).
MatrixXd random_points(const Cells& C, const std::vector<long>& cells, int per_cell, int round) {
  MatrixXd P(static_cast<Index>(cells.size()) * per_cell, 3);
  for (size_t c = 0; c < cells.size(); ++c) {
    std::mt19937_64 rng(static_cast<std::uint64_t>(cells[c]) * 7919u +
                        static_cast<unsigned>(round));
    std::uniform_real_distribution<double> U(0, 1);
    const Vector3d o = C.corner(cells[c]);
    for (int r = 0; r < per_cell; ++r)
      P.row(static_cast<Index>(c) * per_cell + r) =
          (o + C.grid.h * Vector3d(U(rng), U(rng), U(rng))).transpose();
  }
  return P;
}

// Adds the exact foot of p as a start of its cell unless the cell's starts already find it.
// Returns true when a start was added.
bool complete_starts(const BodyPatches& B, std::vector<PatchSeed>& seeds, const Vector3d& p,
                     const BodyDistance& exact, double tolerance) {
  const BodyDistance near = body_distance(B, p, seeds.data(), static_cast<int>(seeds.size()));
  if (near.found && std::abs(near.distance - exact.distance) <= tolerance)
    return false;
  seeds.push_back(exact.seed);
  return true;
}

// Boundary samples that every start set must serve: a grid on the side (nu x nv) and on the
// caps' interiors, refined along rows and columns wherever neighbouring samples' normals turn
// by more than 30 degrees (sharp trailing edges, the turn of a fold), by halving down to 1e-7 of
// the parameter range; plus 16 extra rows inside each end's fold region. `edge` receives the
// refined samples (where the side turns sharply).
std::vector<PatchSeed> boundary_samples(const BodyPatches& B, int nu, int nv,
                                        std::vector<PatchSeed>& edge) {
  const PiecewiseSurface& S = B.patches[0];
  const Eigen::Vector4d dom = domain(S);
  const auto normal = [&](double u, double v) {
    const SurfaceJet J = evaluate_jet(S, u, v);
    return Vector3d(J.Su.cross(J.Sv).normalized());
  };
  std::vector<PatchSeed> out;
  const std::function<void(double, double, double, double, int)> refine =
      [&](double u0, double v0, double u1, double v1, int depth) {
        if (depth > 23 || normal(u0, v0).dot(normal(u1, v1)) > std::cos(M_PI / 6))
          return;
        const double um = 0.5 * (u0 + u1), vm = 0.5 * (v0 + v1);
        out.push_back({0, um, vm});
        edge.push_back({0, um, vm});
        refine(u0, v0, um, vm, depth + 1);
        refine(um, vm, u1, v1, depth + 1);
      };
  std::vector<double> rows;
  for (int j = 0; j < nv; ++j)
    rows.push_back(dom(2) + (dom(3) - dom(2)) * j / (nv - 1));
  for (int e = 0; e < 2; ++e)
    if (B.fold_zone[static_cast<size_t>(e)] > 0) {
      const double ve = e == 0 ? dom(2) : dom(3), fv = B.fold_v[static_cast<size_t>(e)];
      for (int j = 1; j < 16; ++j)
        rows.push_back(ve + (fv - ve) * j / 16);
    }
  for (double v : rows)
    for (int i = 0; i < nu; ++i) {
      const double u0 = double(i) / nu, u1 = double(i + 1) / nu;
      out.push_back({0, u0, v});
      refine(u0, v, u1, v, 0);
    }
  std::sort(rows.begin(), rows.end());
  for (int i = 0; i < nu; ++i)
    for (size_t j = 0; j + 1 < rows.size(); ++j)
      refine(double(i) / nu, rows[j], double(i) / nu, rows[j + 1], 0);
  // Caps: an s-grid, denser towards the edge points s = 0, 1 where the rulings shrink (and
  // may cross where the loop turns round a sharp edge), on t-rows denser towards the loop.
  std::vector<double> cs, ct;
  for (int i = 1; i < nu; ++i)
    cs.push_back(double(i) / nu);
  for (int k = 4; k <= 10; ++k)
    for (double e : {std::pow(10.0, -k), 3 * std::pow(10.0, -k)})
      cs.insert(cs.end(), {e, 1 - e});
  for (int j = 1; j < 16; ++j)
    ct.push_back(j / 16.0);
  for (int k = 2; k <= 8; ++k)
    ct.insert(ct.end(), {std::pow(10.0, -k), 1 - std::pow(10.0, -k)});
  for (int k = 1; k < 3; ++k)
    for (double t : ct)
      for (double sv : cs)
        out.push_back({k, sv, t});
  return out;
}

// The side's sample grid (boundary_samples): 1024 points round each of 128 rows.
constexpr int kSampleU = 1024, kSampleV = 128;
// Random points per round of cover_random_points: over the whole boundary, and near the sharp
// edges (a small area: 20,000 per round leave 0 misses in 400,000 test points, see
// tests/reconstruction/implicit/measure_section_body.cpp).
constexpr long kRandomPoints = 100000, kEdgePoints = 20000;

// kRandomPoints random boundary points: side 60 % (u, v uniform), each cap 20 % (s, t uniform).
std::vector<PatchSeed> uniform_boundary_points(const BodyPatches& B, int round) {
  std::mt19937_64 rng(1234 + static_cast<unsigned>(round));
  std::uniform_real_distribution<double> U(0, 1);
  const Eigen::Vector4d dom = domain(B.patches[0]);
  std::vector<PatchSeed> out;
  for (long i = 0; i < kRandomPoints; ++i) {
    const int patch = i % 5 == 0 ? 1 : i % 5 == 1 ? 2 : 0;
    PatchSeed at{patch, U(rng), U(rng)};
    if (patch == 0)
      at.v = dom(2) + (dom(3) - dom(2)) * at.v;
    out.push_back(at);
  }
  return out;
}

// kEdgePoints random side points near the sharp edges: each within two sample columns and
// one sample row of an edge sample (boundary_samples), where a cell may hold a sliver of the
// edge's other sheet that no sample reaches.
std::vector<PatchSeed> edge_boundary_points(const BodyPatches& B,
                                            const std::vector<PatchSeed>& edge, int round) {
  if (edge.empty())
    return {};
  std::mt19937_64 rng(4321 + static_cast<unsigned>(round));
  std::uniform_real_distribution<double> U(-1, 1);
  std::uniform_int_distribution<size_t> pick(0, edge.size() - 1);
  const Eigen::Vector4d dom = domain(B.patches[0]);
  const double du = 2.0 / kSampleU, dv = (dom(3) - dom(2)) / (kSampleV - 1);
  std::vector<PatchSeed> out;
  for (long i = 0; i < kEdgePoints; ++i) {
    const PatchSeed& e = edge[pick(rng)];
    const double u = e.u + du * U(rng);
    out.push_back({0, u - std::floor(u), std::clamp(e.v + dv * U(rng), dom(2), dom(3))});
  }
  return out;
}

// Gives every boundary point `at` whose cell's starts (start_set(p)) do not find it (|omega| >
// 1e-13 x diagonal) its own start. Returns how many needed one.
long cover_random_points(const BodyPatches& B, const std::vector<PatchSeed>& points,
                         const std::function<std::vector<PatchSeed>&(const Vector3d&)>& start_set,
                         double diag) {
  long misses = 0;
  for (const PatchSeed& at : points) {
    const Vector3d p = evaluate(B, at);
    std::vector<PatchSeed>& st = start_set(p);
    const BodyDistance near = body_distance(B, p, st.data(), static_cast<int>(st.size()));
    if (!near.found || std::abs(near.distance) > 1e-13 * diag) {
      st.push_back(at);
      ++misses;
    }
  }
  return misses;
}

// The options' rules (build_section_body).
void check_body_options(const SectionBodyOptions& o) {
  if (o.resolution < 8 || o.resolution > 1024)
    throw std::invalid_argument("section body: resolution must be from 8 to 1024");
  if (!(o.margin > 0) || !(o.band_inner > 0 && o.band_outer > o.band_inner))
    throw std::invalid_argument("section body: need margin > 0 and 0 < band_inner < band_outer");
  if (o.checks_per_cell < 0)
    throw std::invalid_argument("section body: checks_per_cell must be >= 0");
}

// What the build steps share: the body, its exact projection, the grid, the exact signed
// distance at its nodes and the band cells.
struct BodyGrid {
  const BodyPatches& B;
  const BodyProjection& proj;
  Cells C;
  MatrixXd N;                       // the grid nodes, one row each
  std::vector<BodyDistance> node_d; // their exact signed distances
  std::vector<long> band;           // band cells
  std::vector<long> slot;           // cell -> its index into band, -1 outside the band
  int threads;
  double diag; // bounding-box diagonal of the body

  // The band cell of a boundary point (its index into band); every boundary point has one.
  size_t band_slot(const Vector3d& p) const {
    const long c = C.cell_of(p);
    if (c < 0 || slot[static_cast<size_t>(c)] < 0)
      throw std::runtime_error("section body: a boundary point lies outside the band cells");
    return static_cast<size_t>(slot[static_cast<size_t>(c)]);
  }
};

// The model box (bounding box of the boundary samples + margin x its diagonal) and the grid
// over it: `resolution` cells along the longest side, two cells of padding below, three above.
Cells model_grid(const Eigen::AlignedBox3d& bbox, const SectionBodyOptions& o,
                 SectionBodyModel& M) {
  const double diag = bbox.diagonal().norm();
  M.box = Eigen::AlignedBox3d(bbox.min().array() - o.margin * diag,
                              bbox.max().array() + o.margin * diag);
  Cells C;
  C.grid.h = M.box.sizes().maxCoeff() / o.resolution;
  C.grid.origin = M.box.min().array() - 2 * C.grid.h;
  for (int a = 0; a < 3; ++a)
    C.grid.n(a) = static_cast<int>(std::ceil(M.box.sizes()(a) / C.grid.h)) + 5;
  C.m = C.grid.n - 1;
  M.band_inner = o.band_inner * C.grid.h;
  M.band_outer = o.band_outer * C.grid.h;
  return C;
}

// Far field: the exact signed distance at the grid nodes, stored as the grid's values.
void far_field(BodyGrid& G) {
  NodeGrid& g = G.C.grid;
  const long nodes = static_cast<long>(g.n(0)) * g.n(1) * g.n(2);
  G.N.resize(nodes, 3);
  for (int k = 0; k < g.n(2); ++k)
    for (int j = 0; j < g.n(1); ++j)
      for (int i = 0; i < g.n(0); ++i)
        G.N.row(G.C.node(i, j, k)) = (g.origin + g.h * Vector3d(i, j, k)).transpose();
  G.node_d = G.proj.distances(G.N, G.threads);
  g.values.resize(static_cast<size_t>(nodes));
  for (long i = 0; i < nodes; ++i)
    g.values[static_cast<size_t>(i)] = G.node_d[static_cast<size_t>(i)].distance;
}

// Band cells: some point of the cell may be within band_outer of the boundary (|d| is
// 1-Lipschitz and every point of a cell lies within h sqrt(3) of each corner).
void find_band(BodyGrid& G, double band_outer) {
  G.slot.assign(static_cast<size_t>(G.C.count()), -1);
  for (long c = 0; c < G.C.count(); ++c) {
    double lo = INFINITY;
    for (int q = 0; q < 8; ++q)
      lo = std::min(lo, std::abs(G.node_d[static_cast<size_t>(G.C.corner_node(c, q))].distance));
    if (lo < band_outer + G.C.grid.h * std::sqrt(3.0)) {
      G.slot[static_cast<size_t>(c)] = static_cast<long>(G.band.size());
      G.band.push_back(c);
    }
  }
}

// The near field's check points: per band cell its centre, then checks_per_cell random points;
// their exact distances; and the starts of every band cell.
struct NearField {
  MatrixXd Q;
  std::vector<BodyDistance> q_d;
  std::vector<std::vector<PatchSeed>> starts;
};

// Cells the boundary may cross get the centre's foot on every patch that comes within the
// cell's circumscribed sphere: a sliver of a cap or a side in a corner of the cell has no
// samples there, but its points lie near that foot.
void crossed_cell_feet(const BodyGrid& G, NearField& F, int per) {
  const double half_diagonal = 0.5 * std::sqrt(3.0) * G.C.grid.h;
  std::vector<size_t> crossed;
  for (size_t c = 0; c < G.band.size(); ++c)
    if (std::abs(F.q_d[c * static_cast<size_t>(per)].distance) <= half_diagonal)
      crossed.push_back(c);
  MatrixXd centres(static_cast<Index>(crossed.size()), 3);
  for (size_t i = 0; i < crossed.size(); ++i)
    centres.row(static_cast<Index>(i)) = F.Q.row(static_cast<Index>(crossed[i]) * per);
  for (int patch = 0; patch < 3; ++patch) {
    const std::vector<BodyDistance> f = G.proj.distances(centres, G.threads, patch);
    for (size_t i = 0; i < crossed.size(); ++i)
      if (f[i].found && std::abs(f[i].distance) <= half_diagonal)
        F.starts[crossed[i]].push_back(f[i].seed);
  }
}

// Starts: the foot of the cell centre, completed by the corners and random check points whose
// exact foot the starts do not find.
NearField near_field_starts(const BodyGrid& G, int checks_per_cell, SectionBodyReport& R,
                            const std::function<void(const std::string&)>& progress) {
  const int per = 1 + checks_per_cell;
  const double tolerance = 1e-9 * G.diag;
  NearField F;
  F.Q = random_points(G.C, G.band, per, 0);
  for (size_t c = 0; c < G.band.size(); ++c)
    F.Q.row(static_cast<Index>(c) * per) =
        (G.C.corner(G.band[c]) + Vector3d::Constant(0.5 * G.C.grid.h)).transpose();
  progress("near-field starts for " + std::to_string(G.band.size()) + " band cells (" +
           std::to_string(F.Q.rows()) + " exact feet)");
  F.q_d = G.proj.distances(F.Q, G.threads);
  F.starts.resize(G.band.size());
  crossed_cell_feet(G, F, per);
  std::vector<long> fails(G.band.size(), 0);
  detail::parallel_for(static_cast<long>(G.band.size()), G.threads, [&](long c, int) {
    std::vector<PatchSeed>& s = F.starts[static_cast<size_t>(c)];
    if (s.empty())
      s.push_back(F.q_d[static_cast<size_t>(c * per)].seed);
    long& failed = fails[static_cast<size_t>(c)];
    for (int q = 0; q < 8; ++q) {
      const long n = G.C.corner_node(G.band[static_cast<size_t>(c)], q);
      failed += complete_starts(G.B, s, G.N.row(n).transpose(), G.node_d[static_cast<size_t>(n)],
                                tolerance);
    }
    for (int r = 1; r < per; ++r)
      failed += complete_starts(G.B, s, F.Q.row(c * per + r).transpose(),
                                F.q_d[static_cast<size_t>(c * per + r)], tolerance);
  });
  R.check_points = static_cast<long>(G.band.size()) * (8 + checks_per_cell);
  for (long f : fails)
    R.check_failures += f;
  return F;
}

// The boundary points that must have omega = 0: the input section points and the samples.
std::vector<std::pair<Vector3d, PatchSeed>>
boundary_points(const LoftResult& L, const BodyPatches& B, const std::vector<PatchSeed>& samples) {
  std::vector<std::pair<Vector3d, PatchSeed>> surface;
  for (size_t k = 0; k < L.sections.size(); ++k)
    for (Index i = 0; i < L.sections[k].points.rows(); ++i)
      surface.push_back({L.sections[k].points.row(i).transpose(),
                         PatchSeed{0, L.point_u[k](i), L.section_v(static_cast<Index>(k))}});
  for (const PatchSeed& at : samples)
    surface.push_back({evaluate(B, at), at});
  return surface;
}

// Every sheet of the boundary that passes through a cell gets a start there (two sheets meet
// at a sharp trailing edge: a start on one side does not reach the other side's points);
// sheets by patch and by outward normals within 30 degrees. Then every boundary point the
// starts of its cell do not find exactly gets its own start.
void cover_sheets(const BodyGrid& G, const std::vector<std::pair<Vector3d, PatchSeed>>& surface,
                  std::vector<std::vector<PatchSeed>>& starts) {
  const auto normal_at = [&](const PatchSeed& at) {
    const SurfaceJet J = evaluate_jet(G.B.patches[static_cast<size_t>(at.patch)], at.u, at.v);
    const Vector3d n = J.Su.cross(J.Sv);
    return n.norm() > 0 ? Vector3d(G.B.orientation[static_cast<size_t>(at.patch)] * n.normalized())
                        : Vector3d::Zero();
  };
  std::vector<std::vector<Vector3d>> sheet(starts.size());
  for (size_t c = 0; c < starts.size(); ++c)
    for (const PatchSeed& at : starts[c])
      sheet[c].push_back(normal_at(at));
  for (const auto& [p, at] : surface) {
    const size_t k = G.band_slot(p);
    const Vector3d n = normal_at(at);
    bool covered = false;
    for (size_t j = 0; j < starts[k].size() && !covered; ++j)
      covered = starts[k][j].patch == at.patch && sheet[k][j].dot(n) > std::cos(M_PI / 6);
    if (!covered) {
      starts[k].push_back(at);
      sheet[k].push_back(n);
    }
  }
  for (const auto& [p, at] : surface) {
    std::vector<PatchSeed>& s = starts[G.band_slot(p)];
    const BodyDistance near = body_distance(G.B, p, s.data(), static_cast<int>(s.size()));
    if (!near.found || std::abs(near.distance) > 1e-13 * G.diag)
      s.push_back(at);
  }
}

// Validation on checks_per_cell independent random points per band cell (failures get their
// own start as well).
void validate_near_field(const BodyGrid& G, int checks_per_cell,
                         std::vector<std::vector<PatchSeed>>& starts, SectionBodyReport& R,
                         const std::function<void(const std::string&)>& progress) {
  const MatrixXd V = random_points(G.C, G.band, checks_per_cell, 1);
  progress("validating the near field at " + std::to_string(V.rows()) + " points");
  const std::vector<BodyDistance> v_d = G.proj.distances(V, G.threads);
  R.validation_points = V.rows();
  for (Index r = 0; r < V.rows(); ++r) {
    std::vector<PatchSeed>& s = starts[static_cast<size_t>(r / checks_per_cell)];
    R.validation_failures +=
        complete_starts(G.B, s, V.row(r).transpose(), v_d[static_cast<size_t>(r)], 1e-9 * G.diag);
  }
}

// Measured: the far field's error beyond the inner band (at the check points), and omega on
// the boundary points, which must vanish (a throw otherwise: the exactness guarantee).
void measure_body(const SectionBodyModel& M, const NearField& F,
                  const std::vector<std::pair<Vector3d, PatchSeed>>& surface, double diag,
                  SectionBodyReport& R) {
  const CubicGrid far = cubic_grid(M.grid.values, M.grid.origin, M.grid.h, M.grid.n);
  for (Index r = 0; r < F.Q.rows(); ++r)
    if (std::abs(F.q_d[static_cast<size_t>(r)].distance) >= M.band_inner)
      R.max_far_error = std::max(R.max_far_error, std::abs(evaluate(far, F.Q.row(r).transpose()) -
                                                           F.q_d[static_cast<size_t>(r)].distance));
  Points3 S(static_cast<Index>(surface.size()), 3);
  for (size_t i = 0; i < surface.size(); ++i)
    S.row(static_cast<Index>(i)) = surface[i].first.transpose();
  Eigen::VectorXd w(S.rows());
  section_body_function(M).value(S, w);
  R.max_surface_omega = S.rows() > 0 ? w.cwiseAbs().maxCoeff() : 0.0;
  if (!(R.max_surface_omega <= 1e-12 * diag))
    throw std::runtime_error("section body: |omega| = " + std::to_string(R.max_surface_omega) +
                             " on the boundary exceeds 1e-12 x the diagonal");
}

} // namespace

SectionBodyBuild build_section_body(const std::vector<Section>& sections,
                                    const SectionBodyOptions& o) {
  check_body_options(o);
  if (o.progress)
    o.progress("lofting " + std::to_string(sections.size()) + " sections");
  return build_section_body(loft_sections(sections, o.loft), o);
}

SectionBodyBuild build_section_body(const LoftResult& loft, const SectionBodyOptions& o) {
  check_body_options(o);
  const std::function<void(const std::string&)> progress = [&](const std::string& s) {
    if (o.progress)
      o.progress(s);
  };
  SectionBodyBuild out;
  SectionBodyReport& R = out.report;
  SectionBodyModel& M = out.model;
  R.loft = loft;
  const LoftResult& L = R.loft;
  M.side = L.surface;
  M.edge_u = {cap_edges(L, 0), cap_edges(L, L.sections.size() - 1)};
  const BodyPatches B = body_patches(M.side, M.edge_u);
  const BodyProjection proj(B);

  std::vector<PatchSeed> edge_samples;
  const std::vector<PatchSeed> samples = boundary_samples(B, kSampleU, kSampleV, edge_samples);
  Eigen::AlignedBox3d bbox;
  for (const PatchSeed& at : samples)
    bbox.extend(evaluate(B, at));
  R.bbox_diagonal = bbox.diagonal().norm();
  BodyGrid G{B,
             proj,
             model_grid(bbox, o, M),
             {},
             {},
             {},
             {},
             detail::resolve_threads(o.threads),
             R.bbox_diagonal};
  const Cells& C = G.C;
  progress("exact signed distance at " +
           std::to_string(static_cast<long>(C.grid.n(0)) * C.grid.n(1) * C.grid.n(2)) +
           " grid nodes");
  far_field(G);
  M.grid = C.grid;
  find_band(G, M.band_outer);
  R.band_cells = static_cast<long>(G.band.size());

  NearField F = near_field_starts(G, o.checks_per_cell, R, progress);
  const auto surface = boundary_points(L, B, samples);
  R.surface_points = static_cast<long>(surface.size());
  cover_sheets(G, surface, F.starts);
  // Random boundary points: each one its starts do not find gets its own start (rare points
  // between the samples: in folds, or on a thin edge's other sheet when a cell holds only a
  // sliver of it). Uniform rounds over the whole boundary, then rounds near the sharp edges.
  const auto start_set = [&](const Vector3d& p) -> std::vector<PatchSeed>& {
    return F.starts[G.band_slot(p)];
  };
  for (int round = 0; round < 2; ++round)
    R.boundary_misses =
        cover_random_points(B, uniform_boundary_points(B, round), start_set, R.bbox_diagonal);
  for (int round = 0; round < 2; ++round)
    cover_random_points(B, edge_boundary_points(B, edge_samples, round), start_set,
                        R.bbox_diagonal);
  if (o.checks_per_cell > 0)
    validate_near_field(G, o.checks_per_cell, F.starts, R, progress);

  M.band_start.push_back(0);
  for (size_t c = 0; c < G.band.size(); ++c) {
    M.band_cells.push_back(G.band[c]);
    M.seeds.insert(M.seeds.end(), F.starts[c].begin(), F.starts[c].end());
    M.band_start.push_back(static_cast<std::int64_t>(M.seeds.size()));
  }
  R.seeds = static_cast<long>(M.seeds.size());
  measure_body(M, F, surface, R.bbox_diagonal, R);
  return out;
}

} // namespace interlin
