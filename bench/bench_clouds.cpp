// Point cloud -> surface: interlin's implicit (meshed by implicit_mesh) against PCL's and
// Open3D's screened Poisson on the same clouds and normals, in one run (docs/benchmarks.md,
// "Point clouds"). Each method runs in a fresh worker process (this program re-executed with
// --worker: a forked child would inherit the parent's OpenMP state and deadlock in PCL's and
// Open3D's OpenMP loops), so that its peak memory is its own: VmHWM after the method minus
// VmRSS before it. Metrics: two-sided Chamfer and Hausdorff
// distance between the reconstructed mesh and the true surface (100,000 area-uniform samples on
// each, exact point-to-triangle distances), divided by the truth's bounding-box diagonal; wall
// time of the reconstruction (fit + mesh; Poisson's own call, which includes its mesh).
//
// Usage: bench_clouds [--cases NAME,NAME|all] [--points N] [--resolution R|auto]
//                     [--cells-per-spacing K] [--depths D,D]
//                     [--threads T] [--methods interlin,pcl,open3d|all] [--save DIR]
//                     [--fit KEY=V,KEY=V]... [--diagnose] [--floor] [--no-thin-walls]
//                     [--no-sheet-normals] [--exact-sigmas S,S] [--span-smoothing auto|off]
//                     [--holes R/U/V/S,R/U/V/S]
// (--resolution: interlin's grid cells along the box's longest side; auto, the default:
// default_mesh_cell, cells of spacing / K with K = --cells-per-spacing, 2 by default.)
// (--span-smoothing off: the sectioned scans' sections each fitted to its slice alone,
// SliceFitOptions::smooth_span, for the same-run comparison in docs/benchmarks.md.)
// (--save: every case's cloud as DIR/KEY.xyzn and every method's mesh as DIR/KEY.METHOD.obj, for
// inspection.)
// (--methods: which of interlin (unstructured and, for slices, sectioned), PCL and Open3D run;
// the summary's ratios need at least one Poisson; none: only the cases, e.g. to see how many
// estimated normals point inward. An unknown option, method or case name, or a
// malformed number, is a usage error: one line on stderr, exit 2.)
// (--fit: one more interlin row per --fit, with these CloudFitOptions changed: support,
// fit_ball, min_points, max_depth, noise (sigma in cm), noise_x (a multiple of estimate_noise's
// sigma), noise_aware (0: off), acceptance_per_rho, sample_coarse (0: off), exterior_side (0:
// off), smooth_points (0: off), split_slabs (0: off), split_pockets (1: on), edge_sheets (0:
// off); for sweeps,
// docs/benchmarks.md "What limits the unstructured fit" and "A noise-aware neighbourhood".)
// (--diagnose: per method a line "distances:" with the quantiles of both distance directions in
// units of the case's sigma and the share of the Chamfer from distances above 3 sigma.)
// (--floor: per noisy case with a truth a line "floor:" with the noisy points' own distances to the
// truth and the point-set Chamfer of the points and of their projections onto the truth.)
// (--no-thin-walls: every case's normals prepared with CloudPrepOptions::thin_walls off, the
// orientation before session 9; --no-sheet-normals: with CloudPrepOptions::sheet_normals off,
// PCA's normals as before session 24.)
// (Cases uav-oriented, car-oriented, impeller-oriented: the model clouds with every estimated
// normal turned to the true side, an oracle for the orientation; name them in --cases.)
// (Cases blade-noise-free (the blade without noise, normals estimated) and body11 (the
// R-function model data/models/body11.rf): clean clouds for the family of the sheet normals.)
// (--exact-sigmas: one more case blade-exact-sigma-S per sigma S (cm): the blade with the true
// normals at that noise, for a noise family; name them in --cases.)
// (--holes: one more case blade-hole-R/U/V/S per item: the blade at noise S (cm) without the
// points within R (cm) of the loft's point S(U, V), for a family of missing patches; name them
// in --cases.)

#include "cloud_cases.h"
#include "poisson_baselines.h"
#include "surface_distance.h"

#include "interlin/reconstruction/clouds/choose_cloud_fit.h"
#include "interlin/reconstruction/clouds/cloud_implicit.h"
#include "interlin/reconstruction/clouds/fit_sliced_scan.h"
#include "interlin/reconstruction/clouds/hermite_rbf.h"
#include "interlin/reconstruction/clouds/noise_level.h"
#include "interlin/reconstruction/meshing/implicit_mesh.h"
#include "interlin/reconstruction/meshing/surface_mesh.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace interlin;
using namespace interlin::bench;
using Eigen::Index;

