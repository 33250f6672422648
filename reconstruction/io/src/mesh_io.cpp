#include "interlin/reconstruction/io/mesh_io.h"

#include "mesh_formats.h"

#include "interlin/interflatation/read_input_file.h"
#include "interlin/reconstruction/io/atomic_file.h"

// OpenMesh: MeshIO.hh must come before the mesh kernel header.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace interlin {

namespace {

struct DoubleTraits : OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
};
using OMMesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;

// OpenMesh's writers only ask an exporter for points, face vertex lists and counts (plus the
// kernel's property list, for custom PLY properties: an empty mesh has none). Serving them
// straight from V and F skips building the half-edge structure, which costs about as much as
// writing the file and would reject non-manifold faces. Everything optional (normals, colours,
// texture coordinates, status) is absent.
class SoupExporter final : public OpenMesh::IO::BaseExporter {
public:
  SoupExporter(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) : V_(V), F_(F) {}

  OpenMesh::Vec3f point(OpenMesh::VertexHandle v) const override {
    const auto i = v.idx();
    return {float(V_(i, 0)), float(V_(i, 1)), float(V_(i, 2))};
  }
  OpenMesh::Vec3d pointd(OpenMesh::VertexHandle v) const override {
    const auto i = v.idx();
    return {V_(i, 0), V_(i, 1), V_(i, 2)};
  }
  bool is_point_double() const override { return true; }
  OpenMesh::Vec3f normal(OpenMesh::VertexHandle) const override { return {0.f, 0.f, 0.f}; }
  OpenMesh::Vec3d normald(OpenMesh::VertexHandle) const override { return {0.0, 0.0, 0.0}; }
  bool is_normal_double() const override { return true; }
  OpenMesh::Vec3uc color(OpenMesh::VertexHandle) const override { return {0, 0, 0}; }
  OpenMesh::Vec4uc colorA(OpenMesh::VertexHandle) const override { return {0, 0, 0, 0}; }
  OpenMesh::Vec3ui colori(OpenMesh::VertexHandle) const override { return {0u, 0u, 0u}; }
  OpenMesh::Vec4ui colorAi(OpenMesh::VertexHandle) const override { return {0u, 0u, 0u, 0u}; }
  OpenMesh::Vec3f colorf(OpenMesh::VertexHandle) const override { return {0.f, 0.f, 0.f}; }
  OpenMesh::Vec4f colorAf(OpenMesh::VertexHandle) const override { return {0.f, 0.f, 0.f, 0.f}; }
  OpenMesh::Vec2f texcoord(OpenMesh::VertexHandle) const override { return {0.f, 0.f}; }
  OpenMesh::Vec2f texcoord(OpenMesh::HalfedgeHandle) const override { return {0.f, 0.f}; }
  OpenMesh::Attributes::StatusInfo status(OpenMesh::VertexHandle) const override { return {}; }

  unsigned int get_vhandles(OpenMesh::FaceHandle f,
                            std::vector<OpenMesh::VertexHandle>& vh) const override {
    vh.clear();
    for (int j = 0; j < 3; ++j)
      vh.emplace_back(F_(f.idx(), j));
    return 3;
  }
  OpenMesh::HalfedgeHandle getHeh(OpenMesh::FaceHandle, OpenMesh::VertexHandle) const override {
    return OpenMesh::HalfedgeHandle();
  }
  unsigned int get_face_texcoords(std::vector<OpenMesh::Vec2f>& t) const override {
    t.clear();
    return 0;
  }
  OpenMesh::Vec3f normal(OpenMesh::FaceHandle) const override { return {0.f, 0.f, 0.f}; }
  OpenMesh::Vec3d normald(OpenMesh::FaceHandle) const override { return {0.0, 0.0, 0.0}; }
  OpenMesh::Vec3uc color(OpenMesh::FaceHandle) const override { return {0, 0, 0}; }
  OpenMesh::Vec4uc colorA(OpenMesh::FaceHandle) const override { return {0, 0, 0, 0}; }
  OpenMesh::Vec3ui colori(OpenMesh::FaceHandle) const override { return {0u, 0u, 0u}; }
  OpenMesh::Vec4ui colorAi(OpenMesh::FaceHandle) const override { return {0u, 0u, 0u, 0u}; }
  OpenMesh::Vec3f colorf(OpenMesh::FaceHandle) const override { return {0.f, 0.f, 0.f}; }
  OpenMesh::Vec4f colorAf(OpenMesh::FaceHandle) const override { return {0.f, 0.f, 0.f, 0.f}; }
  OpenMesh::Attributes::StatusInfo status(OpenMesh::FaceHandle) const override { return {}; }

  OpenMesh::Vec3uc color(OpenMesh::EdgeHandle) const override { return {0, 0, 0}; }
  OpenMesh::Vec4uc colorA(OpenMesh::EdgeHandle) const override { return {0, 0, 0, 0}; }
  OpenMesh::Vec3ui colori(OpenMesh::EdgeHandle) const override { return {0u, 0u, 0u}; }
  OpenMesh::Vec4ui colorAi(OpenMesh::EdgeHandle) const override { return {0u, 0u, 0u, 0u}; }
  OpenMesh::Vec3f colorf(OpenMesh::EdgeHandle) const override { return {0.f, 0.f, 0.f}; }
  OpenMesh::Vec4f colorAf(OpenMesh::EdgeHandle) const override { return {0.f, 0.f, 0.f, 0.f}; }
  OpenMesh::Attributes::StatusInfo status(OpenMesh::EdgeHandle) const override { return {}; }

