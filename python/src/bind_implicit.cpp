// Python bindings of reconstruction/implicit and the .ifl models: interlin.implicit() (sections
// -> the section body's equation; a point cloud -> a sectioned scan's section body or the
// partition-of-unity implicit; an R-function model -> its normalised equation, as
// `interlin implicit`), the model it returns (function, report, write to .ifl), and the kinds of
// .ifl models.
#include "bindings.h"

#include "cli_args.h"
#include "implicit_input.h" // tools/: the CLI's rule for sections or cloud (.csv, .txt)

#include "interlin/interflatation/models/ifl_registry.h"
#include "interlin/reconstruction/clouds/choose_cloud_fit.h"
#include "interlin/reconstruction/clouds/cloud_implicit_ifl.h"
#include "interlin/reconstruction/clouds/fit_sliced_scan.h"
#include "interlin/reconstruction/clouds/read_point_cloud.h"
#include "interlin/reconstruction/implicit/normalize_model.h"
#include "interlin/reconstruction/implicit/section_body_build.h"
#include "interlin/reconstruction/io/atomic_file.h"
#include "interlin/reconstruction/io/input_error.h"

#include <iostream>
#include <memory>

namespace interlin::python {

namespace {

using cli::implicit_input_kind;
using cli::ImplicitInput;

// A built implicit model: the .ifl block it is saved as and its function; the far-field grid
// and the blend band of the kinds that have them (not cloud_pu).
struct ImplicitModel {
  std::string kind;
  IflBlock block;
  ImplicitFunction function;
  std::optional<NodeGrid> grid;
  double band_inner = 0, band_outer = 0;
  py::dict report;
};

// What implicit() was given: `interlin implicit`'s rule for a path (implicit_input_kind).
ImplicitInput input_kind(const py::object& input) {
  if (py::isinstance<PointCloud>(input))
    return ImplicitInput::cloud;
  const auto path = path_of(input);
  if (!path)
    return ImplicitInput::sections; // a SectionSet or a list of sections
  try {
    return implicit_input_kind(*path);
  } catch (const cli::UsageError& e) {
    throw py::value_error(e.what());
  }
}

std::function<void(const std::string&)> progress_lines(bool progress) {
  if (!progress)
    return {};
  return [](const std::string& line) { std::cerr << "[implicit] " << line << std::endl; };
}

// The model of a section body build; report: what the build measured.
ImplicitModel section_body_model(const SectionBodyBuild& b) {
  const SectionBodyReport& r = b.report;
  py::dict report =
      fields_dict(r, field("bbox_diagonal", &SectionBodyReport::bbox_diagonal),
                  field("band_cells", &SectionBodyReport::band_cells),
                  field("seeds", &SectionBodyReport::seeds),
                  field("surface_points", &SectionBodyReport::surface_points),
                  field("boundary_misses", &SectionBodyReport::boundary_misses),
                  field("max_surface_omega", &SectionBodyReport::max_surface_omega),
                  field("check_points", &SectionBodyReport::check_points),
                  field("check_failures", &SectionBodyReport::check_failures),
                  field("validation_points", &SectionBodyReport::validation_points),
                  field("validation_failures", &SectionBodyReport::validation_failures),
                  field("max_far_error", &SectionBodyReport::max_far_error));
  report["loft_max_deviation"] = r.loft.max_deviation;
  report["span"] = r.loft.span;
  return {"section_body",   to_ifl(b.model),    section_body_function(b.model),
          b.model.grid,     b.model.band_inner, b.model.band_outer,
          std::move(report)};
}

ImplicitModel section_body(const py::object& sections, SectionBodyOptions o) {
  const SectionsArg s = sections_arg(sections);
  SectionBodyBuild b;
  {
    py::gil_scoped_release release;
    b = build_section_body(s.sections, o);
  }
  ImplicitModel M = section_body_model(b);
  M.report["warnings"] = s.warnings;
  return M;
}

// The options of the cloud path (as `interlin implicit SCAN`).
struct CloudArgs {
  CloudPrepOptions prep;
  SliceKind slices = SliceKind::automatic;
  bool smooth_span = true;
  std::string method = "auto"; // the unstructured fit: auto, pu or hrbf (as --fit)
  CloudFitOptions fit;
};

// A sectioned scan: fitted sections -> loft -> section body (cmd_implicit_cloud.cpp).
ImplicitModel sliced_body(const PointCloud& c, const SliceFamily& family, const CloudArgs& a,
                          SectionBodyOptions o) {
  SliceFitOptions so;
  so.noise = a.fit.noise;
  so.smooth_span = a.smooth_span;
  so.threads = o.threads;
  so.progress = o.progress;
  SlicedFit fit;
  SectionBodyBuild b;
  {
    py::gil_scoped_release release;
    fit = fit_sliced_scan(c.points, family, so);
    b = build_section_body(fit.loft, o);
  }
  ImplicitModel M = section_body_model(b);
  M.report["slices"] = family.kind == SliceKind::planar ? "planar" : "radial";
  M.report["slice_axis"] = Eigen::Vector3d(family.axis);
  M.report["stations"] = family.stations;
  M.report["slice_spread"] = family.spread;
  M.report["noise"] = fit.noise;
  M.report["section_gap"] = fit.section_gap;
  M.report["span_control"] = fit.span_control;
  return M;
}

// The unstructured fit: normals, then the partition of unity (kind cloud_pu) or the Hermite RBF
// (kind cloud_hrbf) by the rule of `interlin implicit --fit` (cmd_implicit_cloud.cpp).
ImplicitModel cloud_fit(const std::string& path, PointCloud& c, const CloudArgs& a,
                        CloudPrepReport& rep, std::vector<std::string>& notes) {
  CloudFitInfo info;
  std::shared_ptr<const CloudImplicit> model;
  std::shared_ptr<const HermiteRbf> rbf;
  std::optional<CloudFitChoice> choice;
  {
    py::gil_scoped_release release;
    cloud_normals(path, c, a.prep, rep, &notes);
    if (a.method == "auto" && hermite_rbf_offered(c, !rep.normals_estimated))
      choice = choose_cloud_fit(c, a.fit);
    if (a.method == "hrbf" && c.points.rows() > kHermiteRbfMaxPoints)
      throw_input_error(path, 0,
                        "fit=\"hrbf\" takes at most " + std::to_string(kHermiteRbfMaxPoints) +
                            " points, the cloud has " + std::to_string(c.points.rows()));
    if (a.method == "hrbf" || (choice && choice->hermite))
      rbf = std::make_shared<const HermiteRbf>(fit_hermite_rbf(c));
    else
      model = std::make_shared<const CloudImplicit>(fit_cloud_implicit(c, a.fit, &info));
  }
  py::dict report;
  if (choice) {
    report["holdout_pu"] = choice->holdout_pu;
    report["holdout_hrbf"] = choice->holdout_hrbf;
  }
  if (rbf) {
    report["fit"] = "hrbf";
    return {"cloud_hrbf", to_ifl(*rbf), hermite_rbf_function(rbf), std::nullopt, 0, 0, report};
  }
  for (const auto& [key, value] : cloud_fit_dict(info))
    report[key] = value;
  report["fit"] = "pu";
  return {
      "cloud_pu", to_ifl(*model, info.noise), cloud_implicit_function(model), std::nullopt, 0, 0,
      report};
}

// A point cloud (a file or a PointCloud) -> sectioned scan body or cloud_pu, as cloud_job.
ImplicitModel cloud_body(const py::object& input, const CloudArgs& a, const SectionBodyOptions& o) {
  const auto file = path_of(input);
  const std::string path = file ? *file : "<cloud>";
  std::vector<std::string> notes;
  CloudPrepReport rep;
  PointCloud c;
  SliceFamily family;
  {
    const PointCloud raw = file ? PointCloud() : input.cast<PointCloud>();
    py::gil_scoped_release release;
    c = filter_cloud(path, file ? read_point_cloud(path, &notes) : raw, a.prep, rep, &notes);
    if (a.slices != SliceKind::none)
      family = detect_slices(c.points, a.slices);
  }
  if (a.slices != SliceKind::none && a.slices != SliceKind::automatic &&
      family.kind == SliceKind::none)
    throw_input_error(path, 0,
                      std::string("no ") + (a.slices == SliceKind::planar ? "planar" : "radial") +
                          " slices found; use slices=\"auto\" or \"none\"");
  ImplicitModel M = family.kind != SliceKind::none ? sliced_body(c, family, a, o)
                                                   : cloud_fit(path, c, a, rep, notes);
  for (const auto& [key, value] : cloud_report_dict(rep))
    M.report[key] = value;
  M.report["notes"] = notes;
  return M;
}

ImplicitModel normalized_rf(const std::string& path, const ModelOptions& mo,
                            const NormalizeOptions& o) {
  NormalizeBuild b;
  {
    py::gil_scoped_release release;
    b = normalize_model(path, mo, o);
  }
  const NormalizeReport& r = b.report;
  py::dict report =
      fields_dict(r, field("mesh_vertices", &NormalizeReport::mesh_vertices),
                  field("mesh_triangles", &NormalizeReport::mesh_triangles),
                  field("max_zero_omega", &NormalizeReport::max_zero_omega),
                  field("max_zero_first_order", &NormalizeReport::max_zero_first_order));
  return {"normalized_rf",  to_ifl(b.model),    normalized_model_function(b.model),
          b.model.grid,     b.model.band_inner, b.model.band_outer,
          std::move(report)};
}

} // namespace

void bind_implicit_models(py::module_& m) {
  py::class_<ImplicitModel>(m, "ImplicitModel", R"(An implicit model built by implicit(): omega = 0
exactly on the body's boundary, > 0 inside, the signed distance near it (docs/design.md); for
an unstructured cloud (kind "cloud_pu") the partition-of-unity implicit, zero near the points.
kind ("section_body", "normalized_rf" or "cloud_pu"), function (Implicit: values and
gradients), M(P) and M.gradient(P) at points P (N, 3), grid_shape (n0, n1, n2) and cell of the
far-field grid and band (inner, outer) in distance units (None for cloud_pu), box (2, 3), report
(dict: what the build measured, as `interlin implicit` prints it), write(path) saves it as .ifl
(read back by load_model).)")
      .def_readonly("kind", &ImplicitModel::kind)
      .def_readonly("function", &ImplicitModel::function)
      .def(
          "__call__",
          [](const ImplicitModel& M, const DoubleArray& P) { return values_at(M.function, P); },
          py::arg("P"), "omega at the points P (N, 3) -> (N,).")
      .def(
          "gradient",
          [](const ImplicitModel& M, const DoubleArray& P) { return gradients_at(M.function, P); },
          py::arg("P"), "(omega (N,), gradient (N, 3)) at the points P (N, 3).")
      .def_property_readonly("grid_shape",
                             [](const ImplicitModel& M) -> py::object {
                               if (!M.grid)
                                 return py::none();
                               return py::make_tuple(M.grid->n(0), M.grid->n(1), M.grid->n(2));
                             })
      .def_property_readonly("cell",
                             [](const ImplicitModel& M) -> py::object {
                               return M.grid ? py::object(py::float_(M.grid->h)) : py::none();
                             })
      .def_property_readonly("band",
                             [](const ImplicitModel& M) -> py::object {
                               if (!M.grid)
                                 return py::none();
                               return py::make_tuple(M.band_inner, M.band_outer);
                             })
      .def_property_readonly("box",
                             [](const ImplicitModel& M) { return box_to_array(M.function.box); })
      .def_readonly("report", &ImplicitModel::report)
      .def(
          "write",
          [](const ImplicitModel& M, const py::object& path) {
            const auto p = path_of(path);
            if (!p)
              throw py::type_error("write: expected a path (str or os.PathLike)");
            py::gil_scoped_release release;
            write_file_atomically(*p, [&](std::ostream& out) { write_ifl(out, M.block); });
          },
          py::arg("path"), "Writes the model as an .ifl file (whole or not at all).");

  m.def(
      "implicit",
      [](const py::object& input, int resolution, std::pair<double, double> band, double margin,
         int mesh_resolution, const std::map<std::string, double>& parameters,
         const std::string& output, int threads, bool progress, int degree,
         const py::object& span_degree, const std::string& align, const std::string& match,
         const py::object& param, const std::string& span, const std::string& slices, double noise,
         int max_depth, int outliers, double outlier_ratio, double voxel,
         const std::string& normals, int normal_neighbours, const std::string& sheet_normals,
         const std::string& span_smoothing, const std::string& fit,
         const std::string& smooth_points) {
        if (resolution < 8 || resolution > 1024)
          throw py::value_error("resolution: expected 8 .. 1024 grid cells");
        if (!(band.first > 0 && band.second > band.first))
          throw py::value_error("band: expected (inner, outer) with 0 < inner < outer (cells)");
        const ImplicitInput kind = input_kind(input);
        if (kind == ImplicitInput::model) {
          NormalizeOptions o;
          o.resolution = resolution;
          o.mesh_resolution = mesh_resolution;
          std::tie(o.band_inner, o.band_outer) = band;
          o.threads = threads;
          o.progress = progress_lines(progress);
          return normalized_rf(*path_of(input), ModelOptions{output, parameters}, o);
        }
        if (!(margin > 0 && margin <= 1))
          throw py::value_error("margin: expected a number in (0, 1]");
        SectionBodyOptions o;
        o.resolution = resolution;
        std::tie(o.band_inner, o.band_outer) = band;
        o.margin = margin;
        o.threads = threads;
        o.progress = progress_lines(progress);
        if (kind == ImplicitInput::sections) {
          o.loft = loft_args(degree, span_degree, align, match, param, span, py::none(), 1e-3)
                       .options.loft;
          return section_body(input, o);
        }
        CloudArgs a;
        a.slices = choice<SliceKind>({{"auto", SliceKind::automatic},
                                      {"planar", SliceKind::planar},
                                      {"radial", SliceKind::radial},
                                      {"none", SliceKind::none}},
                                     slices, "slices");
        if (!(noise >= 0) || !(outlier_ratio > 0) || !(voxel >= 0) || max_depth < 1 ||
            max_depth > 20 || outliers < 0 || (normal_neighbours != 0 && normal_neighbours < 3))
          throw py::value_error(
              "noise >= 0, 1 <= max_depth <= 20, outliers >= 0, "
              "outlier_ratio > 0, voxel >= 0, normal_neighbours 0 or >= 3 expected");
        a.prep.outlier_neighbours = outliers, a.prep.outlier_ratio = outlier_ratio;
        a.prep.voxel = voxel;
        a.prep.normals = choice<NormalSource>({{"auto", NormalSource::automatic},
                                               {"file", NormalSource::file},
                                               {"estimate", NormalSource::estimate}},
                                              normals, "normals");
        a.prep.normal_neighbours = normal_neighbours;
        a.prep.sheet_normals = sheet_normals_choice(sheet_normals);
        a.prep.threads = a.fit.threads = threads;
        a.prep.progress = a.fit.progress = o.progress;
        a.fit.noise = noise;
        a.fit.max_depth = max_depth;
        a.smooth_span =
            choice<bool>({{"auto", true}, {"off", false}}, span_smoothing, "span_smoothing");
        a.method =
            choice<std::string>({{"auto", "auto"}, {"pu", "pu"}, {"hrbf", "hrbf"}}, fit, "fit");
        a.fit.smooth_points =
            choice<bool>({{"auto", true}, {"off", false}}, smooth_points, "smooth_points");
        return cloud_body(input, a, o);
      },
      py::arg("input"), py::arg("resolution") = 96, py::arg("band") = std::pair{1.5, 3.0},
      py::arg("margin") = 0.05, py::arg("mesh_resolution") = 0,
      py::arg("parameters") = std::map<std::string, double>{}, py::arg("output") = "res",
      py::arg("threads") = 0, py::arg("progress") = false, py::arg("degree") = 3,
      py::arg("span_degree") = "auto", py::arg("align") = "first", py::arg("match") = "auto",
      py::arg("param") = "chord", py::arg("span") = "auto", py::arg("slices") = "auto",
      py::arg("noise") = 0.0, py::arg("max_depth") = 12, py::arg("outliers") = 16,
      py::arg("outlier_ratio") = 3.0, py::arg("voxel") = 0.0, py::arg("normals") = "auto",
      py::arg("normal_neighbours") = 0, py::arg("sheet_normals") = "auto",
      py::arg("span_smoothing") = "auto", py::arg("fit") = "auto",
      py::arg("smooth_points") = "auto",
      R"(The implicit equation of a body, as `interlin implicit` -> ImplicitModel.
input            sections (a section file, a SectionSet, or a list of Section / (P, 3) arrays):
                 the body of the loft through every section, closed by ruled end caps; a point
                 cloud (a PointCloud, or a .pcd .ply .xyz .xyzn file; .csv and .txt by their
                 content, docs/formats.md "Sections or a cloud?"): a sectioned scan's fitted
                 sections lofted into a section body, any other cloud the partition-of-unity
                 implicit (kind cloud_pu) or, sparse, the Hermite RBF (cloud_hrbf, see fit); or
                 an R-function model path (.rf): its zero set, normalised
resolution       far-field grid cells along the longest side of the box (8 .. 1024)
band             (inner, outer) blend band in grid cells: exact near field within inner
margin           sections: box = body bounding box + margin x its diagonal
mesh_resolution  .rf: cells of the mesh of F = 0 (0: 2 x resolution, at least 128)
parameters, output   .rf: `param` values and the variable to normalise
threads          worker threads (0: all cores); progress: progress lines on stderr
degree, span, span_degree, align, match, param   the loft's options (as loft())
slices           clouds: "auto" (detect planar, then radial slices), "planar", "radial", "none"
                 (always the unstructured fit)
noise            clouds: the scan noise sigma (0: estimated)
max_depth        unstructured clouds: the octree's deepest level
smooth_points    unstructured clouds: "auto" (noisy scans' points first moved onto local
                 quadrics, as many neighbours as the shape allows) or "off"
fit              unstructured clouds: "auto" (at most 500 points with the file's normals: the
                 better of "pu" and "hrbf" by five-fold hold-out, report holdout_pu and
                 holdout_hrbf; else "pu"), "pu" (partition of unity, kind cloud_pu), "hrbf"
                 (Hermite RBF interpolant of points and normals, kind cloud_hrbf, at most 1000
                 points); report["fit"] says which
span_smoothing   sectioned scans: "auto" (the sections become isocurves of one least-squares
                 surface through all slices when Mallows' C_p prefers it; report span_control:
                 its control points along the span, 0 when not) or "off"
outliers, outlier_ratio, voxel, normals, normal_neighbours, sheet_normals   the preparation
                 steps (as prepare_cloud; outliers 0: off, voxel 0: off, normal_neighbours 0:
                 from the noise; sheet_normals "auto": on clean scans, "on", "off").)");
  m.def("ifl_kinds", &ifl_kinds, "The model kinds .ifl files may hold (load_model reads them).");
}

} // namespace interlin::python
