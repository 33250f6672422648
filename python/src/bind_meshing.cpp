// Python bindings of reconstruction/meshing: implicit bodies to closed meshes and to volume
// meshes and their adaptive refinement (seed 003 §7.2), mesh checks, smoothing on the surface,
// loop triangulation.
#include "bindings.h"

#include "interlin/reconstruction/meshing/adaptive_refinement.h"
#include "interlin/reconstruction/meshing/facet_sag.h"
#include "interlin/reconstruction/meshing/hexahedral_refinement.h"
#include "interlin/reconstruction/meshing/implicit_mesh.h"
#include "interlin/reconstruction/meshing/mesh_check.h"
#include "interlin/reconstruction/meshing/surface_mesh.h"
#include "interlin/reconstruction/meshing/surface_smoothing.h"
#include "interlin/reconstruction/meshing/volume_mesh.h"
#include "interlin/reconstruction/meshing/volume_quality.h"

namespace interlin::python {

namespace {

using Eigen::MatrixXd;
using Eigen::MatrixXi;
using Flags = Eigen::Matrix<bool, Eigen::Dynamic, 1>;

void check_mesh_arrays(const MatrixXd& V, const MatrixXi& F) {
  require_shape(V, 3, "V");
  if (F.cols() != 3)
    throw py::value_error("F: expected an (M, 3) array of vertex indices");
}

py::dict report_dict(const MeshReport& r) {
  py::dict d =
      fields_dict(r, field("vertices", &MeshReport::vertices), field("faces", &MeshReport::faces),
                  field("boundary_edges", &MeshReport::boundary_edges),
                  field("nonmanifold_edges", &MeshReport::nonmanifold_edges),
                  field("nonmanifold_vertices", &MeshReport::nonmanifold_vertices),
                  field("components", &MeshReport::components), field("euler", &MeshReport::euler),
                  field("genus", &MeshReport::genus),
                  field("consistently_oriented", &MeshReport::consistently_oriented),
                  field("area", &MeshReport::area), field("volume", &MeshReport::volume),
                  field("min_angle_deg", &MeshReport::min_angle_deg),
                  field("max_aspect_ratio", &MeshReport::max_aspect_ratio),
                  field("degenerate_faces", &MeshReport::degenerate_faces));
  d["watertight"] = r.watertight();
  return d;
}

py::dict volume_info_dict(const VolumeMeshInfo& i) {
  py::dict d = fields_dict(
      i, field("inside_nodes", &VolumeMeshInfo::inside_nodes),
      field("dropped_nodes", &VolumeMeshInfo::dropped_nodes),
      field("removed_cells", &VolumeMeshInfo::removed_cells),
      field("inner_cells", &VolumeMeshInfo::inner_cells),
      field("layer_elements", &VolumeMeshInfo::layer_elements),
      field("unprojected", &VolumeMeshInfo::unprojected), field("held", &VolumeMeshInfo::held),
      field("max_boundary_f", &VolumeMeshInfo::max_boundary_f),
      field("on_zero", &VolumeMeshInfo::on_zero), field("clipped", &VolumeMeshInfo::clipped),
      field("suggested_cell", &VolumeMeshInfo::suggested_cell),
      field("folded_pillows", &VolumeMeshInfo::folded_pillows),
      field("offset_grid", &VolumeMeshInfo::offset_grid));
  d["boundary"] = boundary_name(i.boundary);
  d["body_volume"] = i.coverage.body;
  d["lost_volume"] = i.coverage.lost;
  d["lost_thickness"] = i.coverage.thickness();
  return d;
}

// A UserWarning when the projected layer leaves out more than kLostVolumeWarning of the body.
void warn_lost_volume(const VolumeMeshInfo& i, bool tets, bool dual) {
  if (!(i.lost_fraction() > kLostVolumeWarning))
    return;
  const std::string m =
      "mesh_volume: the mesh leaves out " + std::to_string(100 * i.lost_fraction()) +
      " % of the body's volume (walls about " + std::to_string(i.coverage.thickness()) +
      (dual ? " thick (walls with no grid node, slivers under held boundary points)"
            : " thick have no inner cell under the boundary layer") +
      "): use cell=" + std::to_string(i.suggested_cell) + " or smaller, or " +
      (tets ? "boundary='cut'" : "elements='tet'");
  if (PyErr_WarnEx(PyExc_UserWarning, m.c_str(), 1) != 0)
    throw py::error_already_set();
}

py::dict quality_dict(const VolumeQuality& q) {
  return fields_dict(q, field("elements", &VolumeQuality::elements),
                     field("inverted", &VolumeQuality::inverted),
                     field("volume", &VolumeQuality::volume),
                     field("min_dihedral_deg", &VolumeQuality::min_dihedral_deg),
                     field("max_dihedral_deg", &VolumeQuality::max_dihedral_deg),
                     field("min_scaled_jacobian", &VolumeQuality::min_scaled_jacobian),
                     field("mean_scaled_jacobian", &VolumeQuality::mean_scaled_jacobian),
                     field("min_radius_ratio", &VolumeQuality::min_radius_ratio),
                     field("mean_radius_ratio", &VolumeQuality::mean_radius_ratio),
                     field("outside_10_170", &VolumeQuality::outside_10_170));
}

// The library's per-node flags (char) as a NumPy bool array (N,).
Flags boundary_flags(const std::vector<char>& b) {
  Flags on(static_cast<Eigen::Index>(b.size()));
  for (size_t i = 0; i < b.size(); ++i)
    on(static_cast<Eigen::Index>(i)) = b[i] != 0;
  return on;
}

py::dict refinement_dict(const RefinementReport& r) {
  return fields_dict(
      r, field("flagged", &RefinementReport::flagged),
      field("refined_nodes", &RefinementReport::refined_nodes),
      field("split", &RefinementReport::split), field("new_nodes", &RefinementReport::new_nodes),
      field("projected", &RefinementReport::projected), field("held", &RefinementReport::held),
      field("widened", &RefinementReport::widened), field("folded", &RefinementReport::folded),
      field("still_folded", &RefinementReport::still_folded),
      field("undone", &RefinementReport::undone));
}

// Elements (E, corners: 4 tetrahedra, 8 hexahedra) and boundary flags (N,) as the refinement
// takes them; ValueError otherwise.
std::vector<char> refinement_input(const MatrixXd& V, const MatrixXi& C, const Flags& boundary,
                                   int corners = 4) {
  require_shape(V, 3, "V");
  if (C.cols() != corners)
    throw py::value_error(corners == 4 ? "C: expected an (E, 4) array of tetrahedra"
                                       : "C: expected an (E, 8) array of hexahedra");
  if (boundary.size() != V.rows())
    throw py::value_error("boundary: expected one flag per node of V");
  return std::vector<char>(boundary.data(), boundary.data() + boundary.size());
}

py::tuple refined_mesh(MatrixXd V, MatrixXi C, const std::vector<char>& b, py::object extra) {
  return py::make_tuple(std::move(V), std::move(C), boundary_flags(b), std::move(extra));
}

// One refinement pass of either element kind (Corners 4: tetrahedra, 8: hexahedra) as a Python
// function; refine(V, C, b, values, delta, f) is refine_tetrahedra or refine_hexahedra.
template <int Corners, class Refine>
auto refinement_pass(Refine refine) {
  return [refine](MatrixXd V, MatrixXi C, const Flags& boundary, Eigen::VectorXd values,
                  double delta, const std::optional<ImplicitFunction>& f) {
    std::vector<char> b = refinement_input(V, C, boundary, Corners);
    RefinementReport r;
    {
      py::gil_scoped_release release;
      r = refine(V, C, b, values, delta, f ? *f : ImplicitFunction{});
    }
    return refined_mesh(std::move(V), std::move(C), b,
                        py::make_tuple(std::move(values), refinement_dict(r)));
  };
}

// Seed 003's adaptive loop of either element kind, the nodal field a Python function of the
// current mesh; adapt(V, C, b, values, delta, iterations, f) is adapt_tetrahedra or
// adapt_hexahedra.
template <int Corners, class Adapt>
auto adaptive_loop(Adapt adapt) {
  return [adapt](MatrixXd V, MatrixXi C, const Flags& boundary, const py::function& field,
                 double delta, int iterations, const std::optional<ImplicitFunction>& f) {
    std::vector<char> b = refinement_input(V, C, boundary, Corners);
    const auto values = [&field](const MatrixXd& Vk, const MatrixXi& Ck) {
      py::gil_scoped_acquire gil;
      return field(Vk, Ck).cast<Eigen::VectorXd>();
    };
    std::vector<RefinementReport> reports;
    {
      py::gil_scoped_release release;
      reports = adapt(V, C, b, values, delta, iterations, f ? *f : ImplicitFunction{});
    }
    py::list passes;
    for (const RefinementReport& r : reports)
      passes.append(refinement_dict(r));
    return refined_mesh(std::move(V), std::move(C), b, passes);
  };
}

void bind_refinement(py::module_& m) {
  m.def("refinement_indicator", &refinement_indicator, py::arg("C"), py::arg("values"),
        release_gil(),
        R"(Seed 003's indicator (digest §7.2): max |C_i - C_j| over each element's nodes over the
range of the nodal quantity values (N,) -> (E,) in [0, 1]. C (E, k) elements of any kind.)");
  m.def("refine_tetrahedra",
        refinement_pass<4>([](auto&&... a) { return refine_tetrahedra(a...); }), py::arg("V"),
        py::arg("C"), py::arg("boundary"), py::arg("values"), py::arg("delta"),
        py::arg("f") = py::none(),
        R"(One pass of seed 003's conforming 2-refinement of tetrahedra (interlin mesh --volume
--adapt): elements with indicator > delta, their vertex neighbours' vertices refined, edges
halved iff both ends are refined (templates of 2, 4, 8 children; no hanging nodes); new nodes
on boundary facet edges projected onto F = 0 when the body f (Implicit) is given.
V (N, 3), C (E, 4) positive tetrahedra, boundary (N,) bool, values (N,) nodal quantity ->
(V (N', 3), C (E', 4) int32, boundary (N',), (values (N',): midpoints the mean of their edge's
ends, report dict: flagged, refined_nodes, split, new_nodes, projected, held (of those, held short of F = 0 so that no element folds))).)");
  m.def("adapt_tetrahedra", adaptive_loop<4>([](auto&&... a) { return adapt_tetrahedra(a...); }),
        py::arg("V"), py::arg("C"), py::arg("boundary"), py::arg("field"), py::arg("delta"),
        py::arg("iterations"), py::arg("f") = py::none(),
        R"(Seed 003's adaptive loop: `iterations` times field(V, C) -> (N,) nodal values (an FE
solution in the seed; any Python function of the current mesh), then refine_tetrahedra with
delta; stops when nothing is flagged -> (V, C, boundary, [report dict per pass]).)");
  m.def("refine_hexahedra", refinement_pass<8>([](auto&&... a) { return refine_hexahedra(a...); }),
        py::arg("V"), py::arg("C"), py::arg("boundary"), py::arg("values"), py::arg("delta"),
        py::arg("f") = py::none(),
        R"(One pass of seed 003's conforming 3-refinement of hexahedra (interlin mesh --volume hex
--adapt): elements with indicator > delta, their vertex neighbours' vertices refined, an edge
trisected iff both ends are refined; the refined nodes widened until every element's refined
edges are none, one, a face's four or all twelve (templates of 5, 13, 27 children; no hanging
nodes); new nodes on boundary facets projected onto F = 0 when the body f (Implicit) is given.
V (N, 3), C (E, 8) positive hexahedra (VTK order), boundary (N,) bool, values (N,) ->
(V (N', 3), C (E', 8) int32, boundary (N',), (values (N',): trilinear in the parents, report
dict: flagged, refined_nodes, widened (added by the closure), split, new_nodes, folded (children
a nearly flat parent's map folds, untangled), still_folded (after), projected, held)).)");
  m.def("adapt_hexahedra", adaptive_loop<8>([](auto&&... a) { return adapt_hexahedra(a...); }),
        py::arg("V"), py::arg("C"), py::arg("boundary"), py::arg("field"), py::arg("delta"),
        py::arg("iterations"), py::arg("f") = py::none(),
        R"(adapt_tetrahedra for hexahedra: `iterations` times field(V, C) -> (N,), then
refine_hexahedra with delta; stops when nothing is flagged, or when a pass leaves children
folded (that pass undone: its report's "undone" is True) -> (V, C, boundary, [report dict per
pass]).)");
}

