#include "interlin/reconstruction/clouds/prepare_cloud.h"

#include "interlin/reconstruction/clouds/cloud_checks.h"
#include "interlin/reconstruction/clouds/cloud_filters.h"
#include "interlin/reconstruction/clouds/noise_level.h"
#include "interlin/reconstruction/clouds/orient_normals.h"
#include "interlin/reconstruction/io/input_error.h"

#include <algorithm>
#include <stdexcept>

namespace interlin {

namespace {

// Orientation disagreement (orient_normals.h) below which a file's normals count as oriented:
// consistent normals give about 0, a noisy scan's estimates a few tenths of a percent near
// edges, random signs 0.5.
constexpr double kOrientedDisagreement = 0.01;

} // namespace

namespace {

void check_options(const CloudPrepOptions& o) {
  if (o.outlier_neighbours < 0 || !(o.outlier_ratio > 0) || !(o.voxel >= 0) ||
      (o.normal_neighbours != 0 && o.normal_neighbours < 3) || o.orient_neighbours < 1)
    throw std::invalid_argument("prepare_cloud: bad options");
}

void say(const CloudPrepOptions& o, const std::string& s) {
  if (o.progress)
    o.progress(s);
}

// The k of the normals: options.normal_neighbours, or from the noise when it is 0 (at least
// kNormalNeighbours, which small clouds keep: estimate_noise needs more than 24 points; at most
// kMostNormalNeighbours, wider neighbourhoods round off the edges they straddle).
int normal_neighbours(const Eigen::MatrixX3d& P, int asked) {
  constexpr int kNormalNeighbours = 16, kMostNormalNeighbours = 64;
  if (asked > 0)
    return asked;
  if (P.rows() <= 24)
    return kNormalNeighbours;
  const int most = int(std::min<Eigen::Index>(kMostNormalNeighbours, P.rows() - 1));
  return normal_neighbours_for_noise(P, estimate_noise(P), kNormalNeighbours,
                                     std::max(most, kNormalNeighbours));
}

} // namespace

PointCloud filter_cloud(const std::string& path, const PointCloud& cloud, const CloudPrepOptions& o,
                        CloudPrepReport& r, std::vector<std::string>* notes) {
  check_options(o);
  r.read = cloud.points.rows();
  PointCloud c = check_cloud(path, cloud, notes);
  r.distinct = c.points.rows();
  if (o.outlier_neighbours > 0) {
    say(o, "statistical outlier removal (k = " + std::to_string(o.outlier_neighbours) + ")");
    c = remove_statistical_outliers(c, o.outlier_neighbours, o.outlier_ratio, &r.outliers);
  }
  if (o.voxel > 0) {
    say(o, "voxel-grid downsampling");
    c = voxel_downsample(c, o.voxel);
  }
  c = check_cloud(path, c); // what the filters left must still bound a volume
  r.kept = c.points.rows();
  return c;
}

void cloud_normals(const std::string& path, PointCloud& c, const CloudPrepOptions& o,
                   CloudPrepReport& r, std::vector<std::string>* notes) {
  check_options(o);
  if (o.normals == NormalSource::file && !c.has_normals())
    throw_input_error(path, 0,
                      "the file has no normals (fields nx, ny, nz); estimate them instead");
  if (o.normals == NormalSource::estimate || !c.has_normals()) {
    const int k = normal_neighbours(c.points, o.normal_neighbours);
    say(o, "normal estimation (k = " + std::to_string(k) + ")");
    c.normals = estimate_normals(c.points, k, o.threads);
    r.normals_estimated = true;
    r.normal_neighbours = k;
  } else if (o.normals == NormalSource::automatic) {
    r.disagreement = orientation_disagreement(c.points, c.normals, o.orient_neighbours);
    r.normals_reoriented = r.disagreement > kOrientedDisagreement;
    if (r.normals_reoriented && notes)
      notes->push_back(path + ": the file's normals are not consistently oriented (" +
                       std::to_string(100 * r.disagreement) +
                       " % of neighbour pairs disagree): re-oriented");
  }
  if (r.normals_estimated || r.normals_reoriented) {
    say(o, "normal orientation (k = " + std::to_string(o.orient_neighbours) + ")");
    OrientationInfo info;
    orient_normals(c.points, c.normals, o.orient_neighbours, &info);
    r.components = info.components;
    say(o, "orientation check by the winding number");
    r.patches_flipped =
        orient_by_winding_number(c.points, c.normals, o.orient_neighbours, o.thin_walls);
  }
}

PointCloud prepare_cloud(const std::string& path, const PointCloud& cloud,
                         const CloudPrepOptions& o, CloudPrepReport* report_out,
                         std::vector<std::string>* notes) {
  CloudPrepReport r;
  PointCloud c = filter_cloud(path, cloud, o, r, notes);
  cloud_normals(path, c, o, r, notes);
  if (report_out)
    *report_out = r;
  return c;
}

} // namespace interlin
