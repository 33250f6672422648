// Python bindings of reconstruction/loft (and the surface files of reconstruction/io): B-spline
// surfaces (evaluation, derivatives, closest points, meshes, files), the loft (plain and guided)
// and the hold-out study.
#include "bindings.h"

#include "interlin/reconstruction/io/iges.h"
#include "interlin/reconstruction/io/input_error.h"
#include "interlin/reconstruction/io/mesh_io.h"
#include "interlin/reconstruction/io/preview.h"
#include "interlin/reconstruction/io/step.h"
#include "interlin/reconstruction/io/surface_json.h"
#include "interlin/reconstruction/loft/closest_point.h"
#include "interlin/reconstruction/loft/end_caps.h"
#include "interlin/reconstruction/loft/guided_loft.h"
#include "interlin/reconstruction/loft/holdout.h"
#include "interlin/reconstruction/loft/loft.h"
#include "interlin/reconstruction/meshing/surface_mesh.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace interlin::python {

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::MatrixXi;
using Eigen::VectorXd;

// A surface with its explicit per-patch form, built once for all evaluations.
struct Surface {
  BSplineSurface b;
  PiecewiseSurface p;
  explicit Surface(BSplineSurface s) : b(std::move(s)) {
    check_surface(b);
    p = to_piecewise(b);
  }
};

std::string lower_extension(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e;
}

bool is_mesh_extension(const std::string& e) {
  return e == ".stl" || e == ".obj" || e == ".ply" || e == ".off";
}

} // namespace

std::optional<std::string> path_of(const py::handle& o) {
  if (py::isinstance<py::str>(o))
    return o.cast<std::string>();
  if (py::hasattr(o, "__fspath__"))
    return o.attr("__fspath__")().cast<std::string>();
  return std::nullopt;
}

