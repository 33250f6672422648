#include "cloud_cases.h"

#include "bench_data.h"

#include "interlin/interflatation/rfunctions/model.h"
#include "interlin/reconstruction/clouds/prepare_cloud.h"
#include "interlin/reconstruction/clouds/read_point_cloud.h"
#include "interlin/reconstruction/clouds/sample_mesh.h"
#include "interlin/reconstruction/loft/closest_point.h"
#include "interlin/reconstruction/loft/loft.h"
#include "interlin/reconstruction/meshing/implicit_mesh.h"
#include "interlin/reconstruction/meshing/surface_mesh.h"

#include <cmath>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>

namespace interlin::bench {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::Vector3d;

namespace {

// The capped loft of all 13 sections and its surface in explicit form.
struct Blade {
  LoftResult loft;
  PiecewiseSurface S;
  double sign = 1; // S_u x S_v * sign points out of the blade
  TruthMesh truth;
};

Vector3d surface_normal(const Blade& b, double u, double v) {
  return (b.sign * evaluate(b.S, u, v, 1, 0).cross(evaluate(b.S, u, v, 0, 1))).normalized();
}

const Blade& blade() {
  static const std::unique_ptr<Blade> b = [] {
    auto r = std::make_unique<Blade>();
    r->loft = loft_sections(rotor37_sections());
    r->S = to_piecewise(r->loft.surface);
    // Orientation: S_u x S_v against the direction from the section's centroid.
    double s = 0;
    for (int k = 0; k < 16; ++k) {
      const double v = (k + 0.5) / 16, u = 0.13;
      Vector3d c = Vector3d::Zero();
      for (int i = 0; i < 64; ++i)
        c += evaluate(r->S, i / 64.0, v) / 64;
      const Vector3d n = evaluate(r->S, u, v, 1, 0).cross(evaluate(r->S, u, v, 0, 1));
      s += n.dot(evaluate(r->S, u, v) - c);
    }
    r->sign = s > 0 ? 1 : -1;
    SurfaceMeshOptions o;
    o.nu = 2400;
    o.nv = 400;
    o.cap = true;
    surface_mesh(r->S, o, r->truth.V, r->truth.F);
    r->truth.diagonal = (r->truth.V.colwise().maxCoeff() - r->truth.V.colwise().minCoeff()).norm();
    // Sag: the distance of the lateral triangles' centroids from the surface (every 7th
    // triangle; the caps are flat fills, they are the truth there).
    const Index lateral = r->truth.F.rows() - 2 * (o.nu - 2);
    Eigen::MatrixXd C(lateral / 7, 3);
    for (Index k = 0; k < C.rows(); ++k) {
      const Index f = 7 * k;
      C.row(k) = (r->truth.V.row(r->truth.F(f, 0)) + r->truth.V.row(r->truth.F(f, 1)) +
                  r->truth.V.row(r->truth.F(f, 2))) /
                 3;
    }
    r->truth.sag = project_to_surface(r->S, C).distance.maxCoeff();
    return r;
  }();
  return *b;
}

// n points uniform by area on the blade's lateral surface (exact points and normals) and caps.
PointCloud sample_blade(int n, unsigned seed) {
  const Blade& b = blade();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0, 1);
  // Area per parameter cell of a 1024 x 256 grid, the caps' area from their triangles.
  const int nu = 1024, nv = 256;
  std::vector<double> cum;
  double total = 0;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const double u = (i + 0.5) / nu, v = (j + 0.5) / nv;
      total += evaluate(b.S, u, v, 1, 0).cross(evaluate(b.S, u, v, 0, 1)).norm() / (nu * nv);
      cum.push_back(total);
    }
  const Index caps = 2 * (2400 - 2); // surface_mesh appends the two cap fills last
  const Eigen::MatrixXi capF = b.truth.F.bottomRows(caps);
  double cap_area = 0;
  for (Index f = 0; f < caps; ++f) {
    const Eigen::RowVector3d p0 = b.truth.V.row(capF(f, 0)), p1 = b.truth.V.row(capF(f, 1)),
                             p2 = b.truth.V.row(capF(f, 2));
    cap_area += 0.5 * (p1 - p0).cross(p2 - p0).norm();
  }
  const int n_cap = static_cast<int>(std::lround(n * cap_area / (cap_area + total)));
  PointCloud c;
  c.points.resize(n, 3);
  c.normals.resize(n, 3);
  for (int k = 0; k < n - n_cap; ++k) {
    const double a = U(rng) * total;
    const Index cell = std::lower_bound(cum.begin(), cum.end(), a) - cum.begin();
    const double u = (double(cell % nu) + U(rng)) / nu, v = (double(cell / nu) + U(rng)) / nv;
    c.points.row(k) = evaluate(b.S, u, v).transpose();
    c.normals.row(k) = surface_normal(b, u, v).transpose();
  }
  const PointCloud cap = sample_mesh(b.truth.V, capF, n_cap, seed + 1);
  c.points.bottomRows(n_cap) = cap.points;
  c.normals.bottomRows(n_cap) = cap.normals;
  return c;
}

