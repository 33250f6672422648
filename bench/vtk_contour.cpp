#include "vtk_contour.h"

#include <vtkDoubleArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkImageData.h>
#include <vtkMarchingCubes.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataAlgorithm.h>
#include <vtkSMPTools.h>
#include <vtkSmartPointer.h>

namespace interlin::bench {

struct VtkContour::Impl {
  vtkSmartPointer<vtkImageData> image;
  vtkSmartPointer<vtkPolyDataAlgorithm> filter;
};

VtkContour::VtkContour(const double* values, const int dims[3], const double origin[3],
                       const double spacing[3], bool flying_edges)
    : impl_(new Impl) {
  impl_->image = vtkSmartPointer<vtkImageData>::New();
  impl_->image->SetDimensions(dims[0], dims[1], dims[2]);
  impl_->image->SetOrigin(origin[0], origin[1], origin[2]);
  impl_->image->SetSpacing(spacing[0], spacing[1], spacing[2]);
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  // save = 1: VTK uses the caller's memory and never frees it.
  array->SetArray(const_cast<double*>(values), vtkIdType(dims[0]) * dims[1] * dims[2], 1);
  array->SetName("F");
  impl_->image->GetPointData()->SetScalars(array);
  if (flying_edges) {
    auto fe = vtkSmartPointer<vtkFlyingEdges3D>::New();
    fe->SetValue(0, 0.0);
    fe->ComputeNormalsOff();
    fe->ComputeGradientsOff();
    fe->ComputeScalarsOff();
    fe->InterpolateAttributesOff();
    impl_->filter = fe;
  } else {
    auto mc = vtkSmartPointer<vtkMarchingCubes>::New();
    mc->SetValue(0, 0.0);
    mc->ComputeNormalsOff();
    mc->ComputeGradientsOff();
    mc->ComputeScalarsOff();
    impl_->filter = mc;
  }
  impl_->filter->SetInputData(impl_->image);
}

VtkContour::~VtkContour() = default;

void VtkContour::run(long& points, long& triangles) {
  impl_->filter->Modified();
  impl_->filter->Update();
  points = long(impl_->filter->GetOutput()->GetNumberOfPoints());
  triangles = long(impl_->filter->GetOutput()->GetNumberOfCells());
}

bool VtkContour::use_threads(int threads) {
  if (!vtkSMPTools::SetBackend(threads == 1 ? "Sequential" : "STDThread"))
    return false;
  vtkSMPTools::Initialize(threads);
  return true;
}

} // namespace interlin::bench