namespace {

std::string require_path(const py::handle& o) {
  if (const auto p = path_of(o))
    return *p;
  throw py::type_error("expected a path (str or os.PathLike)");
}

// S^(du,dv) (or the unit normal) at the pairs (u_k, v_k). Output: shape + (3,).
py::array_t<double> surface_at(const Surface& S, const DoubleArray& u, const DoubleArray& v, int du,
                               int dv, bool normal) {
  std::vector<py::ssize_t> shape = pair_shape(u, v, "u and v");
  const py::ssize_t n = std::max(u.size(), v.size());
  shape.push_back(3);
  py::array_t<double> out(shape);
  double* o = out.mutable_data();
  const double *pu = u.data(), *pv = v.data();
  const bool su = u.size() == 1, sv = v.size() == 1;
  {
    py::gil_scoped_release release;
    for (py::ssize_t k = 0; k < n; ++k) {
      const double a = pu[su ? 0 : k], b = pv[sv ? 0 : k];
      Eigen::Vector3d r = evaluate(S.p, a, b, du, dv);
      if (normal)
        r = evaluate(S.p, a, b, 1, 0).cross(evaluate(S.p, a, b, 0, 1)).normalized();
      std::copy(r.data(), r.data() + 3, o + 3 * k);
    }
  }
  return out;
}

struct MeshArgs {
  int nu = 400, nv = 120;
  std::vector<double> required_v;
  bool cap = false;
  MeshPrecision precision = MeshPrecision::float64;
};

// V (N, 3), F (M, 3) of surface_mesh; called without the GIL.
std::pair<MatrixXd, MatrixXi> mesh_of(const Surface& S, const MeshArgs& a) {
  SurfaceMeshOptions o;
  o.nu = a.nu, o.nv = a.nv, o.required_v = a.required_v, o.cap = a.cap;
  std::pair<MatrixXd, MatrixXi> VF;
  surface_mesh(S.p, o, VF.first, VF.second);
  return VF;
}

LengthUnit unit_of(const std::string& u) {
  return choice<LengthUnit>({{"mm", LengthUnit::mm},
                             {"cm", LengthUnit::cm},
                             {"m", LengthUnit::m},
                             {"in", LengthUnit::inch}},
                            u, "units");
}

// Writes by extension: .igs/.iges, .stp/.step, .json, a mesh (.stl .obj .ply .off) or a .png
// preview.
void write_surface(const Surface& S, const std::string& path, const std::string& units,
                   const std::map<std::string, std::string>& meta, const MeshArgs& mesh,
                   const std::vector<MatrixXd>& polylines) {
  const std::string e = lower_extension(path);
  if (e == ".igs" || e == ".iges") {
    IgesOptions o;
    o.unit = unit_of(units);
    py::gil_scoped_release release;
    write_iges(path, S.b, o);
  } else if (e == ".stp" || e == ".step") {
    StepOptions o;
    o.unit = unit_of(units);
    py::gil_scoped_release release;
    if (mesh.cap) {
      const std::array<StepCap, 2> caps{end_cap(S.b, false), end_cap(S.b, true)};
      write_step(path, S.b, &caps, o);
    } else {
      write_step(path, S.b, nullptr, o);
    }
  } else if (e == ".json") {
    std::map<std::string, std::string> m = meta;
    m.emplace("units", units);
    py::gil_scoped_release release;
    write_surface_json(path, S.b, m);
  } else if (is_mesh_extension(e) || e == ".png") {
    py::gil_scoped_release release;
    const auto [V, F] = mesh_of(S, mesh);
    if (e == ".png")
      write_preview_png(path, V, F, polylines);
    else
      write_mesh(path, V, F, mesh.precision);
  } else {
    throw py::value_error(
        "'" + path +
        "': unknown extension (use .igs .iges .stp .step .json .stl .obj .ply .off .png)");
  }
}

Surface read_surface(const std::string& path) {
  const std::string e = lower_extension(path);
  if (e == ".json")
    return Surface(read_surface_json(path));
  if (e == ".igs" || e == ".iges")
    return Surface(read_iges_surface(path));
  throw py::value_error("'" + path + "': unknown extension (use .json .igs .iges)");
}

void bind_surface(py::module_& m) {
  py::class_<SurfaceProjection>(m, "SurfaceProjection", R"(Closest points on a surface:
u, v (N,) parameters, foot (N, 3) the closest points, distance (N,).)")
      .def_readonly("u", &SurfaceProjection::u)
      .def_readonly("v", &SurfaceProjection::v)
      .def_readonly("foot", &SurfaceProjection::foot)
      .def_readonly("distance", &SurfaceProjection::distance);

  py::class_<Surface, std::shared_ptr<Surface>>(
      m, "Surface", R"(Tensor-product B-spline surface S(u, v), clamped in u and v
(a loft: u around the sections, v along the span; closed_u: closed around, C^{degree_u - 1}).

Surface(degree_u, degree_v, knots_u, knots_v, ctrl, num_u, num_v, closed_u=False) with ctrl
(num_u * num_v, 3), row i + num_u * j. Evaluation uses the explicit per-patch form.)")
      .def(py::init([](int pu, int pv, VectorXd ku, VectorXd kv, MatrixXd ctrl, Index nu, Index nv,
                       bool closed_u) {
             return Surface(BSplineSurface{pu, pv, std::move(ku), std::move(kv), nu, nv,
                                           std::move(ctrl), closed_u});
           }),
           py::arg("degree_u"), py::arg("degree_v"), py::arg("knots_u"), py::arg("knots_v"),
           py::arg("ctrl"), py::arg("num_u"), py::arg("num_v"), py::arg("closed_u") = false)
      .def_property_readonly("degree_u", [](const Surface& S) { return S.b.degree_u; })
      .def_property_readonly("degree_v", [](const Surface& S) { return S.b.degree_v; })
      // Views into the surface (read-only arrays, no copy): properties keep the Surface alive.
      .def_property_readonly("knots_u",
                             [](const Surface& S) -> const VectorXd& { return S.b.knots_u; })
      .def_property_readonly("knots_v",
                             [](const Surface& S) -> const VectorXd& { return S.b.knots_v; })
      .def_property_readonly("num_u", [](const Surface& S) { return S.b.num_u; })
      .def_property_readonly("num_v", [](const Surface& S) { return S.b.num_v; })
      .def_property_readonly(
          "ctrl", [](const Surface& S) -> const MatrixXd& { return S.b.ctrl; },
          "(num_u * num_v, 3), row i + num_u * j")
      .def_property_readonly("closed_u", [](const Surface& S) { return S.b.closed_u; })
      .def_property_readonly(
          "domain",
          [](const Surface& S) {
            const Eigen::Vector4d d = domain(S.p);
            return py::make_tuple(d(0), d(1), d(2), d(3));
          },
          "(u0, u1, v0, v1)")
      .def(
          "evaluate",
          [](const Surface& S, const DoubleArray& u, const DoubleArray& v, int du, int dv) {
            return surface_at(S, u, v, du, dv, false);
          },
          py::arg("u"), py::arg("v"), py::arg("du") = 0, py::arg("dv") = 0,
          R"(d^(du+dv) S / du^du dv^dv at the pairs (u[k], v[k]) (arrays of one shape, or one a
scalar) -> shape + (3,). du = dv = 0: the points.)")
      .def(
          "__call__",
          [](const Surface& S, const DoubleArray& u, const DoubleArray& v) {
            return surface_at(S, u, v, 0, 0, false);
          },
          py::arg("u"), py::arg("v"), "S(u, v) -> shape + (3,).")
      .def(
          "normals",
          [](const Surface& S, const DoubleArray& u, const DoubleArray& v) {
            return surface_at(S, u, v, 0, 0, true);
          },
          py::arg("u"), py::arg("v"), "Unit normals S_u x S_v / |S_u x S_v| -> shape + (3,).")
      .def(
          "grid",
          [](const Surface& S, const VectorXd& u, const VectorXd& v) {
            MatrixXd G;
            {
              py::gil_scoped_release release;
              G = evaluate_grid(S.p, u, v);
            }
            py::array_t<double> out({v.size(), u.size(), Index(3)});
            double* o = out.mutable_data();
            for (Index r = 0; r < G.rows(); ++r)
              for (int c = 0; c < 3; ++c)
                o[3 * r + c] = G(r, c);
            return out;
          },
          py::arg("u"), py::arg("v"), "S on the grid u x v -> (len(v), len(u), 3).")
      .def(
          "closest_point",
          [](const Surface& S, const MatrixXd& P, int su, int sv) {
            require_shape(P, 3, "P");
            py::gil_scoped_release release;
            return project_to_surface(S.p, P, su, sv);
          },
          py::arg("P"), py::arg("samples_u") = 512, py::arg("samples_v") = 128,
          R"(Closest points of the surface to P (N, 3): Newton on |S(u,v) - p|^2 from the nearest
samples of a samples_u x samples_v grid (FLANN) -> SurfaceProjection.)")
      .def(
          "distance",
          [](const Surface& S, const MatrixXd& P, int su, int sv) {
            require_shape(P, 3, "P");
            py::gil_scoped_release release;
            return VectorXd(project_to_surface(S.p, P, su, sv).distance);
          },
          py::arg("P"), py::arg("samples_u") = 512, py::arg("samples_v") = 128,
          "Exact distances of the points P (N, 3) to the surface -> (N,).")
      .def(
          "mesh",
          [](const Surface& S, int nu, int nv, std::vector<double> required_v, bool cap) {
            std::pair<MatrixXd, MatrixXi> VF;
            {
              py::gil_scoped_release release;
              VF = mesh_of(S, {nu, nv, std::move(required_v), cap, MeshPrecision::float64});
            }
            return py::make_tuple(std::move(VF.first), std::move(VF.second));
          },
          py::arg("nu") = 400, py::arg("nv") = 120, py::arg("required_v") = std::vector<double>{},
          py::arg("cap") = false,
          R"(Triangle mesh (V (N, 3), F (M, 3) int32): nu samples around (curvature-adaptive), nv
along v plus the rows required_v exactly; cap closes both ends (closed_u surfaces).)")
      .def(
          "write",
          [](const Surface& S, const py::object& path, const std::string& units,
             const std::map<std::string, std::string>& meta, int nu, int nv,
             std::vector<double> required_v, bool cap, const std::vector<MatrixXd>& polylines,
             const std::string& precision) {
            write_surface(S, require_path(path), units, meta,
                          {nu, nv, std::move(required_v), cap, mesh_precision(precision)},
                          polylines);
          },
          py::arg("path"), py::arg("units") = "mm",
          py::arg("meta") = std::map<std::string, std::string>{}, py::arg("nu") = 400,
          py::arg("nv") = 120, py::arg("required_v") = std::vector<double>{},
          py::arg("cap") = false, py::arg("polylines") = std::vector<MatrixXd>{},
          py::arg("precision") = "float64",
          R"(Writes the surface by extension, atomically: .igs/.iges (IGES 5.3 entity 128, `units`
label), .stp/.step (AP214: one B-spline face, or with cap one closed solid with ruled end caps),
.json (exact, with meta), .stl/.obj/.ply/.off (mesh of nu x nv samples, optional cap;
.ply/.obj coordinates in `precision`, "float64" or "float32"), .png (shaded preview with
polylines).)")
      .def("__repr__", [](const Surface& S) {
        return "<Surface degree " + std::to_string(S.b.degree_u) + " x " +
               std::to_string(S.b.degree_v) + ", control net " + std::to_string(S.b.num_u) + " x " +
               std::to_string(S.b.num_v) + (S.b.closed_u ? ", closed in u>" : ">");
      });
  m.def("read_surface", &read_surface, py::arg("path"),
        "Reads a surface from .json (write_surface_json) or .igs/.iges (first entity 128).");
}