namespace {

constexpr int kSamples = 100000; // area-uniform samples per surface for the distances
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// x with up to 6 significant digits (labels and the worker's command line).
std::string fixed(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

struct Method {
  enum Kind { interlin, pcl, open3d, sectioned, hrbf } kind;
  int depth = 8;      // Poisson octree depth
  int resolution = 0; // interlin: grid cells along the box's longest side; 0: default_mesh_cell
  double cells_per_spacing = 2; // ... with resolution 0
  std::string fit;              // interlin: CloudFitOptions changes (--fit), empty for the defaults
  std::string label() const {
    if (kind == interlin)
      return "interlin (" +
             (resolution > 0 ? "resolution " + std::to_string(resolution)
                             : "cell spacing / " + fixed(cells_per_spacing)) +
             ")" + (fit.empty() ? "" : " [" + fit + "]");
    if (kind == sectioned)
      return "interlin sectioned (slices -> loft)";
    if (kind == hrbf)
      return "interlin Hermite RBF (cell spacing / " + fixed(cells_per_spacing) + ")";
    return std::string(kind == pcl ? "PCL Poisson" : "Open3D Poisson") + " (depth " +
           std::to_string(depth) + ")";
  }
};

// What a child reports (plain data through a pipe).
struct Result {
  double chamfer = kNaN, hausdorff = kNaN;        // mesh vs truth, / diagonal
  double zs_chamfer = kNaN, zs_hausdorff = kNaN;  // interlin's zero set vs truth, / diagonal
  double holdout_mean = kNaN, holdout_max = kNaN; // bunny: held-out points to the surface
  double rms_cm = kNaN, max_cm = kNaN; // mesh -> truth distances (cm), for the 1.5 sigma target
  double section_gap = kNaN;           // sectioned: fitted sections -> loft
  double seconds = kNaN, peak_mb = kNaN;
  long vertices = 0, leaves = 0;
  double noise = kNaN;
  // --diagnose: quantiles 50, 90, 99 % of mesh -> truth (A) and truth -> mesh (B) distances, and
  // the share of the Chamfer from distances above kTail sigma
  double qA[3] = {kNaN, kNaN, kNaN}, qB[3] = {kNaN, kNaN, kNaN}, tail_share = kNaN;
  char error[240] = {0};
};

constexpr double kTail = 3; // sigma: Gaussian noise exceeds it at 0.3 % of the points

double quantile(Eigen::VectorXd d, double q) {
  const auto k = static_cast<Index>(q * double(d.size() - 1));
  std::nth_element(d.data(), d.data() + k, d.data() + d.size());
  return d(k);
}

// CloudFitOptions from a --fit spec "KEY=V,KEY=V" (throws std::invalid_argument on a bad key or
// value); noise_x needs the points (estimate_noise), null: only checked.
CloudFitOptions fit_options(const std::string& spec, const Eigen::MatrixX3d* points) {
  CloudFitOptions o;
  std::stringstream in(spec);
  std::string item;
  while (std::getline(in, item, ',')) {
    const auto eq = item.find('=');
    const std::string key = item.substr(0, eq);
    std::size_t used = 0;
    double v = 0;
    try {
      v = std::stod(item.substr(eq == std::string::npos ? item.size() : eq + 1), &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (eq == std::string::npos || used != item.size() - eq - 1 ||
        !(v > 0 || ((key == "noise_aware" || key == "sample_coarse" || key == "exterior_side" ||
                     key == "smooth_points" || key == "split_slabs" || key == "split_pockets" ||
                     key == "edge_sheets") &&
                    v == 0)))
      throw std::invalid_argument(
          "--fit wants KEY=POSITIVE (noise_aware, sample_coarse, "
          "exterior_side, smooth_points, split_slabs, split_pockets, edge_sheets: 0 or 1), not '" +
          item + "'");
    if (key == "support")
      o.support = v;
    else if (key == "fit_ball")
      o.fit_ball = v;
    else if (key == "min_points")
      o.min_points = static_cast<int>(v);
    else if (key == "max_depth")
      o.max_depth = static_cast<int>(v);
    else if (key == "noise")
      o.noise = v;
    else if (key == "noise_aware")
      o.noise_aware = v >= 1;
    else if (key == "sample_coarse")
      o.sample_coarse = v >= 1;
    else if (key == "exterior_side")
      o.exterior_side = v >= 1;
    else if (key == "smooth_points")
      o.smooth_points = v >= 1;
    else if (key == "split_slabs")
      o.split_slabs = v >= 1;
    else if (key == "split_pockets")
      o.split_pockets = v >= 1;
    else if (key == "edge_sheets")
      o.edge_sheets = v >= 1;
    else if (key == "acceptance_per_rho")
      o.acceptance_per_rho = v;
    else if (key == "noise_x")
      o.noise = points ? v * estimate_noise(*points) : v;
    else
      throw std::invalid_argument("--fit: unknown key '" + key +
                                  "' (known: support, fit_ball, min_points, max_depth, noise, "
                                  "noise_x, noise_aware, acceptance_per_rho, sample_coarse, "
                                  "exterior_side, smooth_points, split_slabs, split_pockets, "
                                  "edge_sheets)");
  }
  return o;
}

long status_kb(const char* key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key, 0) == 0)
      return std::stol(line.substr(std::strlen(key)));
  return 0;
}

struct Reconstruction {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  ImplicitFunction implicit; // interlin only
  CloudFitInfo info;
  double section_gap = kNaN; // sectioned only
};

// --span-smoothing, passed to the workers (as --save is).
constexpr const char* kSpanSmoothingVariable = "BENCH_CLOUDS_SPAN_SMOOTHING";

// Kept apart from the point cloud: the slices' family and noise come from the points alone.
void reconstruct_sectioned(const PointCloud& c, int threads, Reconstruction& r) {
  const SliceFamily family = detect_slices(c.points);
  if (family.kind == SliceKind::none)
    throw std::runtime_error("no slices detected");
  SliceFitOptions fo;
  fo.threads = threads;
  const char* smoothing = std::getenv(kSpanSmoothingVariable);
  fo.smooth_span = !(smoothing && std::string(smoothing) == "off");
  const SlicedFit fit = fit_sliced_scan(c.points, family, fo);
  SurfaceMeshOptions so;
  so.nu = 1200;
  so.nv = 200;
  for (double v : fit.loft.section_v)
    so.required_v.push_back(v);
  surface_mesh(to_piecewise(fit.loft.surface), so, r.V, r.F);
  r.section_gap = fit.section_gap;
  r.info.noise = fit.noise;
}

// interlin's default for a cloud: the Hermite RBF when the cloud is sparse, its normals are
// measured and the hold-out prefers it (choose_cloud_fit), as `interlin implicit --fit auto`
// does.
bool hermite_by_default(const PointCloud& c, bool normals_measured, int threads) {
  if (!hermite_rbf_offered(c, normals_measured))
    return false;
  CloudFitOptions o;
  o.threads = threads;
  return choose_cloud_fit(c, o).hermite;
}

Reconstruction reconstruct(const Method& m, const PointCloud& c, bool normals_measured,
                           int threads) {
  Reconstruction r;
  const bool hermite =
      m.kind == Method::hrbf || (m.kind == Method::interlin && m.fit.empty() && m.resolution == 0 &&
                                 hermite_by_default(c, normals_measured, threads));
  if (hermite || m.kind == Method::interlin) {
    if (hermite) {
      r.implicit = hermite_rbf_function(std::make_shared<const HermiteRbf>(fit_hermite_rbf(c)));
    } else {
      CloudFitOptions o = fit_options(m.fit, &c.points);
      o.threads = threads;
      r.implicit = cloud_implicit_function(
          std::make_shared<const CloudImplicit>(fit_cloud_implicit(c, o, &r.info)));
    }
    ImplicitMeshOptions mo;
    mo.resolution = m.resolution;
    if (m.resolution == 0)
      mo.cell = default_mesh_cell(r.implicit, r.implicit.box, m.cells_per_spacing);
    mo.threads = threads;
    implicit_mesh(r.implicit, mo, r.V, r.F);
  } else if (m.kind == Method::sectioned) {
    reconstruct_sectioned(c, threads, r);
  } else if (m.kind == Method::pcl) {
    pcl_poisson(c.points, c.normals, m.depth, threads, r.V, r.F);
  } else {
    open3d_poisson(c.points, c.normals, m.depth, threads, r.V, r.F);
  }
  return r;
}

// Samples restricted to the stations of a sectioned case.
Eigen::MatrixX3d in_range(const CloudCase& c, const Eigen::MatrixX3d& P) {
  if (!c.sectioned())
    return P;
  std::vector<Index> keep;
  for (Index i = 0; i < P.rows(); ++i) {
    const double s = c.station(P.row(i).transpose());
    if (s >= c.station_lo && s <= c.station_hi)
      keep.push_back(i);
  }
  return P(keep, Eigen::all);
}

// Moves points onto F = 0 along the gradient (three Newton steps).
Eigen::MatrixX3d onto_zero_set(const ImplicitFunction& F, Eigen::MatrixX3d P) {
  for (int it = 0; it < 3; ++it) {
    Eigen::VectorXd v(P.rows());
    Points3 G(P.rows(), 3);
    F.gradient(P, v, G);
    for (Index i = 0; i < P.rows(); ++i) {
      const double g2 = G.row(i).squaredNorm();
      if (g2 > 0)
        P.row(i) -= v(i) / g2 * G.row(i);
    }
  }
  return P;
}

void measure(const CloudCase& c, const MeshDistance& truth, const Eigen::MatrixX3d& truth_samples,
             const Reconstruction& r, Result& out) {
  if (r.F.rows() == 0) {
    std::snprintf(out.error, sizeof out.error, "empty mesh");
    return;
  }
  const double diag = c.truth.diagonal;
  const MeshDistance recon(r.V, r.F);
  const Eigen::MatrixX3d A = in_range(c, sample_mesh(r.V, r.F, kSamples, 99).points);
  const Eigen::VectorXd dA = truth(A), dB = recon(truth_samples);
  out.chamfer = 0.5 * (dA.mean() + dB.mean()) / diag;
  out.rms_cm = std::sqrt(dA.squaredNorm() / double(dA.size()));
  out.max_cm = dA.maxCoeff();
  out.hausdorff = std::max(dA.maxCoeff(), dB.maxCoeff()) / diag;
  if (c.noise > 0) {
    for (int k = 0; k < 3; ++k) {
      const double q = std::array<double, 3>{0.5, 0.9, 0.99}[size_t(k)];
      out.qA[k] = quantile(dA, q) / c.noise;
      out.qB[k] = quantile(dB, q) / c.noise;
    }
    const double t = kTail * c.noise;
    const double tail = (dA.array() > t).select(dA.array(), 0).sum() / double(dA.size()) +
                        (dB.array() > t).select(dB.array(), 0).sum() / double(dB.size());
    out.tail_share = tail / (dA.mean() + dB.mean());
  }
  if (r.implicit.value) {
    const Eigen::VectorXd zA = truth(onto_zero_set(r.implicit, A));
    Eigen::VectorXd v(truth_samples.rows());
    Points3 G(truth_samples.rows(), 3);
    r.implicit.gradient(truth_samples, v, G);
    const Eigen::ArrayXd zB = v.array().abs() / G.rowwise().norm().array().max(1e-300);
    out.zs_chamfer = 0.5 * (zA.mean() + zB.mean()) / diag;
    out.zs_hausdorff = std::max(zA.maxCoeff(), zB.maxCoeff()) / diag;
  }
}

std::string num(double x, int digits = 3) {
  if (std::isnan(x))
    return "–";
  std::ostringstream s;
  s.precision(digits);
  s << x;
  return s.str();
}

// --floor: what the points themselves score against the truth. The noisy points' mean distance
// to the truth (about 0.8 sigma for Gaussian noise), and the point-set Chamfer (the mean of the
// points' distances to the truth and of the truth samples' distances to the nearest point) of
// the noisy points and of their projections onto the truth: a perfect denoiser that outputs
// points still scores the latter, the sampling term; a surface does not (docs/benchmarks.md).
std::string noise_floor(const CloudCase& c) {
  const double diag = c.truth.diagonal;
  const MeshDistance truth(c.truth.V, c.truth.F);
  const Eigen::MatrixX3d samples =
      in_range(c, sample_mesh(c.truth.V, c.truth.F, kSamples, 98).points);
  const Eigen::MatrixX3d P = in_range(c, c.cloud.points);
  const double to_truth = truth(P).mean();
  const double noisy = 0.5 * (to_truth + PointSetDistance(P)(samples).mean());
  const double gap = PointSetDistance(truth.closest(P))(samples).mean();
  std::ostringstream s;
  s << "\nfloor: points -> truth mean " << num(to_truth / diag) << " (" << num(to_truth / c.noise)
    << " sigma); point-set Chamfer of the noisy points " << num(noisy / diag)
    << ", of their projections onto the truth " << num(0.5 * gap / diag)
    << " (truth -> nearest projection mean " << num(gap / c.noise) << " sigma)\n";
  return s.str();
}

// Ten-fold hold-out for a cloud without a truth: distance of each held-out point to the surface
// fitted to the other nine tenths.
void holdout(const Method& m, const CloudCase& c, int threads, Result& out) {
  const Index n = c.cloud.points.rows();
  std::vector<Index> order(static_cast<size_t>(n));
  std::iota(order.begin(), order.end(), Index{0});
  std::shuffle(order.begin(), order.end(), std::mt19937(5));
  const double diag =
      (c.cloud.points.colwise().maxCoeff() - c.cloud.points.colwise().minCoeff()).norm();
  double sum = 0, mx = 0;
  for (int fold = 0; fold < 10; ++fold) {
    std::vector<Index> train, test;
    for (Index k = 0; k < n; ++k)
      (k % 10 == fold ? test : train).push_back(order[static_cast<size_t>(k)]);
    PointCloud t;
    t.points = c.cloud.points(train, Eigen::all);
    t.normals = c.cloud.normals(train, Eigen::all);
    const Reconstruction r = reconstruct(m, t, c.normals_measured, threads);
    const Eigen::VectorXd d = MeshDistance(r.V, r.F)(c.cloud.points(test, Eigen::all));
    sum += d.sum();
    mx = std::max(mx, d.maxCoeff());
  }
  out.holdout_mean = sum / double(n) / diag;
  out.holdout_max = mx / diag;
}

// --save passes its directory to the workers in this environment variable.
constexpr const char* kSaveVariable = "BENCH_CLOUDS_SAVE";

void save_obj(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  std::ofstream out(path);
  out.precision(9);
  for (Index i = 0; i < V.rows(); ++i)
    out << "v " << V(i, 0) << ' ' << V(i, 1) << ' ' << V(i, 2) << '\n';
  for (Index i = 0; i < F.rows(); ++i)
    out << "f " << F(i, 0) + 1 << ' ' << F(i, 1) + 1 << ' ' << F(i, 2) + 1 << '\n';
}

// A method's label as part of a file name: '/' (interlin's "cell spacing / 2") and spaces become
// '_'.
std::string file_name(std::string label) {
  std::replace_if(
      label.begin(), label.end(), [](char ch) { return ch == '/' || ch == ' '; }, '_');
  return label;
}

// Reconstructs, then (after its memory is read) measures against the truth when the case has
// one, else by hold-out.
Result run_child(const Method& m, const CloudCase& c, int threads) {
  Result out;
  try {
    const long before = status_kb("VmRSS:");
    const auto t0 = std::chrono::steady_clock::now();
    const Reconstruction r = reconstruct(m, c.cloud, c.normals_measured, threads);
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    out.peak_mb = double(status_kb("VmHWM:") - before) / 1024.0;
    if (const char* dir = std::getenv(kSaveVariable))
      save_obj(std::string(dir) + "/" + c.name + "." + file_name(m.label()) + ".obj", r.V, r.F);
    out.vertices = static_cast<long>(r.V.rows());
    out.leaves = r.info.leaves;
    out.noise = r.info.noise;
    out.section_gap = r.section_gap;
    if (c.truth.F.rows() > 0) {
      const MeshDistance truth(c.truth.V, c.truth.F);
      const Eigen::MatrixX3d samples =
          in_range(c, sample_mesh(c.truth.V, c.truth.F, kSamples, 98).points);
      measure(c, truth, samples, r, out);
    } else {
      holdout(m, c, threads, out);
    }
  } catch (const std::exception& e) {
    std::snprintf(out.error, sizeof out.error, "%s", e.what());
  }
  return out;
}

// Runs one method in a fresh worker process (`self` --worker ...) and returns its report.
Result run_worker(const std::string& self, const std::string& case_file, const Method& m,
                  int threads) {
  int fd[2];
  if (pipe(fd) != 0)
    throw std::runtime_error("pipe failed");
  std::cout.flush();
  const std::vector<std::string> args{self,
                                      "--worker",
                                      case_file,
                                      std::to_string(int(m.kind)),
                                      std::to_string(m.depth),
                                      std::to_string(m.resolution),
                                      std::to_string(threads),
                                      std::to_string(fd[1]),
                                      m.fit.empty() ? "-" : m.fit,
                                      fixed(m.cells_per_spacing)};
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    std::vector<char*> argv;
    for (const std::string& a : args)
      argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(self.c_str(), argv.data());
    _exit(127);
  }
  close(fd[1]);
  Result r;
  const ssize_t got = read(fd[0], &r, sizeof r);
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (got != sizeof r)
    std::snprintf(r.error, sizeof r.error, "the worker died (status %d)", status);
  return r;
}

// The worker: loads the case, runs the method, writes its Result to file descriptor `fd`.
int worker(char** argv) {
  const CloudCase c = load_case(argv[2]);
  const Method m{static_cast<Method::Kind>(std::stoi(argv[3])), std::stoi(argv[4]),
                 std::stoi(argv[5]), std::stod(argv[9]),
                 std::string(argv[8]) == "-" ? "" : argv[8]};
  const int threads = std::stoi(argv[6]), fd = std::stoi(argv[7]);
  const Result r = run_child(m, c, threads);
  return write(fd, &r, sizeof r) == sizeof r ? 0 : 1;
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ','))
    out.push_back(item);
  return out;
}

} // namespace

