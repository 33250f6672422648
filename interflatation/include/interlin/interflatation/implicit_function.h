#pragma once
// An implicit body F(x,y,z): F > 0 inside, F = 0 on the surface, F < 0 outside (the R-function
// convention of seeds 000/002/003). The interface between whatever defines F (R-function models,
// interflatation operators, point-cloud fits) and whatever consumes it (meshing, evaluation).
// Evaluation is by batch, so that producers can run vectorisable loops without a virtual or
// std::function call per point.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>

namespace interlin {

using Points3 = Eigen::Matrix<double, Eigen::Dynamic, 3>;

struct ImplicitFunction {
  // F at every row of P (#P by 3) into F (#P). Must be safe to call concurrently from several
  // threads on disjoint outputs.
  std::function<void(const Eigen::Ref<const Points3>& P, Eigen::Ref<Eigen::VectorXd> F)> value;
  // F and its gradient (#P by 3) at every row of P; may be empty when no gradient is available.
  std::function<void(const Eigen::Ref<const Points3>& P, Eigen::Ref<Eigen::VectorXd> F,
                     Eigen::Ref<Points3> G)>
      gradient;
  // A box that contains the body (the model's declared bounding box); empty when unknown.
  Eigen::AlignedBox3d box;
  // Optional: +1 (-1) when F is certainly > 0 (< 0) at every point of the closed box B, 0 when it
  // cannot tell (a bound, e.g. interval arithmetic: 0 is always a correct answer). Meshers skip
  // boxes with a sign (implicit_mesh's narrow band). Empty: unknown everywhere.
  std::function<int(const Eigen::AlignedBox3d& B)> sign_on_box;
  // The finest detail F resolves (a point cloud fit's point spacing, twice it for a smoothed
  // noisy scan), which sets the mesh cell that shows it (default_mesh_cell); 0 when unknown.
  double sample_spacing = 0;
};

} // namespace interlin