// The items of a list as T (Section, Guide): T objects as they are, (P, 3) arrays (P >= min_rows)
// as T{"k", points, lines 1..P} with k the position in the list.
template <class T>
std::vector<T> items_of(const py::handle& list, const char* what, Index min_rows) {
  std::vector<T> items;
  for (const py::handle& item : list) {
    if (py::isinstance<T>(item)) {
      items.push_back(item.cast<T>());
    } else {
      const MatrixXd P = item.cast<MatrixXd>();
      require_shape(P, 3, what, min_rows);
      items.push_back({std::to_string(items.size()), P, row_numbers(P.rows())});
    }
  }
  return items;
}

} // namespace

SectionsArg sections_arg(const py::object& o) {
  if (const auto path = path_of(o)) {
    SectionSet set;
    {
      py::gil_scoped_release release;
      set = read_sections(*path);
    }
    return {std::move(set.sections), *path, std::move(set.warnings)};
  }
  if (py::isinstance<SectionSet>(o)) {
    const SectionSet& set = o.cast<const SectionSet&>();
    return {set.sections, set.path, set.warnings};
  }
  return {items_of<Section>(o, "section points", 1), "", {}};
}

namespace {

// Guides: None, a path, a GuideSet, or a list of Guide objects or (P, 3) arrays.
std::optional<GuideSet> guides_arg(const py::object& o) {
  if (o.is_none())
    return std::nullopt;
  if (const auto path = path_of(o)) {
    py::gil_scoped_release release;
    return read_guides(*path);
  }
  if (py::isinstance<GuideSet>(o))
    return o.cast<GuideSet>();
  return GuideSet{"<guides>", items_of<Guide>(o, "guide points", 2)};
}

// An exponent given by name (as the CLI's --param) or as a number.
double exponent_arg(const py::object& o, const char* what) {
  if (py::isinstance<py::str>(o))
    return choice<double>({{"chord", 1.0}, {"centripetal", 0.5}}, o.cast<std::string>(), what);
  return o.cast<double>();
}

// The span degree: "auto" (chosen by leave-one-out) or a degree >= 1 (as --span-degree).
int span_degree_arg(const py::object& o) {
  if (py::isinstance<py::str>(o)) {
    if (o.cast<std::string>() != "auto")
      throw py::value_error("span_degree: expected \"auto\" or a degree >= 1");
    return kAutoSpanDegree;
  }
  const int q = o.cast<int>();
  if (q < 1)
    throw py::value_error("span_degree: expected \"auto\" or a degree >= 1");
  return q;
}

} // namespace

