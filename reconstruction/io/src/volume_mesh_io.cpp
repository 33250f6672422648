// Volume-mesh writers: VTK XML (.vtu), Gmsh MSH 4.1 (.msh), Abaqus / CalculiX (.inp).
#include "interlin/reconstruction/io/volume_mesh_io.h"

#include "interlin/reconstruction/io/atomic_file.h"

#include "cad_text.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace interlin {

namespace {

std::string extension_lower(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

// Shortest text that reads back to the same double (17 significant digits at most).
std::string real(double x) {
  return detail::cad_real(x);
}

// CalculiX reads at most 20 characters per number of a data line: where the shortest exact text
// is longer (up to 17 digits with a sign and an exponent), as many significant digits as fit (at
// least 14 with an exponent of 2 digits: a relative change below 1e-13 of numbers that are tiny or
// huge next to 1).
std::string inp_real(double x) {
  constexpr size_t kField = 20;
  std::string s = real(x);
  for (int digits = 16; s.size() > kField && digits >= 12; --digits) {
    std::array<char, 32> buf{};
    std::snprintf(buf.data(), buf.size(), "%.*G", digits, x);
    s = buf.data();
  }
  return s;
}

void check(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C, const Eigen::MatrixXi& B,
           const VolumeMeshFields& fields) {
  if (V.cols() != 3)
    throw std::invalid_argument("write_volume_mesh: V must be #V by 3");
  if (C.cols() != 4 && C.cols() != 8)
    throw std::invalid_argument("write_volume_mesh: C must be #C by 4 (tetrahedra) or 8");
  if (B.size() > 0 && B.cols() != (C.cols() == 4 ? 3 : 4))
    throw std::invalid_argument("write_volume_mesh: B must be #B by 3 for tetrahedra, 4 for "
                                "hexahedra");
  for (const Eigen::MatrixXi* M : {&C, &B})
    if (M->size() > 0 && (M->minCoeff() < 0 || M->maxCoeff() >= V.rows()))
      throw std::invalid_argument("write_volume_mesh: node index outside [0, #V)");
  for (const auto& [name, values] : fields.node)
    if (values.size() != V.rows())
      throw std::invalid_argument("write_volume_mesh: node field '" + name + "' needs #V values");
  for (const auto& [name, values] : fields.element)
    if (values.size() != C.rows())
      throw std::invalid_argument("write_volume_mesh: element field '" + name +
                                  "' needs #C values");
}

// The first n entries of a face key in increasing order (n <= 4; insertion sort).
std::array<int, 4> face_key(std::array<int, 4> key, int n) {
  for (int i = 1; i < n; ++i)
    for (int j = i; j > 0 && key[size_t(j - 1)] > key[size_t(j)]; --j)
      std::swap(key[size_t(j - 1)], key[size_t(j)]);
  return key;
}

std::vector<char> boundary_flags(long nv, const Eigen::MatrixXi& B) {
  std::vector<char> on(size_t(nv), 0);
  for (long i = 0; i < B.size(); ++i)
    on[size_t(B.data()[i])] = 1;
  return on;
}

// ---------------------------------------------------------------------------------- .vtu --

// Appended raw data: each array is a UInt64 byte count followed by the bytes (little-endian).
class Appended {
public:
  // Registers an array and returns its offset in the appended block.
  template <class T>
  std::uint64_t add(const std::vector<T>& values) {
    const std::uint64_t offset = bytes_.size();
    const std::uint64_t n = values.size() * sizeof(T);
    append(&n, sizeof n);
    append(values.data(), size_t(n));
    return offset;
  }
  const std::string& bytes() const { return bytes_; }

private:
  void append(const void* p, size_t n) { bytes_.append(static_cast<const char*>(p), n); }
  std::string bytes_;
};

bool little_endian() {
  const std::uint16_t one = 1;
  return *reinterpret_cast<const unsigned char*>(&one) == 1;
}

void write_vtu(std::ostream& out, const Eigen::MatrixXd& V, const Eigen::MatrixXi& C,
               const Eigen::MatrixXi& B, const VolumeMeshFields& fields) {
  if (!little_endian())
    throw std::runtime_error("write_volume_mesh: .vtu output assumes a little-endian machine");
  Appended data;
  std::vector<double> points(size_t(V.size()));
  for (long i = 0; i < V.rows(); ++i)
    for (int a = 0; a < 3; ++a)
      points[size_t(3 * i + a)] = V(i, a);
  const std::uint64_t p_off = data.add(points);
  std::vector<std::int64_t> conn(size_t(C.size())), offsets(size_t(C.rows()));
  for (long e = 0; e < C.rows(); ++e) {
    for (long j = 0; j < C.cols(); ++j)
      conn[size_t(e * C.cols() + j)] = C(e, j);
    offsets[size_t(e)] = (e + 1) * C.cols();
  }
  const std::vector<std::uint8_t> types(size_t(C.rows()), C.cols() == 4 ? 10 : 12);
  const std::uint64_t c_off = data.add(conn), o_off = data.add(offsets), t_off = data.add(types);
  const std::vector<char> on = boundary_flags(V.rows(), B);
  const std::uint64_t b_off = data.add(std::vector<std::uint8_t>(on.begin(), on.end()));
  std::vector<std::pair<std::string, std::uint64_t>> node_fields, element_fields;
  for (const auto& [name, v] : fields.node)
    node_fields.emplace_back(name, data.add(std::vector<double>(v.data(), v.data() + v.size())));
  for (const auto& [name, v] : fields.element)
    element_fields.emplace_back(name, data.add(std::vector<double>(v.data(), v.data() + v.size())));
  auto array = [&](const char* type, const std::string& name, int comps, std::uint64_t off) {
    out << "        <DataArray type=\"" << type << "\" Name=\"" << name
        << "\" NumberOfComponents=\"" << comps << "\" format=\"appended\" offset=\"" << off
        << "\"/>\n";
  };
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n"
      << "  <UnstructuredGrid>\n"
      << "    <Piece NumberOfPoints=\"" << V.rows() << "\" NumberOfCells=\"" << C.rows() << "\">\n"
      << "      <PointData>\n";
  array("UInt8", "boundary", 1, b_off);
  for (const auto& [name, off] : node_fields)
    array("Float64", name, 1, off);
  out << "      </PointData>\n      <CellData>\n";
  for (const auto& [name, off] : element_fields)
    array("Float64", name, 1, off);
  out << "      </CellData>\n      <Points>\n";
  array("Float64", "Points", 3, p_off);
  out << "      </Points>\n      <Cells>\n";
  array("Int64", "connectivity", 1, c_off);
  array("Int64", "offsets", 1, o_off);
  array("UInt8", "types", 1, t_off);
  out << "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n"
      << "  <AppendedData encoding=\"raw\">\n   _";
  out.write(data.bytes().data(), std::streamsize(data.bytes().size()));
  out << "\n  </AppendedData>\n</VTKFile>\n";
}

// ---------------------------------------------------------------------------------- .msh --

void write_msh(std::ostream& out, const Eigen::MatrixXd& V, const Eigen::MatrixXi& C,
               const Eigen::MatrixXi& B) {
  const bool tets = C.cols() == 4;
  const std::vector<char> on = boundary_flags(V.rows(), B);
  const long nb = std::count(on.begin(), on.end(), char(1)), ni = V.rows() - nb;
  Eigen::RowVector3d lo = Eigen::RowVector3d::Zero(), hi = lo;
  if (V.rows() > 0)
    lo = V.colwise().minCoeff(), hi = V.colwise().maxCoeff();
  const std::string bbox = real(lo(0)) + " " + real(lo(1)) + " " + real(lo(2)) + " " + real(hi(0)) +
                           " " + real(hi(1)) + " " + real(hi(2));
  out << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
      << "$PhysicalNames\n2\n2 1 \"boundary\"\n3 2 \"solid\"\n$EndPhysicalNames\n"
      << "$Entities\n0 0 1 1\n"
      << "1 " << bbox << " 1 1 0\n"   // surface 1: physical 1, no bounding curves
      << "1 " << bbox << " 1 2 1 1\n" // volume 1: physical 2, bounded by surface 1
      << "$EndEntities\n";
  // Nodes: the boundary ones on the surface, the others on the volume (tags = index + 1).
  out << "$Nodes\n2 " << V.rows() << " " << (V.rows() ? 1 : 0) << " " << V.rows() << "\n";
  for (const int dim : {2, 3}) {
    const char want = dim == 2;
    out << dim << " 1 0 " << (dim == 2 ? nb : ni) << "\n";
    for (long i = 0; i < V.rows(); ++i)
      if (on[size_t(i)] == want)
        out << i + 1 << "\n";
    for (long i = 0; i < V.rows(); ++i)
      if (on[size_t(i)] == want)
        out << real(V(i, 0)) << " " << real(V(i, 1)) << " " << real(V(i, 2)) << "\n";
  }
  out << "$EndNodes\n";
  const long total = B.rows() + C.rows();
  out << "$Elements\n2 " << total << " " << (total ? 1 : 0) << " " << total << "\n";
  out << "2 1 " << (tets ? 2 : 3) << " " << B.rows() << "\n";
  for (long f = 0; f < B.rows(); ++f) {
    out << f + 1;
    for (long j = 0; j < B.cols(); ++j)
      out << " " << B(f, j) + 1;
    out << "\n";
  }
  out << "3 1 " << (tets ? 4 : 5) << " " << C.rows() << "\n";
  for (long e = 0; e < C.rows(); ++e) {
    out << B.rows() + e + 1;
    for (long j = 0; j < C.cols(); ++j)
      out << " " << C(e, j) + 1;
    out << "\n";
  }
  out << "$EndElements\n";
}

// ---------------------------------------------------------------------------------- .inp --

// Abaqus element faces (local node positions, 0-based) in the order S1, S2, ...
constexpr int kC3D4Face[4][3] = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
constexpr int kC3D8Face[6][4] = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1},
                                 {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0}};