void add_noise(PointCloud& c, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> G(0, sigma);
  for (Index i = 0; i < c.points.rows(); ++i)
    for (int a = 0; a < 3; ++a)
      c.points(i, a) += G(rng);
}

CloudPrepOptions preparation; // set_case_preparation

// What an unstructured scan gives every method: points only; normals from prepare_cloud.
// `inward`: how many of those normals point against the scan's true normals (prepare_cloud
// keeps the points' order, so the kept points are matched as a subsequence); with `orient` they
// are flipped (an oracle orientation, for the bench's experiments).
PointCloud prepared(const std::string& name, const PointCloud& scan, Index& inward,
                    bool orient = false) {
  PointCloud p;
  p.points = scan.points;
  p = prepare_cloud(name, p, preparation);
  inward = 0;
  for (Index i = 0, j = 0; i < p.points.rows(); ++i, ++j) {
    while (j < scan.points.rows() && scan.points.row(j) != p.points.row(i))
      ++j;
    if (j < scan.points.rows() && p.normals.row(i).dot(scan.normals.row(j)) < 0) {
      ++inward;
      if (orient)
        p.normals.row(i) *= -1;
    }
  }
  return p;
}

// The point on the blade's section curve at parameter u where station(S(u, v)) = s (bisection
// on v, then Newton): the section of the slice surface station = s.
template <class Station>
double slice_v(const Blade& b, double u, double s, const Station& station) {
  double lo = 0, hi = 1;
  const double flo = station(evaluate(b.S, u, lo)) - s;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    const double fm = station(evaluate(b.S, u, mid)) - s;
    ((fm < 0) == (flo < 0) ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

} // namespace

namespace {
std::string shortest(double x) { // 0.25, not 0.250000
  std::ostringstream s;
  s << x;
  return s.str();
}
} // namespace

CloudCase blade_unstructured(int n, double sigma, double hole, unsigned seed, Normals normals,
                             double hole_u, double hole_v) {
  const Blade& b = blade();
  CloudCase c;
  c.name = "rotor37 " + std::to_string(n / 1000) + "k sigma " + std::to_string(sigma).substr(0, 5) +
           (hole > 0 ? " hole" : "") +
           (hole > 0 && (hole_u != 0.25 || hole_v != 0.5)
                ? " " + shortest(hole) + " at " + shortest(hole_u) + "/" + shortest(hole_v)
                : "") +
           (normals == Normals::exact      ? " exact normals"
            : normals == Normals::oriented ? " oriented normals"
                                           : "");
  c.description = std::to_string(n) + " points uniform by area on the capped loft, sigma " +
                  std::to_string(sigma) + " cm" +
                  (hole > 0 ? ", no points within " + std::to_string(hole) + " cm of S(" +
                                  shortest(hole_u) + ", " + shortest(hole_v) + ")"
                            : "") +
                  (normals == Normals::exact      ? ", the true normals"
                   : normals == Normals::oriented ? ", estimated normals turned to the true side"
                                                  : "");
  PointCloud scan = sample_blade(n, seed);
  if (sigma > 0)
    add_noise(scan, sigma, seed + 7);
  if (hole > 0) {
    const Vector3d centre = evaluate(b.S, hole_u, hole_v);
    std::vector<Index> keep;
    for (Index i = 0; i < scan.points.rows(); ++i)
      if ((scan.points.row(i).transpose() - centre).norm() > hole)
        keep.push_back(i);
    PointCloud k;
    k.points = scan.points(keep, Eigen::all);
    k.normals = scan.normals(keep, Eigen::all);
    scan = k;
  }
  if (normals == Normals::exact) {
    c.cloud = scan;
    c.inward = 0;
    c.normals_measured = true;
  } else {
    c.cloud = prepared(c.name, scan, c.inward, normals == Normals::oriented);
  }
  c.truth = b.truth;
  c.noise = sigma;
  return c;
}

CloudCase blade_slices(bool radial, int slices, int per_slice, double sigma, unsigned seed) {
  const Blade& b = blade();
  CloudCase c;
  c.name = std::string("rotor37 ") + (radial ? "radial" : "planar") + " slices sigma " +
           std::to_string(sigma).substr(0, 5);
  c.stations = radial ? CloudCase::Station::radius : CloudCase::Station::x;
  c.noise = sigma;
  c.truth = b.truth;
  const auto station = [&c](const Vector3d& p) { return c.station(p); };
  // Stations strictly between hub and tip: the hub and tip sections' station ranges excluded.
  double hub_max = -1e300, tip_min = 1e300;
  for (int i = 0; i < 200; ++i) {
    hub_max = std::max(hub_max, c.station(evaluate(b.S, i / 200.0, 0.0)));
    tip_min = std::min(tip_min, c.station(evaluate(b.S, i / 200.0, 1.0)));
  }
  const double margin = 0.05 * (tip_min - hub_max);
  c.station_lo = hub_max + margin;
  c.station_hi = tip_min - margin;
  c.description = std::to_string(slices) + (radial ? " cylinders r" : " planes x") + " = " +
                  std::to_string(c.station_lo).substr(0, 5) + " .. " +
                  std::to_string(c.station_hi).substr(0, 5) + " cm, " + std::to_string(per_slice) +
                  " points each (even arc length), sigma " + std::to_string(sigma) + " cm";
  PointCloud scan;
  scan.points.resize(slices * per_slice, 3);
  scan.normals.resize(slices * per_slice, 3);
  const int dense = 8 * per_slice;
  for (int k = 0; k < slices; ++k) {
    const double s = c.station_lo + (c.station_hi - c.station_lo) * k / (slices - 1);
    // the slice polyline on a dense u grid, then even arc length
    std::vector<double> len{0};
    std::vector<Vector3d> pts;
    for (int i = 0; i <= dense; ++i) {
      const double u = double(i) / dense;
      pts.push_back(evaluate(b.S, u, slice_v(b, u, s, station)));
      if (i > 0)
        len.push_back(len.back() + (pts[i] - pts[i - 1]).norm());
    }
    for (int j = 0; j < per_slice; ++j) {
      const double target = len.back() * j / per_slice;
      const size_t i = std::upper_bound(len.begin(), len.end(), target) - len.begin() - 1;
      const double t = (target - len[i]) / (len[i + 1] - len[i]);
      const double u = (double(i) + t) / dense, v = slice_v(b, u, s, station);
      scan.points.row(k * per_slice + j) = evaluate(b.S, u, v).transpose();
      scan.normals.row(k * per_slice + j) = surface_normal(b, u, v).transpose();
    }
  }
  add_noise(scan, sigma, seed);
  c.cloud = scan;
  return c;
}

CloudCase model_cloud(const std::string& name, int n, double sigma, unsigned seed, bool orient) {
  const ImplicitFunction F = load_model(std::string(INTERLIN_DATA_DIR) + "/models/" + name + ".rf");
  CloudCase c;
  c.name = name + (sigma > 0 ? " noisy" : "") + (orient ? " oriented" : "");
  ImplicitMeshOptions o;
  o.resolution = 512;
  implicit_mesh(F, o, c.truth.V, c.truth.F);
  c.truth.diagonal = (c.truth.V.colwise().maxCoeff() - c.truth.V.colwise().minCoeff()).norm();
  // First-order distance |F| / |grad F| at the truth triangles' centroids: the sag.
  {
    Points3 C(c.truth.F.rows(), 3);
    for (Index f = 0; f < c.truth.F.rows(); ++f)
      C.row(f) = (c.truth.V.row(c.truth.F(f, 0)) + c.truth.V.row(c.truth.F(f, 1)) +
                  c.truth.V.row(c.truth.F(f, 2))) /
                 3;
    Eigen::VectorXd v(C.rows());
    Points3 G(C.rows(), 3);
    F.gradient(C, v, G);
    Eigen::ArrayXd d = v.array().abs() / G.rowwise().norm().array().max(1e-300);
    std::vector<double> sorted(d.data(), d.data() + d.size());
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() * 999 / 1000, sorted.end());
    c.truth.sag = sorted[sorted.size() * 999 / 1000]; // 99.9th percentile (edges of R-functions
                                                      // have a gradient kink)
  }
  // Samples on the truth mesh moved onto F = 0 along the gradient (two Newton steps).
  PointCloud s = sample_mesh(c.truth.V, c.truth.F, n, seed);
  for (int it = 0; it < 2; ++it) {
    Eigen::VectorXd v(n);
    Points3 G(n, 3);
    F.gradient(s.points, v, G);
    for (Index i = 0; i < n; ++i) {
      const double g2 = G.row(i).squaredNorm();
      if (g2 > 0)
        s.points.row(i) -= v(i) / g2 * G.row(i);
    }
  }
  c.noise = sigma * c.truth.diagonal;
  add_noise(s, c.noise, seed + 3);
  c.description = std::to_string(n) + " points on the zero set of data/models/" + name +
                  ".rf, sigma " + std::to_string(sigma) + " x diagonal";
  c.cloud = prepared(c.name, s, c.inward, orient);
  return c;
}

