// Python bindings of reconstruction/io: section, guide and points files, mesh and volume mesh
// files, previews.
#include "bindings.h"

#include "interlin/reconstruction/io/guide_csv.h"
#include "interlin/reconstruction/io/mesh_io.h"
#include "interlin/reconstruction/io/points_csv.h"
#include "interlin/reconstruction/io/preview.h"
#include "interlin/reconstruction/io/section_csv.h"
#include "interlin/reconstruction/io/volume_mesh_io.h"

namespace interlin::python {

namespace {

using Eigen::MatrixXd;
using Eigen::MatrixXi;

template <class T>
T with_points(const std::string& id, MatrixXd points, std::vector<long> lines) {
  require_shape(points, 3, "points", 1);
  if (lines.empty())
    lines = row_numbers(points.rows());
  if (lines.size() != static_cast<size_t>(points.rows()))
    throw py::value_error("lines: expected one line number per point");
  return T{id, std::move(points), std::move(lines)};
}

void bind_sections(py::module_& m) {
  py::class_<Section>(m, "Section", R"(One closed blade section.
Section(id, points (P, 3), lines=None): lines are the source line numbers of the points (for
messages; default 1..P).)")
      .def(py::init(&with_points<Section>), py::arg("id"), py::arg("points"),
           py::arg("lines") = std::vector<long>{})
      .def_readonly("id", &Section::id)
      .def_readonly("points", &Section::points, "(P, 3)")
      .def_readonly("lines", &Section::lines)
      .def("__repr__", [](const Section& s) {
        return "<Section " + s.id + ", " + std::to_string(s.points.rows()) + " points>";
      });
  py::class_<SectionSet>(m, "SectionSet", "The sections of one file, its path and warnings.")
      .def_readonly("path", &SectionSet::path)
      .def_readonly("sections", &SectionSet::sections)
      .def_readonly("warnings", &SectionSet::warnings)
      .def("__len__", [](const SectionSet& s) { return s.sections.size(); })
      .def("__getitem__", [](const SectionSet& s, size_t i) {
        if (i >= s.sections.size())
          throw py::index_error();
        return s.sections[i];
      });
  m.def("read_sections", &read_sections, py::arg("path"), release_gil(),
        R"(Reads a section file (CSV section,index,x,y,z or plain x y z blocks; docs/formats.md)
-> SectionSet. InputError "FILE:LINE: ..." exactly as `interlin loft` prints it.)");
  m.def("write_sections", &write_sections_csv, py::arg("path"), py::arg("sections"), release_gil(),
        "Writes sections as CSV section,index,x,y,z (17 digits, atomically).");

  py::class_<Guide>(m, "Guide", "One guide polyline: Guide(id, points (P, 3), lines=None).")
      .def(py::init(&with_points<Guide>), py::arg("id"), py::arg("points"),
           py::arg("lines") = std::vector<long>{})
      .def_readonly("id", &Guide::id)
      .def_readonly("points", &Guide::points)
      .def_readonly("lines", &Guide::lines);
  py::class_<GuideSet>(m, "GuideSet", "Guides of one file: GuideSet(guides, path='<guides>').")
      .def(py::init([](std::vector<Guide> guides, std::string path) {
             return GuideSet{std::move(path), std::move(guides)};
           }),
           py::arg("guides"), py::arg("path") = "<guides>")
      .def_readonly("path", &GuideSet::path)
      .def_readonly("guides", &GuideSet::guides);
  m.def("read_guides", &read_guides, py::arg("path"), release_gil(),
        "Reads a guide file (CSV guide,index,x,y,z) -> GuideSet. InputError on bad input.");
  m.def("read_points", &read_points_csv, py::arg("path"), release_gil(),
        "Reads a points file (CSV with columns x, y, z) -> (N, 3). InputError on bad input.");
}

void bind_meshes(py::module_& m) {
  m.def(
      "read_mesh",
      [](const std::string& path) {
        MatrixXd V;
        MatrixXi F;
        {
          py::gil_scoped_release release;
          read_mesh(path, V, F);
        }
        return py::make_tuple(std::move(V), std::move(F));
      },
      py::arg("path"),
      "Reads a triangle mesh (.stl .obj .ply .off) -> (V (N, 3), F (M, 3) int32).");
  m.def(
      "write_mesh",
      [](const std::string& path, const MatrixXd& V, const MatrixXi& F,
         const std::string& precision) {
        require_shape(V, 3, "V");
        if (F.cols() != 3)
          throw py::value_error("F: expected an (M, 3) array of vertex indices");
        write_mesh(path, V, F, mesh_precision(precision));
      },
      py::arg("path"), py::arg("V"), py::arg("F"), py::arg("precision") = "float64", release_gil(),
      R"(Writes a triangle mesh by extension, atomically: V (N, 3), F (M, 3). .ply (binary) and .obj
carry `precision` coordinates ("float64": exact, or "float32"); .stl and .off are float32.)");
  m.def(
      "write_volume_mesh",
      [](const std::string& path, const MatrixXd& V, const MatrixXi& C, const MatrixXi& B,
         const std::map<std::string, Eigen::VectorXd>& node_fields,
         const std::map<std::string, Eigen::VectorXd>& element_fields) {
        require_shape(V, 3, "V");
        VolumeMeshFields fields;
        fields.node.assign(node_fields.begin(), node_fields.end());
        fields.element.assign(element_fields.begin(), element_fields.end());
        write_volume_mesh(path, V, C, B, fields);
      },
      py::arg("path"), py::arg("V"), py::arg("C"), py::arg("B") = MatrixXi(0, 3),
      py::arg("node_fields") = std::map<std::string, Eigen::VectorXd>{},
      py::arg("element_fields") = std::map<std::string, Eigen::VectorXd>{}, release_gil(),
      R"(Writes a volume mesh by extension, atomically: .vtu (VTK XML, with the named node and
element fields: dicts of (N,) and (E,) arrays), .msh (Gmsh 4.1), .inp (Abaqus / CalculiX).
V (N, 3), C (E, 4) tetrahedra or (E, 8) hexahedra (VTK order), B (K, 3 or 4) boundary facets
(mesh_volume's).)");

  const auto options = [](int width, int height, const Eigen::Vector3d& up, double azimuth,
                          double elevation, int supersample) {
    PreviewOptions o;
    o.width = width, o.height = height, o.up = up;
    o.azimuth_deg = azimuth, o.elevation_deg = elevation, o.supersample = supersample;
    return o;
  };
  m.def(
      "render_preview",
      [options](const MatrixXd& V, const MatrixXi& F, const std::vector<MatrixXd>& polylines,
                int width, int height, const Eigen::Vector3d& up, double azimuth, double elevation,
                int supersample) {
        Image img;
        {
          py::gil_scoped_release release;
          img = render_preview(V, F, polylines,
                               options(width, height, up, azimuth, elevation, supersample));
        }
        py::array_t<std::uint8_t> out({img.height, img.width, 3});
        std::copy(img.rgb.begin(), img.rgb.end(), out.mutable_data());
        return out;
      },
      py::arg("V"), py::arg("F"), py::arg("polylines") = std::vector<MatrixXd>{},
      py::arg("width") = 1200, py::arg("height") = 900, py::arg("up") = Eigen::Vector3d::Zero(),
      py::arg("azimuth") = 45.0, py::arg("elevation") = 25.0, py::arg("supersample") = 2,
      R"(Shaded 3/4 view of a triangle mesh V (N, 3), F (M, 3) with dark polylines (each (P, 3))
on it -> (height, width, 3) uint8 RGB. up: the vertical direction (zero: automatic).)");
  m.def(
      "write_png",
      [](const std::string& path,
         const py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>& rgb) {
        if (rgb.ndim() != 3 || rgb.shape(2) != 3)
          throw py::value_error("image: expected an (H, W, 3) uint8 array");
        Image img{int(rgb.shape(1)), int(rgb.shape(0)),
                  std::vector<std::uint8_t>(rgb.data(), rgb.data() + rgb.size())};
        py::gil_scoped_release release;
        write_png(path, img);
      },
      py::arg("path"), py::arg("image"), "Writes an (H, W, 3) uint8 image as PNG, atomically.");
}

} // namespace

MeshPrecision mesh_precision(const std::string& name) {
  return choice<MeshPrecision>(
      {{"float64", MeshPrecision::float64}, {"float32", MeshPrecision::float32}}, name,
      "precision");
}

void bind_io(py::module_& m) {
  bind_sections(m);
  bind_meshes(m);
}

} // namespace interlin::python
