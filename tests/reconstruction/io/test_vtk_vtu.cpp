// Independent check of the .vtu writer: VTK's own XML reader (vtkXMLUnstructuredGridReader, what
// ParaView uses) reads our files back with the same points (exact doubles), cells of type
// VTK_TETRA / VTK_HEXAHEDRON with our node order, and the point and cell data. Built only when
// VTK is found (a C++17 target: VTK 9.1's headers).
#include "interlin/reconstruction/io/volume_mesh_io.h"
#include "interlin/reconstruction/meshing/volume_mesh.h"

#include "support/test_implicits.h"
#include "support/test_support.h"

#include <catch2/catch.hpp>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

using namespace interlin;

TEST_CASE("VTK reads our .vtu volume meshes back", "[vtk][volume]") {
  test::TempDir tmp("vtk-vtu");
  for (const VolumeElements e : {VolumeElements::tetrahedra, VolumeElements::hexahedra}) {
    VolumeMeshOptions o;
    o.elements = e;
    o.resolution = 10;
    const VolumeMesh m = volume_mesh(test::body11_function(), o);
    const std::string path = tmp.file("mesh.vtu");
    VolumeMeshFields fields;
    Eigen::VectorXd id(m.C.rows()), x(m.V.rows());
    for (long k = 0; k < m.C.rows(); ++k)
      id(k) = double(k);
    x = m.V.col(0);
    fields.element = {{"element_id", id}};
    fields.node = {{"x", x}};
    write_volume_mesh(path, m.V, m.C, m.B, fields);
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    vtkUnstructuredGrid* g = reader->GetOutput();
    INFO((e == VolumeElements::tetrahedra ? "tetrahedra" : "hexahedra"));
    REQUIRE(g->GetNumberOfPoints() == m.V.rows());
    REQUIRE(g->GetNumberOfCells() == m.C.rows());
    bool same = true;
    for (long i = 0; i < m.V.rows(); ++i) {
      double p[3];
      g->GetPoint(i, p);
      same = same && p[0] == m.V(i, 0) && p[1] == m.V(i, 1) && p[2] == m.V(i, 2);
    }
    CHECK(same);
    bool cells = true;
    vtkNew<vtkIdList> ids;
    for (long c = 0; c < m.C.rows(); ++c) {
      cells = cells && g->GetCellType(c) == (m.C.cols() == 4 ? 10 : 12);
      g->GetCellPoints(c, ids);
      for (long j = 0; j < m.C.cols(); ++j)
        cells = cells && ids->GetId(j) == m.C(c, j);
    }
    CHECK(cells);
    vtkDataArray* b = g->GetPointData()->GetArray("boundary");
    vtkDataArray* xs = g->GetPointData()->GetArray("x");
    vtkDataArray* ids_out = g->GetCellData()->GetArray("element_id");
    REQUIRE(b);
    REQUIRE(xs);
    REQUIRE(ids_out);
    bool data = true;
    for (long i = 0; i < m.V.rows(); ++i)
      data = data && b->GetTuple1(i) == double(m.boundary[size_t(i)]) && xs->GetTuple1(i) == x(i);
    for (long c = 0; c < m.C.rows(); ++c)
      data = data && ids_out->GetTuple1(c) == double(c);
    CHECK(data);
  }
}