CloudCase bunny() {
  CloudCase c;
  c.name = "bun0.pcd";
  c.description = "PCL's bunny scan, 397 points with PCL normals (re-oriented)";
  const std::string path = std::string(INTERLIN_DATA_DIR) + "/clouds/bun0.pcd";
  c.cloud = prepare_cloud(path, read_point_cloud(path), preparation);
  c.normals_measured = true; // the file's (PCL's, from the full-resolution scan), re-oriented
  return c;
}

void set_case_preparation(const CloudPrepOptions& o) {
  preparation = o;
}

namespace {

template <class T>
void put(std::ofstream& out, const T* p, size_t n) {
  out.write(reinterpret_cast<const char*>(p), static_cast<std::streamsize>(n * sizeof(T)));
}
template <class T>
void get(std::ifstream& in, T* p, size_t n) {
  in.read(reinterpret_cast<char*>(p), static_cast<std::streamsize>(n * sizeof(T)));
}

} // namespace

void save_case(const CloudCase& c, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  const long sizes[4] = {long(c.cloud.points.rows()), long(c.cloud.normals.rows()),
                         long(c.truth.V.rows()), long(c.truth.F.rows())};
  const double reals[5] = {c.truth.diagonal, c.truth.sag, c.noise, c.station_lo, c.station_hi};
  const int kind[2] = {static_cast<int>(c.stations), c.normals_measured ? 1 : 0};
  put(out, sizes, 4);
  put(out, reals, 5);
  put(out, kind, 2);
  for (const std::string& s : {c.name, c.description}) {
    const long n = long(s.size());
    put(out, &n, 1);
    put(out, s.data(), s.size());
  }
  put(out, c.cloud.points.data(), size_t(c.cloud.points.size()));
  put(out, c.cloud.normals.data(), size_t(c.cloud.normals.size()));
  put(out, c.truth.V.data(), size_t(c.truth.V.size()));
  put(out, c.truth.F.data(), size_t(c.truth.F.size()));
  if (!out)
    throw std::runtime_error("cannot write " + path);
}