// The command line, checked: an unknown option, a missing or malformed value, an unknown method
// or case name is a usage error (one line, exit 2), never a crash or a silently empty run.
struct Options {
  std::string cases = "all", methods = "all";
  int points = 100000, resolution = 0, threads = 2; // resolution 0: auto
  double cells_per_spacing = 2;
  std::vector<int> depths{8, 9};
  std::vector<std::string> fits;            // --fit, one interlin row each
  std::vector<std::string> exact_sigmas;    // --exact-sigmas: cases blade-exact-sigma-S
  std::vector<std::array<double, 4>> holes; // --holes: R, U, V, S of cases blade-hole-R/U/V/S
  std::vector<std::string> hole_keys;
  bool diagnose = false, floor = false, no_thin_walls = false, no_sheet_normals = false;
};

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

int positive(const std::string& option, const std::string& v) {
  std::size_t used = 0;
  int x = 0;
  try {
    x = std::stoi(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != v.size() || x <= 0)
    throw UsageError(option + " wants a positive integer, not '" + v + "'");
  return x;
}

// v as a number; NaN unless the whole of v is one.
double parse_number(const std::string& v) {
  std::size_t used = 0;
  double x = kNaN;
  try {
    x = std::stod(v, &used);
  } catch (const std::exception&) {
    return kNaN;
  }
  return used == v.size() ? x : kNaN;
}

// Each name of the comma-separated list must be one of `known` (or the list is "all").
void check_names(const std::string& option, const std::string& list,
                 const std::vector<std::string>& known) {
  if (list == "all")
    return;
  for (const std::string& name : split(list))
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      std::string names;
      for (const std::string& k : known)
        names += (names.empty() ? "" : ",") + k;
      throw UsageError(option + ": unknown name '" + name + "' (known: " + names + ")");
    }
}

