#include "interlin/reconstruction/clouds/prepare_cloud.h"

#include "interlin/reconstruction/clouds/cloud_checks.h"
#include "interlin/reconstruction/clouds/cloud_filters.h"
#include "interlin/reconstruction/clouds/noise_level.h"
#include "interlin/reconstruction/clouds/orient_normals.h"
#include "interlin/reconstruction/io/input_error.h"

#include <algorithm>
#include <cmath>
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
int normal_neighbours(const Eigen::MatrixX3d& P, int asked, double sigma) {
  constexpr int kNormalNeighbours = 16, kMostNormalNeighbours = 64;
  if (asked > 0)
    return asked;
  if (P.rows() <= 24)
    return kNormalNeighbours;
  const int most = int(std::min<Eigen::Index>(kMostNormalNeighbours, P.rows() - 1));
  return normal_neighbours_for_noise(P, sigma, kNormalNeighbours,
                                     std::max(most, kNormalNeighbours));
}

// Whether the normals of k neighbours are sheet normals (estimate_noise and is_clean_scan need
// more than 24 points).
bool use_sheet_normals(const Eigen::MatrixX3d& P, SheetNormals asked, int k) {
  if (asked == SheetNormals::off || P.rows() <= std::max(24, k) || k < 6)
    return false;
  return asked == SheetNormals::on || is_clean_scan(P);
}

// The number of rows of A and B more than 20 degrees apart (either sign).
Eigen::Index count_apart(const Eigen::MatrixX3d& A, const Eigen::MatrixX3d& B) {
  const double kApart = std::cos(20 * M_PI / 180);
  return ((A.array() * B.array()).rowwise().sum().abs() < kApart).count();
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
  Eigen::MatrixX3d sheet; // sheet normals, signed after PCA's are oriented
  double sigma = 0;
  if (o.normals == NormalSource::estimate || !c.has_normals()) {
    sigma = c.points.rows() > 24 ? estimate_noise(c.points) : 0;
    const int k = normal_neighbours(c.points, o.normal_neighbours, sigma);
    r.sheet_normals = use_sheet_normals(c.points, o.sheet_normals, k);
    say(o, std::string(r.sheet_normals ? "sheet " : "") +
               "normal estimation (k = " + std::to_string(k) + ")");
    c.normals = estimate_normals(c.points, k, o.threads);
    if (r.sheet_normals)
      sheet = estimate_sheet_normals(c.points, k, sigma, o.threads);
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
  if (r.sheet_normals) {
    say(o, "sheet normal signs");
    r.sheet_changed = count_apart(sheet, c.normals);
    c.normals = sign_sheet_normals(c.points, sheet, c.normals, sigma, o.threads);
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
