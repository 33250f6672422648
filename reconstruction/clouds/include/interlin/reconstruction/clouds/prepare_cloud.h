#pragma once
// The preparation steps of the cloud job, in order: repeated points and degenerate clouds
// (check_cloud), statistical outlier removal, voxel downsampling, normals (kept, estimated) and
// their orientation. Each step is an option with a default that suits scans.

#include "interlin/reconstruction/clouds/point_cloud.h"

#include <functional>
#include <string>
#include <vector>

namespace interlin {

enum class NormalSource {
  automatic, // the file's normals when consistently oriented, re-oriented when not, else estimated
  file,      // the file's normals as they are (they must be oriented outward)
  estimate   // always estimated (PCL) and oriented (orient_normals)
};

// Which estimated normals keep their neighbourhoods to one sheet (estimate_sheet_normals,
// sign_sheet_normals) instead of PCL's PCA of all k neighbours.
enum class SheetNormals {
  automatic, // on clean scans (is_clean_scan: sampled from a model or a mesh), where edges and
             // narrow gaps are sharp; noisy scans keep PCA's normals (docs/benchmarks.md)
  on,
  off
};

struct CloudPrepOptions {
  int outlier_neighbours = 16; // statistical outlier removal: k (0 switches it off) ...
  double outlier_ratio = 3.0;  // ... and the standard-deviation multiple
  double voxel = 0;            // voxel-grid downsampling leaf size (0: off)
  NormalSource normals = NormalSource::automatic;
  int normal_neighbours = 0; // PCL normal estimation: k nearest neighbours (0: from the noise,
                             // normal_neighbours_for_noise, at least 16)
  SheetNormals sheet_normals = SheetNormals::automatic;
  int orient_neighbours = 10; // orientation graph: k nearest neighbours
  bool thin_walls = true;     // orient_by_winding_number: thin walls and edges (false: as before)
  int threads = 0;
  std::function<void(const std::string&)> progress; // one line per step
};

struct CloudPrepReport {
  Eigen::Index read = 0, distinct = 0, outliers = 0, kept = 0;
  bool normals_estimated = false, normals_reoriented = false;
  int normal_neighbours = 0;        // the k of the estimated normals (0: not estimated)
  double disagreement = 0;          // orientation_disagreement of the file's normals (automatic)
  Eigen::Index components = 0;      // parts of the orientation graph
  Eigen::Index patches_flipped = 0; // normals negated by orient_by_winding_number
  bool sheet_normals = false;       // the estimated normals are sheet normals
  Eigen::Index sheet_changed = 0;   // ... more than 20 degrees from PCA's at this many points
};

// Inputs: path (named in messages), the cloud as read, options.
// Output: the cloud with unit normals, oriented outward (or as the file gave them); the report
// (optional) and notes (optional, lines for the summary).
// Throws InputError "PATH: ..." for degenerate clouds (check_cloud) and for
// NormalSource::file without normals in the file; std::invalid_argument for bad options.
// Same as filter_cloud followed by cloud_normals.
PointCloud prepare_cloud(const std::string& path, const PointCloud& cloud,
                         const CloudPrepOptions& options = {}, CloudPrepReport* report = nullptr,
                         std::vector<std::string>* notes = nullptr);

// The steps before the normals: repeated points, outliers, voxels, and the checks of what is
// left (report fields read .. kept). For jobs that need the points only (sectioned scans).
PointCloud filter_cloud(const std::string& path, const PointCloud& cloud,
                        const CloudPrepOptions& options, CloudPrepReport& report,
                        std::vector<std::string>* notes = nullptr);

// The normal steps of a filtered cloud `c` (kept, estimated and/or oriented by options.normals;
// report fields normals_* .. components).
void cloud_normals(const std::string& path, PointCloud& c, const CloudPrepOptions& options,
                   CloudPrepReport& report, std::vector<std::string>* notes = nullptr);

} // namespace interlin