Options parse_options(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--diagnose" || a == "--floor" || a == "--no-thin-walls" ||
        a == "--no-sheet-normals") { // flags without a value
      (a == "--floor"              ? o.floor
       : a == "--diagnose"         ? o.diagnose
       : a == "--no-sheet-normals" ? o.no_sheet_normals
                                   : o.no_thin_walls) = true;
      --i;
      continue;
    }
    if (i + 1 >= argc)
      throw UsageError(a + " wants a value");
    const std::string v = argv[i + 1];
    if (a == "--cases")
      o.cases = v;
    else if (a == "--points")
      o.points = positive(a, v);
    else if (a == "--resolution")
      o.resolution = v == "auto" ? 0 : positive(a + " (cells or auto)", v);
    else if (a == "--cells-per-spacing") {
      o.cells_per_spacing = parse_number(v);
      if (!(o.cells_per_spacing > 0))
        throw UsageError(a + " wants a number > 0, not '" + v + "'");
    } else if (a == "--threads")
      o.threads = positive(a, v);
    else if (a == "--methods")
      o.methods = v;
    else if (a == "--save")
      setenv(kSaveVariable, v.c_str(), 1);
    else if (a == "--span-smoothing") {
      if (v != "auto" && v != "off")
        throw UsageError(a + " wants auto or off, not '" + v + "'");
      setenv(kSpanSmoothingVariable, v.c_str(), 1);
    } else if (a == "--fit") {
      try {
        fit_options(v, nullptr);
      } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
      }
      o.fits.push_back(v);
    } else if (a == "--exact-sigmas") {
      for (const std::string& s : split(v)) {
        if (!(parse_number(s) >= 0))
          throw UsageError(a + " wants sigmas >= 0 (cm), not '" + s + "'");
        o.exact_sigmas.push_back(s);
      }
    } else if (a == "--holes") {
      for (const std::string& h : split(v)) {
        std::array<double, 4> x{};
        size_t at = 0;
        for (int k = 0; k < 4; ++k) {
          const size_t slash = k < 3 ? h.find('/', at) : h.size();
          x[size_t(k)] = slash == std::string::npos ? -1 : parse_number(h.substr(at, slash - at));
          at = slash + 1;
        }
        if (!(x[0] > 0 && x[1] >= 0 && x[1] <= 1 && x[2] >= 0 && x[2] <= 1 && x[3] >= 0))
          throw UsageError(a + " wants R/U/V/S (R > 0 cm, U and V in [0, 1], S >= 0 cm), not '" +
                           h + "'");
        o.holes.push_back(x);
        o.hole_keys.push_back("blade-hole-" + h);
      }
    } else if (a == "--depths") {
      o.depths.clear();
      for (const std::string& d : split(v))
        o.depths.push_back(positive(a, d));
    } else
      throw UsageError("unknown option " + a);
  }
  check_names("--methods", o.methods, {"interlin", "hrbf", "pcl", "open3d", "none"});
  return o;
}

