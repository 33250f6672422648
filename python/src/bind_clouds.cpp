// Python bindings of reconstruction/clouds: point-cloud files, PCL filters and normals, normal
// orientation, noise estimates and the partition-of-unity implicit of unstructured scans.
#include "bindings.h"

#include "interlin/reconstruction/clouds/cloud_checks.h"
#include "interlin/reconstruction/clouds/cloud_filters.h"
#include "interlin/reconstruction/clouds/cloud_implicit.h"
#include "interlin/reconstruction/clouds/noise_level.h"
#include "interlin/reconstruction/clouds/orient_normals.h"
#include "interlin/reconstruction/clouds/prepare_cloud.h"
#include "interlin/reconstruction/clouds/read_point_cloud.h"
#include "interlin/reconstruction/clouds/smooth_scan_points.h"

#include <memory>

namespace interlin::python {

namespace {

using Eigen::Index;
using Eigen::MatrixX3d;

// A fitted cloud implicit and its evaluator (built once).
struct CloudModel {
  std::shared_ptr<const CloudImplicit> model;
  ImplicitFunction function;
  CloudFitInfo info;
};

void bind_cloud_io(py::module_& m) {
  py::class_<PointCloud>(m, "PointCloud", R"(A point cloud: points (N, 3) and unit normals (N, 3),
or (0, 3) without normals. PointCloud(points, normals=None).)")
      .def(py::init([](MatrixX3d points, std::optional<MatrixX3d> normals) {
             PointCloud c{std::move(points)};
             if (normals) {
               if (normals->rows() != c.points.rows())
                 throw py::value_error("normals: expected one row per point");
               c.normals = std::move(*normals);
             }
             return c;
           }),
           py::arg("points"), py::arg("normals") = py::none())
      .def_readonly("points", &PointCloud::points, "(N, 3)")
      .def_readonly("normals", &PointCloud::normals, "(N, 3), or (0, 3) without normals")
      .def_property_readonly("has_normals", &PointCloud::has_normals)
      .def("__len__", [](const PointCloud& c) { return c.points.rows(); });
  m.def(
      "read_point_cloud",
      [](const std::string& path, bool with_notes) -> py::object {
        std::vector<std::string> notes;
        PointCloud c;
        {
          py::gil_scoped_release release;
          c = read_point_cloud(path, &notes);
        }
        return with_notes ? py::object(py::make_tuple(std::move(c), notes))
                          : py::object(py::cast(std::move(c)));
      },
      py::arg("path"), py::arg("with_notes") = false,
      R"(Reads a point cloud (.pcd, .ply, .xyz/.xyzn/.txt, .csv; docs/formats.md "Point clouds")
-> PointCloud, or (PointCloud, notes) with with_notes. InputError "FILE:LINE: ..." on bad input.)");
  m.def(
      "check_cloud",
      [](const PointCloud& c, const std::string& path) { return check_cloud(path, c); },
      py::arg("cloud"), py::arg("path") = "<cloud>", release_gil(),
      "Removes repeated points; InputError \"PATH: ...\" for fewer than 20 distinct points or "
      "points on one point, line or plane.");
}

void bind_cloud_steps(py::module_& m) {
  m.def(
      "remove_statistical_outliers",
      [](const PointCloud& c, int k, double ratio) {
        Index removed = 0;
        PointCloud kept;
        {
          py::gil_scoped_release release;
          kept = remove_statistical_outliers(c, k, ratio, &removed);
        }
        return py::make_tuple(std::move(kept), removed);
      },
      py::arg("cloud"), py::arg("k") = 16, py::arg("std_ratio") = 3.0,
      "PCL's statistical outlier removal -> (kept PointCloud, number removed).");
  m.def("voxel_downsample", &voxel_downsample, py::arg("cloud"), py::arg("leaf"), release_gil(),
        "PCL's voxel grid: the points of each cubic voxel of side `leaf` replaced by their "
        "centroid.");
  m.def("estimate_normals", &estimate_normals, py::arg("P"), py::arg("k") = 16,
        py::arg("threads") = 0, release_gil(),
        "PCL's normals of the points P (N, 3) from their k nearest neighbours -> (N, 3), "
        "unoriented.");
  m.def("estimate_sheet_normals", &estimate_sheet_normals, py::arg("P"), py::arg("k") = 16,
        py::arg("sigma") = 0.0, py::arg("threads") = 0, release_gil(),
        "Normals of the points P (N, 3) from those of their k nearest neighbours on one sheet "
        "(the plane proposed by a neighbour's 6-point normal with the most of them within a "
        "quarter spacing + 3 sigma) -> (N, 3), unoriented.");
  m.def("sign_sheet_normals", &sign_sheet_normals, py::arg("P"), py::arg("S"), py::arg("O"),
        py::arg("sigma") = 0.0, py::arg("threads") = 0, release_gil(),
        "Signs of sheet normals S (N, 3) from oriented PCA normals O (N, 3): a local vote of the "
        "points where they agree, along each sheet -> (N, 3).");
  m.def(
      "orient_normals",
      [](const MatrixX3d& P, MatrixX3d N, int k) {
        OrientationInfo info;
        {
          py::gil_scoped_release release;
          orient_normals(P, N, k, &info);
        }
        return py::make_tuple(std::move(N), info.components, info.flipped);
      },
      py::arg("P"), py::arg("N"), py::arg("k") = 10,
      "Consistent outward signs of the normals N (N, 3) at P (Hoppe et al. 1992, MST) -> "
      "(N oriented, components, flipped).");
  m.def("orientation_disagreement", &orientation_disagreement, py::arg("P"), py::arg("N"),
        py::arg("k") = 10, release_gil(),
        "Fraction of neighbouring pairs on one sheet whose normals point to opposite sides.");
  m.def("estimate_noise", &estimate_noise, py::arg("P"), py::arg("k") = 24,
        py::arg("samples") = 2000, release_gil(),
        "Standard deviation of the scan noise normal to the surface (median of local quadric "
        "residuals).");
  m.def("median_point_spacing", &median_point_spacing, py::arg("P"), py::arg("k") = 16,
        py::arg("samples") = 2000, release_gil(),
        "Median over up to `samples` points of d sqrt(pi / k), d the k-th neighbour's distance.");
  m.def("is_clean_scan", &is_clean_scan, py::arg("P"), release_gil(),
        "Whether the scan noise is below 0.002 point spacings (sampled from a model or a mesh).");
  m.def("normal_neighbours_for_noise", &normal_neighbours_for_noise, py::arg("P"), py::arg("sigma"),
        py::arg("k_min") = 16, py::arg("k_max") = 64, py::arg("samples") = 2000, release_gil(),
        "Neighbours for PCA normals at noise sigma: 2 sqrt(pi) sigma / (spacing 0.1 rad), "
        "clamped to [k_min, k_max].");
  m.def(
      "smooth_scan_points",
      [](const MatrixX3d& P, const MatrixX3d& N, double sigma, int k_max, double kappa, bool edges,
         int threads) {
        SmoothedPoints s;
        {
          py::gil_scoped_release release;
          s = smooth_scan_points(P, N, sigma, k_max, kappa, edges, threads);
        }
        return py::make_tuple(std::move(s.P), std::move(s.N), std::move(s.k));
      },
      py::arg("P"), py::arg("N"), py::arg("sigma"), py::arg("k_max") = 512, py::arg("kappa") = 1.5,
      py::arg("edges") = true, py::arg("threads") = 0,
      "Noisy points P (N, 3) with oriented normals N moved onto local quadrics of 16, 32, ..., "
      "k_max neighbours, the number chosen per point by Lepski's method at noise sigma, or onto "
      "the join of two quadrics at a sharp edge (edges) -> (P, N, k).");
  m.def(
      "prepare_cloud",
      [](const PointCloud& cloud, const std::string& path, int outlier_neighbours,
         double outlier_ratio, double voxel, const std::string& normals, int normal_neighbours,
         const std::string& sheet_normals, int orient_neighbours, int threads) {
        CloudPrepOptions o;
        o.outlier_neighbours = outlier_neighbours, o.outlier_ratio = outlier_ratio;
        o.voxel = voxel;
        o.normals = choice<NormalSource>({{"auto", NormalSource::automatic},
                                          {"file", NormalSource::file},
                                          {"estimate", NormalSource::estimate}},
                                         normals, "normals");
        o.normal_neighbours = normal_neighbours, o.orient_neighbours = orient_neighbours;
        o.sheet_normals = sheet_normals_choice(sheet_normals);
        o.threads = threads;
        CloudPrepReport report;
        std::vector<std::string> notes;
        PointCloud c;
        {
          py::gil_scoped_release release;
          c = prepare_cloud(path, cloud, o, &report, &notes);
        }
        return py::make_tuple(std::move(c), cloud_report_dict(report), notes);
      },
      py::arg("cloud"), py::arg("path") = "<cloud>", py::arg("outlier_neighbours") = 16,
      py::arg("outlier_ratio") = 3.0, py::arg("voxel") = 0.0, py::arg("normals") = "auto",
      py::arg("normal_neighbours") = 0, py::arg("sheet_normals") = "auto",
      py::arg("orient_neighbours") = 10, py::arg("threads") = 0,
      R"(The preparation steps in order: repeated points and degenerate clouds, statistical
outlier removal (outlier_neighbours 0: off), voxel downsampling (voxel 0: off), normals ("auto":
the file's when consistent, re-oriented or estimated; "file"; "estimate"; normal_neighbours 0:
k from the noise, normal_neighbours_for_noise; sheet_normals "auto": estimated normals keep to
one sheet on clean scans, "on", "off") and their orientation -> (PointCloud, report dict,
notes).)");
}

void bind_cloud_fit(py::module_& m) {
  py::class_<CloudModel>(m, "CloudModel", R"(A partition-of-unity implicit fitted to a cloud
(Ohtake et al. 2003): function (Implicit: F > 0 inside), info (dict: noise, leaves, depth,
rms_distance, max_distance, within_3_sigma, ...), leaves (number of local fits).)")
      .def_readonly("function", &CloudModel::function)
      .def_property_readonly("info", [](const CloudModel& c) { return cloud_fit_dict(c.info); })
      .def_property_readonly("leaves", [](const CloudModel& c) { return c.model->fits.size(); })
      .def_property_readonly("box", [](const CloudModel& c) { return box_to_array(c.model->box); });
  m.def(
      "fit_cloud_implicit",
      [](const PointCloud& cloud, double noise, int min_points, int max_depth, double support,
         double fit_ball, bool smooth_points, int threads) {
        CloudFitOptions o;
        o.noise = noise, o.min_points = min_points, o.max_depth = max_depth;
        o.support = support, o.fit_ball = fit_ball, o.threads = threads;
        o.smooth_points = smooth_points;
        py::gil_scoped_release release;
        CloudModel c;
        c.model = std::make_shared<const CloudImplicit>(fit_cloud_implicit(cloud, o, &c.info));
        c.function = cloud_implicit_function(c.model);
        return c;
      },
      py::arg("cloud"), py::arg("noise") = 0.0, py::arg("min_points") = 0,
      py::arg("max_depth") = 12, py::arg("support") = 0.6, py::arg("fit_ball") = 0.75,
      py::arg("smooth_points") = true, py::arg("threads") = 0,
      R"(Fits the multi-level partition-of-unity implicit to a cloud with oriented normals
(prepare_cloud) -> CloudModel. noise 0: estimated from the points;
min_points 0: automatic (10 per fit on a clean cloud, 20 on a noisy one, more by the noise);
smooth_points: noisy scans' points first moved onto local quadrics (smooth_scan_points).)");
}

} // namespace

py::dict cloud_fit_dict(const CloudFitInfo& i) {
  return fields_dict(
      i, field("noise", &CloudFitInfo::noise),
      field("noise_estimated", &CloudFitInfo::noise_estimated),
      field("cells", &CloudFitInfo::cells), field("leaves", &CloudFitInfo::leaves),
      field("two_sheet_leaves", &CloudFitInfo::two_sheet_leaves),
      field("far_leaves", &CloudFitInfo::far_leaves),
      field("sign_fixed_leaves", &CloudFitInfo::sign_fixed_leaves),
      field("exterior_negated_leaves", &CloudFitInfo::exterior_negated_leaves),
      field("exterior_split_cells", &CloudFitInfo::exterior_split_cells),
      field("slab_split_cells", &CloudFitInfo::slab_split_cells),
      field("pocket_split_cells", &CloudFitInfo::pocket_split_cells),
      field("depth", &CloudFitInfo::depth), field("rms_distance", &CloudFitInfo::rms_distance),
      field("max_distance", &CloudFitInfo::max_distance),
      field("within_3_sigma", &CloudFitInfo::within_3_sigma),
      field("flipped", &CloudFitInfo::flipped), field("spacing", &CloudFitInfo::spacing),
      field("scan_noise", &CloudFitInfo::scan_noise),
      field("min_points", &CloudFitInfo::min_points),
      field("acceptance", &CloudFitInfo::acceptance),
      field("smoothed_points", &CloudFitInfo::smoothed_points),
      field("smoothed_on_edges", &CloudFitInfo::smoothed_on_edges),
      field("smoothing_noise", &CloudFitInfo::smoothing_noise),
      field("smoothing_neighbours", &CloudFitInfo::smoothing_neighbours));
}

SheetNormals sheet_normals_choice(const std::string& s) {
  return choice<SheetNormals>(
      {{"auto", SheetNormals::automatic}, {"on", SheetNormals::on}, {"off", SheetNormals::off}}, s,
      "sheet_normals");
}

py::dict cloud_report_dict(const CloudPrepReport& r) {
  return fields_dict(
      r, field("read", &CloudPrepReport::read), field("distinct", &CloudPrepReport::distinct),
      field("outliers", &CloudPrepReport::outliers), field("kept", &CloudPrepReport::kept),
      field("normals_estimated", &CloudPrepReport::normals_estimated),
      field("normals_reoriented", &CloudPrepReport::normals_reoriented),
      field("normal_neighbours", &CloudPrepReport::normal_neighbours),
      field("disagreement", &CloudPrepReport::disagreement),
      field("components", &CloudPrepReport::components),
      field("patches_flipped", &CloudPrepReport::patches_flipped),
      field("sheet_normals", &CloudPrepReport::sheet_normals),
      field("sheet_changed", &CloudPrepReport::sheet_changed));
}

void bind_clouds(py::module_& m) {
  bind_cloud_io(m);
  bind_cloud_steps(m);
  bind_cloud_fit(m);
}

} // namespace interlin::python
