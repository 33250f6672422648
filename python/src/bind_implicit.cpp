// Python bindings of reconstruction/implicit and the .ifl models: interlin.implicit() (sections
// -> the section body's equation, or an R-function model -> its normalised equation, as
// `interlin implicit`), the model it returns (function, report, write to .ifl), and the kinds of
// .ifl models.
#include "bindings.h"

#include "interlin/interflatation/models/ifl_registry.h"
#include "interlin/reconstruction/implicit/normalize_model.h"
#include "interlin/reconstruction/implicit/section_body_build.h"
#include "interlin/reconstruction/io/atomic_file.h"

#include <filesystem>
#include <iostream>

namespace interlin::python {

namespace {

// A built implicit model: the .ifl block it is saved as and its function.
struct ImplicitModel {
  std::string kind;
  IflBlock block;
  ImplicitFunction function;
  NodeGrid grid;
  double band_inner = 0, band_outer = 0;
  py::dict report;
};

bool is_rf_path(const py::object& o) {
  const auto path = path_of(o);
  if (!path)
    return false;
  std::string e = std::filesystem::path(*path).extension().string();
  for (char& c : e)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e == ".rf";
}

std::function<void(const std::string&)> progress_lines(bool progress) {
  if (!progress)
    return {};
  return [](const std::string& line) { std::cerr << "[implicit] " << line << std::endl; };
}

ImplicitModel section_body(const py::object& sections, const LoftOptions& loft,
                           SectionBodyOptions o) {
  o.loft = loft;
  const SectionsArg s = sections_arg(sections);
  SectionBodyBuild b;
  {
    py::gil_scoped_release release;
    b = build_section_body(s.sections, o);
  }
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
  report["warnings"] = s.warnings;
  return {"section_body",   to_ifl(b.model),    section_body_function(b.model),
          b.model.grid,     b.model.band_inner, b.model.band_outer,
          std::move(report)};
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
exactly on the body's boundary, > 0 inside, the signed distance near it (docs/design.md).
kind ("section_body" or "normalized_rf"), function (Implicit: values and gradients), M(P) and
M.gradient(P) at points P (N, 3), grid_shape (n0, n1, n2) and cell of the far-field grid, band (inner, outer)
in distance units, box (2, 3), report (dict: what the build measured, as `interlin implicit`
prints it), write(path) saves it as .ifl (read back by load_model).)")
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
                             [](const ImplicitModel& M) {
                               return py::make_tuple(M.grid.n(0), M.grid.n(1), M.grid.n(2));
                             })
      .def_property_readonly("cell", [](const ImplicitModel& M) { return M.grid.h; })
      .def_property_readonly(
          "band", [](const ImplicitModel& M) { return py::make_tuple(M.band_inner, M.band_outer); })
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
         const py::object& param, const std::string& span) {
        if (resolution < 8 || resolution > 1024)
          throw py::value_error("resolution: expected 8 .. 1024 grid cells");
        if (!(band.first > 0 && band.second > band.first))
          throw py::value_error("band: expected (inner, outer) with 0 < inner < outer (cells)");
        if (is_rf_path(input)) {
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
        const LoftArgs a =
            loft_args(degree, span_degree, align, match, param, span, py::none(), 1e-3);
        return section_body(input, a.options.loft, o);
      },
      py::arg("input"), py::arg("resolution") = 96, py::arg("band") = std::pair{1.5, 3.0},
      py::arg("margin") = 0.05, py::arg("mesh_resolution") = 0,
      py::arg("parameters") = std::map<std::string, double>{}, py::arg("output") = "res",
      py::arg("threads") = 0, py::arg("progress") = false, py::arg("degree") = 3,
      py::arg("span_degree") = "auto", py::arg("align") = "first", py::arg("match") = "auto",
      py::arg("param") = "chord", py::arg("span") = "auto",
      R"(The implicit equation of a body, as `interlin implicit` -> ImplicitModel.
input            sections (a section file, a SectionSet, or a list of Section / (P, 3) arrays):
                 the body of the loft through every section, closed by ruled end caps; or an
                 R-function model path (.rf): its zero set, normalised
resolution       far-field grid cells along the longest side of the box (8 .. 1024)
band             (inner, outer) blend band in grid cells: exact near field within inner
margin           sections: box = body bounding box + margin x its diagonal
mesh_resolution  .rf: cells of the mesh of F = 0 (0: 2 x resolution, at least 128)
parameters, output   .rf: `param` values and the variable to normalise
threads          worker threads (0: all cores); progress: progress lines on stderr
degree, span, span_degree, align, match, param   the loft's options (as loft()).)");
  m.def("ifl_kinds", &ifl_kinds, "The model kinds .ifl files may hold (load_model reads them).");
}

} // namespace interlin::python
