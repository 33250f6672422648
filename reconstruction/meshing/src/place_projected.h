#pragma once
// Refinement's new boundary nodes moved onto their projections on F = 0 without folding an element
// (seed 003, §7.2, for tetrahedra and hexahedra).

#include <Eigen/Core>

#include <cmath>
#include <vector>

namespace interlin::detail {

// Moves the new nodes n0 + project[r] to their projections P.row(r) where `moved`, one at a time:
// the largest fraction 1, 1/2, ..., 1/1024 of the way that keeps every element at the node that
// is valid (valid(V, e)) valid, else none. Valid elements stay valid after each move (the others'
// positions are the current ones), so no element is inverted by the moves; a small element at a
// curved boundary (a cut grid's sliver, a thin pillow) can make the full step fold it.
// Returns the nodes held short of F = 0.
template <class Valid>
std::vector<long> place_projected(const Eigen::MatrixXi& C, long n0,
                                  const std::vector<long>& project, const Eigen::MatrixXd& P,
                                  const std::vector<char>& moved, Eigen::MatrixXd& V,
                                  const Valid& valid) {
  constexpr int kHalvings = 10;
  std::vector<std::vector<long>> star(project.size());
  std::vector<long> row(size_t(V.rows() - n0), -1);
  for (size_t r = 0; r < project.size(); ++r)
    row[size_t(project[r])] = long(r);
  for (long e = 0; e < C.rows(); ++e)
    for (long j = 0; j < C.cols(); ++j)
      if (C(e, j) >= n0 && row[size_t(C(e, j) - n0)] >= 0)
        star[size_t(row[size_t(C(e, j) - n0)])].push_back(e);
  std::vector<long> held;
  for (size_t r = 0; r < project.size(); ++r) {
    if (!moved[r])
      continue;
    const long n = n0 + project[r];
    const Eigen::RowVector3d start = V.row(n), step = P.row(long(r)) - start;
    std::vector<long> kept; // the elements to keep valid: an inverted one has no fold to avoid
    for (long e : star[r])
      if (valid(V, e))
        kept.push_back(e);
    double s = 1;
    for (int k = 0; k <= kHalvings; ++k, s *= 0.5) {
      V.row(n) = start + s * step;
      bool ok = true;
      for (long e : kept)
        ok = ok && valid(V, e);
      if (ok)
        break;
    }
    if (s < 1) {
      held.push_back(n);
      if (s < std::ldexp(1.0, -kHalvings))
        V.row(n) = start;
    }
  }
  return held;
}

} // namespace interlin::detail