LoftArgs loft_args(int degree, const py::object& span_degree, const std::string& align,
                   const std::string& match, const py::object& param, const std::string& span,
                   const py::object& guides, double guide_tolerance) {
  LoftArgs a;
  LoftOptions& o = a.options.loft;
  o.degree = degree;
  o.span_degree = span_degree_arg(span_degree);
  o.align = choice<StartAlign>({{"first", StartAlign::first},
                                {"le", StartAlign::leading_edge},
                                {"te", StartAlign::trailing_edge}},
                               align, "align");
  o.match = choice<Correspondence>({{"auto", Correspondence::automatic},
                                    {"index", Correspondence::index},
                                    {"arclength", Correspondence::arc_length}},
                                   match, "match");
  o.section_exponent = exponent_arg(param, "param");
  o.span = choice<SpanParameters>({{"auto", SpanParameters::automatic},
                                   {"station", SpanParameters::station},
                                   {"chord", SpanParameters::chord},
                                   {"centripetal", SpanParameters::centripetal},
                                   {"uniform", SpanParameters::uniform}},
                                  span, "span");
  a.options.guide_tolerance = guide_tolerance;
  a.guides = guides_arg(guides);
  return a;
}

namespace {

// The result of loft(): the loft, its surface ready for evaluation, the guides' fits.
struct Loft {
  LoftResult result;
  std::shared_ptr<Surface> surface;
  std::vector<GuideFit> guides;
  double max_guide_deviation = 0, max_input_deviation = 0;
  std::vector<std::string> warnings;
};

// Runs `body` (which lofts) and reports a property of the sections of a file as the CLI does:
// InputError "FILE: message".
template <class F>
auto as_input_error(const std::string& path, F body) {
  try {
    return body();
  } catch (const std::invalid_argument& e) {
    if (path.empty())
      throw;
    throw_input_error(path, 0, e.what());
  }
}

Loft loft_of(const std::vector<Section>& sections, const LoftArgs& a) {
  Loft L;
  if (a.guides) {
    GuidedLoftResult g = guided_loft(sections, *a.guides, a.options);
    L.result = std::move(g.loft);
    L.guides = std::move(g.guides);
    L.max_guide_deviation = g.max_guide_deviation;
    L.max_input_deviation = g.max_input_deviation;
  } else {
    L.result = loft_sections(sections, a.options.loft);
  }
  L.surface = std::make_shared<Surface>(L.result.surface);
  return L;
}

const char* const kLoftOptionsDoc = R"(
Options (as `interlin loft`):
  degree            spline degree around the sections (default 3)
  span              spacing of the sections along the span: "auto" (default: chosen by
                    leave-one-out cross-validation), "station" (the sections' own positions),
                    "chord", "centripetal" or "uniform" (as --span)
  span_degree       degree along the span: "auto" (default: 3, 5 or #sections - 1 by
                    leave-one-out) or a degree, reduced to #sections - 1
  align             section start: "first" (keep), "le" / "te" (detected edge)
  match             correspondence: "auto", "index" (equal counts), "arclength"
  param             parameters along the sections: "chord", "centripetal" or an exponent
  guides            guide lines (path, GuideSet, or list of Guide / (P, 3) arrays): the surface is
                    then a Gordon surface through every section and every guide
  guide_tolerance   a guide must pass within this x bbox diagonal of every section (1e-3)
sections: a section file path, a SectionSet, or a list of Section / (P, 3) arrays.
Errors: InputError with the CLI's one-line message for bad files, ValueError for bad arguments.)";

void bind_loft_results(py::module_& m) {
  py::class_<PreparedSection>(m, "PreparedSection", R"(A section after preparation: points (P, 3)
rolled and wound like the first section; source (P,) rows of the input section (-1: a crossing
inserted by a guide); le, te detected edge rows (-1: none); reversed.)")
      .def_readonly("id", &PreparedSection::id)
      .def_readonly("points", &PreparedSection::points)
      .def_readonly("lines", &PreparedSection::lines)
      .def_readonly("source", &PreparedSection::source)
      .def_readonly("le", &PreparedSection::le)
      .def_readonly("te", &PreparedSection::te)
      .def_readonly("reversed", &PreparedSection::reversed);
  py::class_<GuideFit>(m, "GuideFit", R"(One guide after fitting: id, u (its parameter around the
sections), points (R, 3) and v (R,) the interpolated points and span parameters, crossing (K,)
rows of the crossings, input_deviation (per input point), deviation (per row), curve_deviation.)")
      .def_readonly("id", &GuideFit::id)
      .def_readonly("u", &GuideFit::u)
      .def_readonly("points", &GuideFit::points)
      .def_readonly("v", &GuideFit::v)
      .def_readonly("crossing", &GuideFit::crossing)
      .def_readonly("source", &GuideFit::source)
      .def_readonly("input_row", &GuideFit::input_row)
      .def_readonly("input_deviation", &GuideFit::input_deviation)
      .def_readonly("deviation", &GuideFit::deviation)
      .def_readonly("curve_deviation", &GuideFit::curve_deviation)
      .def_readonly("reversed", &GuideFit::reversed);
  py::class_<SpanCandidate>(m, "SpanCandidate", R"(One spanwise model: parameters ("station",
"chord", "centripetal", "uniform"), degree, and its leave-one-out error loo_max, loo_rms (each
interior section withheld in turn; NaN without interior sections), score.)")
      .def_property_readonly("parameters",
                             [](const SpanCandidate& c) { return to_string(c.parameters); })
      .def_readonly("degree", &SpanCandidate::degree)
      .def_readonly("loo_max", &SpanCandidate::loo_max)
      .def_readonly("loo_rms", &SpanCandidate::loo_rms)
      .def_property_readonly("score", &span_model_score,
                             "What span=\"auto\" minimises (lower is better; ties go to the "
                             "earlier candidate).");
  py::class_<SpanModel>(m, "SpanModel", R"(The spanwise model a loft used: used (SpanCandidate),
chosen (by leave-one-out among candidates, else fixed by the options), candidates, stacking
("parallel planes", "coaxial surfaces of revolution about z" or "none"), stations (K,) (empty
for none), folds (sections withheld in turn).)")
      .def_readonly("used", &SpanModel::used)
      .def_readonly("chosen", &SpanModel::chosen)
      .def_readonly("candidates", &SpanModel::candidates)
      .def_property_readonly("stacking",
                             [](const SpanModel& m) { return to_string(m.stations.stacking); })
      .def_property_readonly("stations", [](const SpanModel& m) { return m.stations.station; })
      .def_readonly("folds", &SpanModel::folds);
  py::class_<Loft>(m, "Loft", R"(Result of loft(): surface (Surface; u around, v along the span),
section_v (K,), point_u (list of (P_k,)), sections (list of PreparedSection), correspondence,
deviation (list of (P_k,) |S(u_i, v_k) - P_i|), max_deviation, bbox_diagonal, notes, span
(SpanModel: the spanwise model and its leave-one-out error), warnings
(from the file), guides (list of GuideFit), max_guide_deviation, max_input_deviation.)")
      .def_property_readonly("surface", [](const Loft& L) { return L.surface; })
      .def_property_readonly("section_v", [](const Loft& L) { return L.result.section_v; })
      .def_property_readonly("point_u", [](const Loft& L) { return L.result.point_u; })
      .def_property_readonly("sections", [](const Loft& L) { return L.result.sections; })
      .def_property_readonly("correspondence",
                             [](const Loft& L) {
                               return L.result.used == Correspondence::index ? "index"
                                                                             : "arclength";
                             })
      .def_property_readonly("deviation", [](const Loft& L) { return L.result.deviation; })
      .def_property_readonly("max_deviation", [](const Loft& L) { return L.result.max_deviation; })
      .def_property_readonly("bbox_diagonal", [](const Loft& L) { return L.result.bbox_diagonal; })
      .def_property_readonly("notes", [](const Loft& L) { return L.result.notes; })
      .def_property_readonly("span", [](const Loft& L) { return L.result.span; })
      .def_readonly("warnings", &Loft::warnings)
      .def_readonly("guides", &Loft::guides)
      .def_readonly("max_guide_deviation", &Loft::max_guide_deviation)
      .def_readonly("max_input_deviation", &Loft::max_input_deviation);
}