CloudCase load_case(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  long sizes[4];
  double reals[5];
  int kind[2] = {0, 0};
  get(in, sizes, 4);
  get(in, reals, 5);
  get(in, kind, 2);
  CloudCase c;
  for (std::string* s : {&c.name, &c.description}) {
    long n = 0;
    get(in, &n, 1);
    s->resize(size_t(n));
    get(in, s->data(), size_t(n));
  }
  c.cloud.points.resize(sizes[0], 3);
  c.cloud.normals.resize(sizes[1], 3);
  c.truth.V.resize(sizes[2], 3);
  c.truth.F.resize(sizes[3], 3);
  get(in, c.cloud.points.data(), size_t(c.cloud.points.size()));
  get(in, c.cloud.normals.data(), size_t(c.cloud.normals.size()));
  get(in, c.truth.V.data(), size_t(c.truth.V.size()));
  get(in, c.truth.F.data(), size_t(c.truth.F.size()));
  c.truth.diagonal = reals[0];
  c.truth.sag = reals[1];
  c.noise = reals[2];
  c.station_lo = reals[3];
  c.station_hi = reals[4];
  c.stations = static_cast<CloudCase::Station>(kind[0]);
  c.normals_measured = kind[1] == 1;
  if (!in)
    throw std::runtime_error("cannot read " + path);
  return c;
}

} // namespace interlin::bench
