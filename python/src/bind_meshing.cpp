// Python bindings of reconstruction/meshing: implicit bodies to closed meshes, mesh checks,
// smoothing on the surface, loop triangulation.
#include "bindings.h"

#include "interlin/reconstruction/meshing/implicit_mesh.h"
#include "interlin/reconstruction/meshing/mesh_check.h"
#include "interlin/reconstruction/meshing/surface_mesh.h"
#include "interlin/reconstruction/meshing/surface_smoothing.h"

namespace interlin::python {

namespace {

using Eigen::MatrixXd;
using Eigen::MatrixXi;

void check_mesh_arrays(const MatrixXd& V, const MatrixXi& F) {
  require_shape(V, 3, "V");
  if (F.cols() != 3)
    throw py::value_error("F: expected an (M, 3) array of vertex indices");
}

py::dict report_dict(const MeshReport& r) {
  py::dict d;
  d["vertices"] = r.vertices;
  d["faces"] = r.faces;
  d["boundary_edges"] = r.boundary_edges;
  d["nonmanifold_edges"] = r.nonmanifold_edges;
  d["nonmanifold_vertices"] = r.nonmanifold_vertices;
  d["components"] = r.components;
  d["euler"] = r.euler;
  d["genus"] = r.genus;
  d["consistently_oriented"] = r.consistently_oriented;
  d["area"] = r.area;
  d["volume"] = r.volume;
  d["min_angle_deg"] = r.min_angle_deg;
  d["max_aspect_ratio"] = r.max_aspect_ratio;
  d["degenerate_faces"] = r.degenerate_faces;
  d["watertight"] = r.watertight();
  return d;
}

} // namespace

void bind_meshing(py::module_& m) {
  m.def(
      "mesh_implicit",
      [](const ImplicitFunction& f, int resolution, double cell, const std::optional<MatrixXd>& box,
         const Eigen::Vector3i& subboxes, int threads, bool project, double tolerance) {
        ImplicitMeshOptions o;
        if (box)
          o.box = box_from_array(*box);
        o.resolution = resolution, o.cell = cell, o.subboxes = subboxes.array();
        o.threads = threads, o.project = project;
        o.root.tolerance = tolerance;
        MatrixXd V;
        MatrixXi F;
        {
          py::gil_scoped_release release;
          implicit_mesh(f, o, V, F);
        }
        return py::make_tuple(std::move(V), std::move(F));
      },
      py::arg("f"), py::arg("resolution") = 128, py::arg("cell") = 0.0, py::arg("box") = py::none(),
      py::arg("subboxes") = Eigen::Vector3i::Zero(), py::arg("threads") = 0,
      py::arg("project") = true, py::arg("tolerance") = 1e-10,
      R"(Closed mesh of the body {F > 0} (interlin mesh): a grid with `resolution` cubic cells along
the box's longest side (or cells of size `cell`), marching cubes per sub-box on `threads` threads
(0: all cores), vertices projected onto F = 0 -> (V (N, 3), F (M, 3) int32). box (2, 3) defaults
to f.box; the mesh closes along the box where the body reaches it. Closed, 2-manifold, oriented
outward.)");
  m.def(
      "check_mesh",
      [](const MatrixXd& V, const MatrixXi& F) {
        check_mesh_arrays(V, F);
        MeshReport r;
        {
          py::gil_scoped_release release;
          r = check_mesh(V, F);
        }
        return report_dict(r);
      },
      py::arg("V"), py::arg("F"),
      R"(Topology and quality of a triangle mesh V (N, 3), F (M, 3) -> dict: vertices, faces,
boundary_edges, nonmanifold_edges, nonmanifold_vertices, components, euler, genus,
consistently_oriented, area, volume (signed), min_angle_deg, max_aspect_ratio, degenerate_faces,
watertight.)");
  m.def(
      "smooth_on_surface",
      [](const ImplicitFunction& f, MatrixXd V, const MatrixXi& F, int iterations, double kappa,
         bool laplacian, int threads) {
        check_mesh_arrays(V, F);
        SurfaceSmoothingOptions o;
        o.iterations = iterations, o.kappa = kappa, o.laplacian = laplacian, o.threads = threads;
        SurfaceSmoothingReport r;
        {
          py::gil_scoped_release release;
          r = smooth_on_surface(f, V, F, o);
        }
        return py::make_tuple(std::move(V), r.fit);
      },
      py::arg("f"), py::arg("V"), py::arg("F"), py::arg("iterations") = 4, py::arg("kappa") = 0.001,
      py::arg("laplacian") = true, py::arg("threads") = 0,
      R"(Seed 003's smoothing: vertices slide over F = 0 onto creases -> (V (N, 3), fit) with fit
the sum of squared centroid offsets before the first and after each sweep.)");
  m.def("triangulate_loop", &triangulate_loop, py::arg("P"),
        "Triangles (P - 2, 3) filling the closed loop P (P, 3): constrained Delaunay in its "
        "best-fit plane.");
}

} // namespace interlin::python