// Hold-out: the C++ result with the loft wrapped as above.
struct Holdout {
  HoldoutResult result;
  Loft loft;
  std::vector<std::string> test_ids;
};

void bind_loft_functions(py::module_& m) {
  m.def(
      "loft",
      [](const py::object& sections, int degree, const py::object& span_degree,
         const std::string& align, const std::string& match, const py::object& param,
         const std::string& span, const py::object& guides, double guide_tolerance) {
        const SectionsArg s = sections_arg(sections);
        const LoftArgs a =
            loft_args(degree, span_degree, align, match, param, span, guides, guide_tolerance);
        py::gil_scoped_release release;
        Loft L = as_input_error(s.path, [&] { return loft_of(s.sections, a); });
        L.warnings = s.warnings;
        return L;
      },
      py::arg("sections"), py::arg("degree") = 3, py::arg("span_degree") = "auto",
      py::arg("align") = "first", py::arg("match") = "auto", py::arg("param") = "chord",
      py::arg("span") = "auto", py::arg("guides") = py::none(), py::arg("guide_tolerance") = 1e-3,
      (std::string("Lofts closed sections into one B-spline surface through every section "
                   "exactly (seed 001 §2.5) -> Loft.\n") +
       kLoftOptionsDoc)
          .c_str());

  py::class_<Holdout>(m, "Holdout", R"(Result of holdout(): train, test (section indices),
test_ids, distance (list of (P,) distances of each withheld section's points to the surface),
max, rms (over all withheld points), loft (the Loft of the training sections).)")
      .def_property_readonly("train", [](const Holdout& h) { return h.result.train; })
      .def_property_readonly("test", [](const Holdout& h) { return h.result.test; })
      .def_readonly("test_ids", &Holdout::test_ids)
      .def_property_readonly("distance", [](const Holdout& h) { return h.result.distance; })
      .def_property_readonly("max", [](const Holdout& h) { return h.result.max; })
      .def_property_readonly("rms", [](const Holdout& h) { return h.result.rms; })
      .def_readonly("loft", &Holdout::loft);
  m.def(
      "holdout",
      [](const py::object& sections, std::optional<std::vector<size_t>> withhold,
         std::optional<int> every, int degree, const py::object& span_degree,
         const std::string& align, const std::string& match, const py::object& param,
         const std::string& span, const py::object& guides, double guide_tolerance) {
        if (withhold.has_value() == every.has_value())
          throw py::value_error("give exactly one of withhold=[indices] and every=K");
        const SectionsArg s = sections_arg(sections);
        const LoftArgs a =
            loft_args(degree, span_degree, align, match, param, span, guides, guide_tolerance);
        py::gil_scoped_release release;
        Holdout h;
        const std::vector<size_t> out =
            withhold ? *withhold : withheld_every(s.sections.size(), *every);
        h.result = as_input_error(s.path, [&] {
          return holdout_study(s.sections, out, [&](const std::vector<Section>& train) {
            h.loft = loft_of(train, a);
            return h.loft.result;
          });
        });
        for (size_t t : h.result.test)
          h.test_ids.push_back(s.sections[t].id);
        return h;
      },
      py::arg("sections"), py::arg("withhold") = py::none(), py::arg("every") = py::none(),
      py::arg("degree") = 3, py::arg("span_degree") = "auto", py::arg("align") = "first",
      py::arg("match") = "auto", py::arg("param") = "chord", py::arg("span") = "auto",
      py::arg("guides") = py::none(), py::arg("guide_tolerance") = 1e-3,
      (std::string(R"(Hold-out study: lofts the sections not withheld and measures the exact
distance of every point of the withheld sections to that surface -> Holdout.
withhold  indices of the withheld sections (0-based; neither the first nor the last), or
every     K: keep sections 0, K, 2K, ... and the last (interlin loft --holdout K).
)") + kLoftOptionsDoc)
          .c_str());
  m.def("withheld_every", &withheld_every, py::arg("count"), py::arg("K"),
        "The sections withheld when every K-th of `count` is kept (and the last).");
}

} // namespace

void bind_loft(py::module_& m) {
  bind_surface(m);
  bind_loft_results(m);
  bind_loft_functions(m);
}

} // namespace interlin::python
