#pragma once
// The clouds of the point cloud -> surface benchmark (docs/benchmarks.md, "Point clouds"): the
// Rotor 37 blade as a closed solid (the capped loft of data/rotor37/sections.csv is the truth)
// scanned unstructured, with a hole, and in planar or radial slices; clouds sampled from the seed
// R-function models (the zero set is the truth); PCL's bunny scan (no truth).

#include "interlin/reconstruction/clouds/point_cloud.h"
#include "interlin/reconstruction/clouds/prepare_cloud.h"
#include "interlin/reconstruction/clouds/sample_mesh.h" // the cases' sampler, for bench_clouds too

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

namespace interlin::bench {

// A closed triangle mesh of the true surface; `sag` is its own measured distance from the
// exact surface (largest over triangle centroids), the floor of every distance measured to it.
struct TruthMesh {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  double diagonal = 0, sag = 0;
};

struct CloudCase {
  std::string name, description;
  PointCloud cloud; // points and the normals every method is given
  // The normals are measured (a file's, or the truth's), not estimated from the points: only
  // then does interlin's automatic fit (`interlin implicit --fit auto`) consider the Hermite RBF.
  bool normals_measured = false;
  TruthMesh truth;          // empty for the bunny
  double noise = 0;         // sigma of the simulated noise (0 for the bunny: unknown)
  Eigen::Index inward = -1; // normals pointing against the true ones (-1: unknown; not saved)
  // Sectioned scans: the station coordinate of a point (x for planar slices, the radius about z
  // for radial ones) and the range of the stations; distances are measured where it is inside.
  enum class Station { none, x, radius } stations = Station::none;
  double station_lo = 0, station_hi = 0;
  bool sectioned() const { return stations != Station::none; }
  double station(const Eigen::Vector3d& p) const {
    return stations == Station::x ? p(0) : std::hypot(p(0), p(1));
  }
};

// The case in a binary file, for a benchmark worker process (save then load gives it back).
void save_case(const CloudCase& c, const std::string& path);
CloudCase load_case(const std::string& path);

// Rotor 37 blade scanned without structure: n points uniform by area on the capped loft, noise
// sigma (cm). hole > 0 removes the points within that distance of the loft's point S(hole_u,
// hole_v) (by default a suction-side point at mid-span). Normals: prepare_cloud's (estimated),
// prepare_cloud's with each turned to the side of the true normal (oriented: estimated directions,
// oracle orientation), or the true normals at the points' noise-free positions (exact); the oracles
// separate the fit's error from the normals' (docs/benchmarks.md "What limits the unstructured
// fit").
enum class Normals { estimated, oriented, exact };
CloudCase blade_unstructured(int n, double sigma, double hole, unsigned seed,
                             Normals normals = Normals::estimated, double hole_u = 0.25,
                             double hole_v = 0.5);

// Rotor 37 blade scanned in `slices` planar sections x = const (radial: cylinders r = const about
// the z axis) between hub and tip, `per_slice` points each, evenly spaced along the profile,
// noise sigma (cm). The normals are the exact ones.
CloudCase blade_slices(bool radial, int slices, int per_slice, double sigma, unsigned seed);

// n points on the zero set of an R-function model (data/models/NAME.rf) with its normalised
// gradient as normal, noise sigma relative to the bounding-box diagonal; the normals estimated
// (prepare_cloud) and, with `orient` (an oracle for the orientation), each turned to the true
// normal's side.
CloudCase model_cloud(const std::string& name, int n, double sigma, unsigned seed,
                      bool orient = false);

// The options of the cases' prepare_cloud (default: prepare_cloud's; bench_clouds
// --no-thin-walls and --no-sheet-normals change them).
void set_case_preparation(const CloudPrepOptions& o);

// data/clouds/bun0.pcd (its normals re-oriented by prepare_cloud).
CloudCase bunny();

} // namespace interlin::bench