int main(int argc, char** argv) {
  if (argc == 10 && std::string(argv[1]) == "--worker")
    return worker(argv);
  const std::string self = "/proc/self/exe";
  Options o;
  try {
    o = parse_options(argc, argv);
  } catch (const UsageError& e) {
    std::cerr << "bench_clouds: " << e.what() << "\n";
    return 2;
  }
  CloudPrepOptions preparation;
  preparation.thin_walls = !o.no_thin_walls;
  if (o.no_sheet_normals)
    preparation.sheet_normals = SheetNormals::off;
  set_case_preparation(preparation);
  const std::string &cases = o.cases, &methods_wanted = o.methods;
  const int points = o.points, resolution = o.resolution, threads = o.threads;
  const std::vector<int>& depths = o.depths;
  const std::vector<std::string> wanted = split(cases);
  auto want = [&](const std::string& key) {
    return cases == "all" || std::find(wanted.begin(), wanted.end(), key) != wanted.end();
  };
  std::vector<std::pair<std::string, std::function<CloudCase()>>> all{
      {"bunny", [] { return bunny(); }},
      {"blade", [&] { return blade_unstructured(points, 0.005, 0, 1); }},
      {"blade-noisy", [&] { return blade_unstructured(points, 0.02, 0, 2); }},
      {"blade-hole", [&] { return blade_unstructured(points, 0.005, 0.75, 3); }},
      {"blade-oriented",
       [&] { return blade_unstructured(points, 0.005, 0, 1, Normals::oriented); }},
      {"blade-noisy-oriented",
       [&] { return blade_unstructured(points, 0.02, 0, 2, Normals::oriented); }},
      {"blade-clean", [&] { return blade_unstructured(points, 0, 0, 1, Normals::exact); }},
      {"blade-noise-free", [&] { return blade_unstructured(points, 0, 0, 1); }},
      {"blade-exact", [&] { return blade_unstructured(points, 0.005, 0, 1, Normals::exact); }},
      {"blade-noisy-exact", [&] { return blade_unstructured(points, 0.02, 0, 2, Normals::exact); }},
      {"slices", [] { return blade_slices(false, 30, 500, 0.005, 4); }},
      {"slices-noisy", [] { return blade_slices(false, 30, 500, 0.02, 5); }},
      {"radial", [] { return blade_slices(true, 30, 500, 0.005, 6); }},
      {"radial-noisy", [] { return blade_slices(true, 30, 500, 0.02, 13); }},
      {"impeller", [&] { return model_cloud("impeller", points, 0, 7); }},
      {"uav", [&] { return model_cloud("uav", points, 0, 8); }},
      {"uav-oriented", [&] { return model_cloud("uav", points, 0, 8, true); }},
      {"car-oriented", [&] { return model_cloud("car", points, 0, 9, true); }},
      {"impeller-oriented", [&] { return model_cloud("impeller", points, 0, 7, true); }},
      {"car", [&] { return model_cloud("car", points, 0, 9); }},
      {"valve", [&] { return model_cloud("valve", points, 0, 10); }},
      {"naca0011_plate", [&] { return model_cloud("naca0011_plate", points, 0, 11); }},
      {"body11", [&] { return model_cloud("body11", points, 0, 14); }},
      {"valve-noisy", [&] { return model_cloud("valve", points, 0.001, 12); }}};
  for (const std::string& s : o.exact_sigmas) // the true normals: the fit alone against the noise
    all.push_back({"blade-exact-sigma-" + s, [&points, s] {
                     return blade_unstructured(points, std::stod(s), 0, 1, Normals::exact);
                   }});
  for (size_t i = 0; i < o.holes.size(); ++i)
    all.push_back({o.hole_keys[i], [&points, h = o.holes[i]] {
                     return blade_unstructured(points, h[3], h[0], 3, Normals::estimated, h[1],
                                               h[2]);
                   }});
  std::vector<std::string> keys;
  for (const auto& entry : all)
    keys.push_back(entry.first);
  try {
    check_names("--cases", cases, keys);
  } catch (const UsageError& e) {
    std::cerr << "bench_clouds: " << e.what() << "\n";
    return 2;
  }

  std::cout << "# bench_clouds: points " << points << ", interlin "
            << (resolution > 0 ? "resolution " + std::to_string(resolution)
                               : "cell spacing / " + fixed(o.cells_per_spacing))
            << ", threads " << threads << "\n";
  std::ostringstream summary;
  summary << "\n| cloud | better Poisson | its Chamfer | its time [s] | interlin Chamfer | "
             "ratio | interlin time [s] | time ratio |\n|---|---|---|---|---|---|---|---|\n";
  for (const auto& [key, make] : all) {
    if (!want(key))
      continue;
    const CloudCase c = make();
    std::cout << "\n## " << c.name << " (" << key << ")\n\n"
              << c.description << "; " << c.cloud.points.rows() << " points given to every method";
    const std::string case_file = "/tmp/bench_clouds_" + std::to_string(getpid()) + ".case";
    save_case(c, case_file);
    if (const char* dir = std::getenv(kSaveVariable)) {
      std::ofstream xyzn(std::string(dir) + "/" + c.name + ".xyzn");
      xyzn.precision(9);
      for (Index i = 0; i < c.cloud.points.rows(); ++i)
        xyzn << c.cloud.points.row(i) << ' ' << c.cloud.normals.row(i) << '\n';
    }
    if (c.inward >= 0)
      std::cout << "; " << c.inward << " normals ("
                << num(100.0 * double(c.inward) / double(c.cloud.points.rows()), 3)
                << " %) point inward against the true ones";
    if (c.sectioned()) {
      const SliceFamily f = detect_slices(c.cloud.points);
      std::cout << "; slices detected: " << f.members.size() << " ("
                << (f.kind == SliceKind::planar   ? "planar"
                    : f.kind == SliceKind::radial ? "radial"
                                                  : "none")
                << ", spread " << num(f.spread, 3) << " cm)";
    }
    if (c.truth.F.rows() > 0)
      std::cout << "; truth: " << c.truth.F.rows() << " triangles, diagonal "
                << num(c.truth.diagonal, 4) << ", its own sag " << num(c.truth.sag, 2);
    std::cout << "\n\n| method | Chamfer / diag | Hausdorff / diag | zero-set Chamfer | "
                 "hold-out mean / max | time [s] | peak MB | vertices |\n"
                 "|---|---|---|---|---|---|---|---|\n";
    const std::vector<std::string> mw = split(methods_wanted);
    auto run_method = [&](const std::string& m) {
      return methods_wanted == "all" || std::find(mw.begin(), mw.end(), m) != mw.end();
    };
    std::vector<Method> methods;
    if (run_method("interlin")) {
      if (c.sectioned())
        methods.push_back({Method::sectioned, 0, 0, 0, ""});
      methods.push_back({Method::interlin, 0, resolution, o.cells_per_spacing, ""});
      for (const std::string& fit : o.fits)
        methods.push_back({Method::interlin, 0, resolution, o.cells_per_spacing, fit});
    }
    if (run_method("hrbf"))
      methods.push_back({Method::hrbf, 0, 0, o.cells_per_spacing, ""});
    for (int d : depths) {
      if (run_method("pcl"))
        methods.push_back({Method::pcl, d, 0, 0, ""});
      if (run_method("open3d"))
        methods.push_back({Method::open3d, d, 0, 0, ""});
    }
    double best = kNaN, best_time = kNaN, ours = kNaN, our_time = kNaN;
    std::string best_label;
    std::ostringstream notes;
    for (const Method& m : methods) {
      const Result r = run_worker(self, case_file, m, threads);
      const double score = c.truth.F.rows() > 0 ? r.chamfer : r.holdout_mean;
      std::cout << "| " << m.label() << " | " << num(r.chamfer) << " | " << num(r.hausdorff)
                << " | " << num(r.zs_chamfer) << " | " << num(r.holdout_mean) << " / "
                << num(r.holdout_max) << " | " << num(r.seconds) << " | " << num(r.peak_mb) << " | "
                << r.vertices << (r.error[0] ? std::string(" | ") + r.error : "") << " |\n";
      std::cout.flush();
      if (o.diagnose && !std::isnan(r.tail_share))
        notes << "\ndistances: " << m.label() << ": mesh -> truth p50/p90/p99 " << num(r.qA[0])
              << " / " << num(r.qA[1]) << " / " << num(r.qA[2]) << " sigma, truth -> mesh "
              << num(r.qB[0]) << " / " << num(r.qB[1]) << " / " << num(r.qB[2])
              << " sigma; Chamfer share from distances > " << kTail << " sigma "
              << num(100 * r.tail_share) << " %\n";
      if (m.kind == Method::sectioned && !std::isnan(r.rms_cm))
        notes << "\nsectioned: distance to the truth rms " << num(r.rms_cm / c.noise)
              << " sigma, max " << num(r.max_cm / c.noise) << " sigma; fitted sections to "
              << "the loft " << num(r.section_gap) << " cm (noise used " << num(r.noise)
              << " cm)\n";
      if (m.kind == (c.sectioned() ? Method::sectioned : Method::interlin) && m.fit.empty()) {
        ours = score;
        our_time = r.seconds;
      } else if ((m.kind == Method::pcl || m.kind == Method::open3d) && !std::isnan(score) &&
                 (std::isnan(best) || score < best)) {
        best = score;
        best_time = r.seconds;
        best_label = m.label();
      }
    }
    std::cout << notes.str();
    if (o.floor && c.truth.F.rows() > 0 && c.noise > 0)
      std::cout << noise_floor(c);
    std::remove(case_file.c_str());
    summary << "| " << c.name << " | " << best_label << " | " << num(best) << " | "
            << num(best_time) << " | " << num(ours) << " | " << num(ours / best, 2) << " | "
            << num(our_time) << " | " << num(our_time / best_time, 2) << " |\n";
  }
  std::cout << summary.str();
  return 0;
}