void bind_volume_meshes(py::module_& m) {
  m.def(
      "mesh_volume",
      [](const ImplicitFunction& f, const std::string& elements, int resolution, double cell,
         const std::optional<MatrixXd>& box, const std::string& rule, double margin,
         int surface_sweeps, int interior_sweeps, int threads, const std::string& boundary,
         const std::string& lattice) {
        VolumeMeshOptions o;
        o.elements = choice<VolumeElements>(
            {{"tet", VolumeElements::tetrahedra}, {"hex", VolumeElements::hexahedra}}, elements,
            "elements");
        std::map<std::string, VolumeBoundary> boundaries;
        for (VolumeBoundary b : kVolumeBoundaries)
          boundaries[boundary_name(b)] = b;
        o.boundary = choice<VolumeBoundary>(boundaries, boundary, "boundary");
        o.lattice =
            choice<Lattice>({{"bcc", Lattice::bcc}, {"kuhn", Lattice::kuhn}}, lattice, "lattice");
        o.rule = choice<ZeroRule>(
            {{"strict", ZeroRule::strict}, {"inclusive", ZeroRule::inclusive}}, rule, "rule");
        if (box)
          o.box = box_from_array(*box);
        o.resolution = resolution, o.cell = cell, o.margin = margin;
        o.surface_sweeps = surface_sweeps, o.interior_sweeps = interior_sweeps, o.threads = threads;
        VolumeMeshInfo info;
        VolumeMesh v;
        {
          py::gil_scoped_release release;
          v = volume_mesh(f, o, &info);
        }
        warn_lost_volume(info, o.elements == VolumeElements::tetrahedra,
                         info.boundary == VolumeBoundary::dual ||
                             info.boundary == VolumeBoundary::pillow);
        return py::make_tuple(std::move(v.V), std::move(v.C), std::move(v.B),
                              boundary_flags(v.boundary), volume_info_dict(info));
      },
      py::arg("f"), py::arg("elements") = "tet", py::arg("resolution") = 64, py::arg("cell") = 0.0,
      py::arg("box") = py::none(), py::arg("rule") = "strict", py::arg("margin") = 0.35,
      py::arg("surface_sweeps") = 0, py::arg("interior_sweeps") = -1, py::arg("threads") = 0,
      py::arg("boundary") = "cut", py::arg("lattice") = "bcc",
      R"(Finite-element mesh of the solid {F > 0} by seed 003's solid-element method (interlin mesh
--volume): background cells inside, a boundary layer projected onto F = 0, smoothing ->
(V (N, 3), C (E, 4) tetrahedra or (E, 8) hexahedra (VTK order) int32, B (K, 3 or 4) boundary
facets, boundary (N,) bool, info dict). elements "tet" or "hex"; boundary (tetrahedra) "cut" (the
lattice's tetrahedra clipped at F = 0; lattice "bcc", the body-centred cubic lattice of
isosurface stuffing, or "kuhn", the grid's cubes in 6 tetrahedra: 0.55-0.8x the elements, poorer
angles) or "projected" (the seed's layer); interior_sweeps -1: 8, none for "bcc" (the corner
functional distorts its lattice); hexahedra "cut" (the
default: "pillow"; where pillows stay folded, "pillow" on the grid offset by half, then a quarter
of a cell (info["offset_grid"]: 0.5 or 0.25), or "dual" where those fold too; info["boundary"] says which and
info["folded_pillows"] how many folded on the grid), "projected", "dual": one per inside grid node, corners
at the cells' points on F = 0 (Zhang & Bajaj 2006: walls one node layer thick kept; "tet" with
"dual" raises ValueError); "pillow": dual
hexahedra inside (made manifold) and one pillow layer out to F = 0 (Mitchell & Tautges 1995),
the boundary nodes on F = 0 but those of pillows still folded after untangling (info["held"]);
folds may remain on walls under a cell thick: check volume_quality(V, C)["inverted"];
rule "strict" (F > eps) or "inclusive" (F >= -eps) for the inside nodes; margin: inside nodes
within margin x cell of F = 0 count as outside (no thin layer elements). info["held"]: layer
nodes held short of F = 0 so that no element folds (max_boundary_f is over the others,
info["on_zero"] counts them); info["clipped"]: grid nodes where the body reaches the box;
projected layer: body_volume (the grid clipped at F = 0), lost_volume (its part no element
covers: walls with no inner cell under the layer), lost_thickness (their mean thickness) and
suggested_cell (the cell that keeps such walls), with a UserWarning above 0.5 % lost.)");
  m.def(
      "volume_quality",
      [](const MatrixXd& V, const MatrixXi& C, int threads) {
        require_shape(V, 3, "V");
        VolumeQuality q;
        {
          py::gil_scoped_release release;
          q = volume_quality(V, C, threads);
        }
        return quality_dict(q);
      },
      py::arg("V"), py::arg("C"), py::arg("threads") = 0,
      R"(Quality of a volume mesh V (N, 3), C (E, 4) or (E, 8) -> dict: elements, inverted, volume,
min/max_dihedral_deg, min/mean_scaled_jacobian, min/mean_radius_ratio (NaN for hexahedra),
outside_10_170 (elements with a dihedral angle outside [10, 170] degrees).)");
  m.def(
      "facet_sag",
      [](const ImplicitFunction& f, const MatrixXd& V, const MatrixXi& B, int threads) {
        require_shape(V, 3, "V");
        if (B.cols() != 3 && B.cols() != 4)
          throw py::value_error("B: expected an (M, 3) or (M, 4) array of node indices");
        if (B.size() > 0 && (B.minCoeff() < 0 || B.maxCoeff() >= V.rows()))
          throw py::value_error("B: node index outside [0, N)");
        FacetSag s;
        {
          py::gil_scoped_release release;
          s = facet_sag(f, V, B, threads);
        }
        py::dict d;
        d["volume"] = s.volume, d["max_distance"] = s.max_distance, d["area"] = s.area;
        d["skipped_area"] = s.skipped_area;
        return d;
      },
      py::arg("f"), py::arg("V"), py::arg("B"), py::arg("threads") = 0,
      R"(How far the boundary facets B (M, 3) triangles or (M, 4) quadrilaterals, counter-clockwise
from outside, of a mesh with nodes V (N, 3) lie from F = 0 -> dict: volume (the integral of the
distance to F = 0 along the facet normals, > 0 where the body reaches beyond the facets: the body's
volume is about the mesh's plus it), max_distance, area (measured) and skipped_area (facets more
than 60 degrees from -grad F or with no zero within their diameter). Triangles by their edge
midpoints, quadrilaterals by 3 x 3 Simpson points.)");
}

} // namespace