  int get_halfedge_id(OpenMesh::VertexHandle) override { return -1; }
  int get_halfedge_id(OpenMesh::FaceHandle) override { return -1; }
  int get_next_halfedge_id(OpenMesh::HalfedgeHandle) override { return -1; }
  int get_to_vertex_id(OpenMesh::HalfedgeHandle) override { return -1; }
  int get_face_id(OpenMesh::HalfedgeHandle) override { return -1; }
  OpenMesh::Attributes::StatusInfo status(OpenMesh::HalfedgeHandle) const override { return {}; }

  const OpenMesh::BaseKernel* kernel() override { return &empty_; }
  size_t n_vertices() const override { return size_t(V_.rows()); }
  size_t n_faces() const override { return size_t(F_.rows()); }
  size_t n_edges() const override { return 0; }
  bool is_triangle_mesh() const override { return true; }

private:
  const Eigen::MatrixXd& V_;
  const Eigen::MatrixXi& F_;
  OMMesh empty_;
};

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

// Silences OpenMesh's log and error streams while alive ("[STLWriter] : write binary file");
// failures are reported by our exceptions instead.
class QuietLog {
public:
  QuietLog() : log_(::omlog().is_enabled()), err_(::omerr().is_enabled()) {
    ::omlog().disable();
    ::omerr().disable();
  }
  ~QuietLog() {
    if (log_)
      ::omlog().enable();
    if (err_)
      ::omerr().enable();
  }
  QuietLog(const QuietLog&) = delete;
  QuietLog& operator=(const QuietLog&) = delete;

private:
  bool log_, err_;
};

} // namespace

void write_mesh(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                MeshPrecision precision) {
  const std::string ext = lower_extension(path);
  if (ext != ".stl" && ext != ".ply" && ext != ".obj" && ext != ".off")
    throw std::invalid_argument("write_mesh: unknown mesh extension '" + ext + "' in " + path +
                                " (supported: .stl, .obj, .ply, .off)");
  if (V.cols() != 3 || F.cols() != 3)
    throw std::invalid_argument("write_mesh: V and F must have 3 columns");
  if (F.size() > 0 && (F.minCoeff() < 0 || F.maxCoeff() >= V.rows()))
    throw std::invalid_argument("write_mesh: face index outside [0, #V)");
  const bool in_double = precision == MeshPrecision::float64;
  if (ext == ".ply" || ext == ".obj") { // OpenMesh would round to float: our own writers
    write_file_atomically(path, [&](std::ostream& out) {
      ext == ".ply" ? detail::write_ply(out, V, F, in_double)
                    : detail::write_obj(out, V, F, in_double);
    });
    return;
  }
  OpenMesh::IO::Options opt;
  if (ext == ".stl")
    opt += OpenMesh::IO::Options::Binary;
  AtomicPath target(path); // same extension: OpenMesh picks the writer from it
  SoupExporter exporter(V, F);
  bool ok = false;
  {
    QuietLog quiet;
    // 17 significant digits in OFF (more than the 9 a float needs).
    ok = OpenMesh::IO::IOManager().write(target.temp(), exporter, opt, 17);
  }
  if (!ok || !std::filesystem::exists(target.temp()))
    throw std::runtime_error("cannot write " + path + ": the OpenMesh writer failed");
  target.commit();
}

void parse_mesh(std::string_view content, const std::string& path, Eigen::MatrixXd& V,
                Eigen::MatrixXi& F) {
  const std::string ext = lower_extension(path);
  if (ext == ".ply")
    detail::parse_ply(content, path, V, F);
  else if (ext == ".obj")
    detail::parse_obj(content, path, V, F);
  else
    throw std::invalid_argument("parse_mesh: " + path +
                                ": only .ply and .obj are read from memory");
}

void read_mesh(const std::string& path, Eigen::MatrixXd& V, Eigen::MatrixXi& F) {
  if (const std::string ext = lower_extension(path); ext == ".ply" || ext == ".obj")
    return parse_mesh(read_input_file(path), path, V, F);
  if (!std::filesystem::is_regular_file(path))
    throw std::runtime_error("cannot read " + path + ": no such file");
  OMMesh mesh;
  OpenMesh::IO::Options opt; // readers detect binary/ASCII themselves
  bool ok = false;
  {
    QuietLog quiet;
    ok = OpenMesh::IO::read_mesh(mesh, path, opt);
  }
  if (!ok)
    throw std::runtime_error("cannot read " + path + ": not a mesh file OpenMesh can read");
  V.resize(Eigen::Index(mesh.n_vertices()), 3);
  for (const auto vh : mesh.vertices()) {
    const auto& p = mesh.point(vh);
    V.row(vh.idx()) << p[0], p[1], p[2];
  }
  F.resize(Eigen::Index(mesh.n_faces()), 3);
  for (const auto fh : mesh.faces()) {
    int j = 0;
    for (const auto vh : mesh.fv_range(fh)) {
      if (j == 3)
        throw std::runtime_error("cannot read " + path + ": a face is not a triangle");
      F(fh.idx(), j++) = vh.idx();
    }
  }
}

} // namespace interlin