void write_inp(std::ostream& out, const Eigen::MatrixXd& V, const Eigen::MatrixXi& C,
               const Eigen::MatrixXi& B) {
  const bool tets = C.cols() == 4;
  out << "*HEADING\ninterlin volume mesh: " << C.rows() << (tets ? " C3D4" : " C3D8")
      << " elements, " << V.rows() << " nodes\n*NODE, NSET=NALL\n";
  for (long i = 0; i < V.rows(); ++i)
    out << i + 1 << ", " << inp_real(V(i, 0)) << ", " << inp_real(V(i, 1)) << ", "
        << inp_real(V(i, 2)) << "\n";
  out << "*ELEMENT, TYPE=" << (tets ? "C3D4" : "C3D8") << ", ELSET=SOLID\n";
  for (long e = 0; e < C.rows(); ++e) {
    out << e + 1;
    for (long j = 0; j < C.cols(); ++j)
      out << ", " << C(e, j) + 1;
    out << "\n";
  }
  if (B.rows() == 0)
    return;
  // Boundary nodes, 16 per line (the format's limit).
  const std::vector<char> on = boundary_flags(V.rows(), B);
  out << "*NSET, NSET=BOUNDARY\n";
  long k = 0;
  for (long i = 0; i < V.rows(); ++i)
    if (on[size_t(i)])
      out << (k == 0 ? "" : k % 16 == 0 ? "\n" : ", ") << i + 1, ++k;
  out << "\n";
  // Boundary facets as element faces: match each element face against the facets.
  std::map<std::array<int, 4>, long> facet;
  for (long f = 0; f < B.rows(); ++f) {
    std::array<int, 4> key = {-1, -1, -1, -1};
    for (long j = 0; j < B.cols(); ++j)
      key[size_t(j)] = B(f, j);
    facet[face_key(key, int(B.cols()))] = f;
  }
  out << "*SURFACE, NAME=BOUNDARY, TYPE=ELEMENT\n";
  long found = 0;
  const int faces = tets ? 4 : 6, per = tets ? 3 : 4;
  for (long e = 0; e < C.rows(); ++e)
    for (int s = 0; s < faces; ++s) {
      std::array<int, 4> key = {-1, -1, -1, -1};
      for (int j = 0; j < per; ++j)
        key[size_t(j)] = C(e, tets ? kC3D4Face[s][j] : kC3D8Face[s][j]);
      if (facet.count(face_key(key, per))) {
        out << e + 1 << ", S" << s + 1 << "\n";
        ++found;
      }
    }
  if (found != B.rows())
    throw std::invalid_argument("write_volume_mesh: " + std::to_string(B.rows() - found) +
                                " boundary facets are not element faces");
}

} // namespace

bool is_volume_mesh_path(const std::string& path) {
  const std::string ext = extension_lower(path);
  return ext == ".vtu" || ext == ".msh" || ext == ".inp";
}

void write_volume_mesh(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& C,
                       const Eigen::MatrixXi& B, const VolumeMeshFields& fields) {
  const std::string ext = extension_lower(path);
  if (!is_volume_mesh_path(path))
    throw std::invalid_argument("write_volume_mesh: unknown extension '" + ext + "' in " + path +
                                " (supported: .vtu, .msh, .inp)");
  check(V, C, B, fields);
  write_file_atomically(path, [&](std::ostream& out) {
    if (ext == ".vtu")
      write_vtu(out, V, C, B, fields);
    else if (ext == ".msh")
      write_msh(out, V, C, B);
    else
      write_inp(out, V, C, B);
  });
}

} // namespace interlin