void bind_meshing(py::module_& m) {
  bind_volume_meshes(m);
  bind_refinement(m);
  m.def(
      "mesh_implicit",
      [](const ImplicitFunction& f, std::optional<int> resolution, double cell,
         const std::optional<MatrixXd>& box, const Eigen::Vector3i& subboxes, int threads,
         bool project, double tolerance) {
        ImplicitMeshOptions o;
        if (box)
          o.box = box_from_array(*box);
        o.cell = cell, o.subboxes = subboxes.array();
        if (resolution)
          o.resolution = *resolution;
        else if (!(cell > 0))
          o.cell = default_mesh_cell(f, o.box.isEmpty() ? f.box : o.box);
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
      py::arg("f"), py::arg("resolution") = py::none(), py::arg("cell") = 0.0,
      py::arg("box") = py::none(), py::arg("subboxes") = Eigen::Vector3i::Zero(),
      py::arg("threads") = 0, py::arg("project") = true, py::arg("tolerance") = 1e-10,
      R"(Closed mesh of the body {F > 0} (interlin mesh): a grid with `resolution` cubic cells along
the box's longest side (or cells of size `cell`; neither: default_mesh_cell, i.e. 128 cells, or
cells of half the point spacing for a point cloud's fit, of the spacing for a smoothed noisy
scan), marching cubes per sub-box on
`threads` threads (0: all cores), vertices projected onto F = 0 -> (V (N, 3), F (M, 3) int32).
box (2, 3) defaults to f.box; the mesh closes along the box where the body reaches it. Closed,
2-manifold, oriented outward.)");
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
      R"(Seed 003's smoothing: vertices slide over F = 0 onto creases (no descent move takes a face
below 5 degrees) -> (V (N, 3), fit) with fit the sum of squared centroid offsets before the first
and after each sweep.)");
  m.def("triangulate_loop", &triangulate_loop, py::arg("P"),
        "Triangles (P - 2, 3) filling the closed loop P (P, 3): constrained Delaunay in its "
        "best-fit plane.");
}

} // namespace interlin::python
