#pragma once
// VTK baselines of the implicit-surface extraction benchmarks: the same sampled grid contoured at
// F = 0 by vtkFlyingEdges3D or vtkMarchingCubes. Only vtk_contour.cpp sees VTK's headers (VTK 9.1
// headers are C++17 and do not compile as C++20), so this interface is plain C++.

#include <memory>

namespace interlin::bench {

class VtkContour {
public:
  // Wraps `values` (x fastest, dims[0] * dims[1] * dims[2], not copied: must outlive this) as
  // vtkImageData with the given origin and spacing; normals, gradients and scalars off.
  VtkContour(const double* values, const int dims[3], const double origin[3],
             const double spacing[3], bool flying_edges);
  ~VtkContour();
  // Runs the filter once (marked modified first); returns the output's points and triangles.
  void run(long& points, long& triangles);
  // VTK's SMP backend for the following runs: "Sequential" for 1 thread, "STDThread" with
  // `threads` workers otherwise. False when the backend is not available.
  static bool use_threads(int threads);

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace interlin::bench
