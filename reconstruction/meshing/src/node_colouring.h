#pragma once
// Internal: greedy colouring of mesh nodes so that the nodes of one colour share no element (no
// row of C); each class can then be updated in parallel as one Gauss-Seidel step.

#include <Eigen/Core>
#include <algorithm>
#include <vector>

namespace interlin::detail {

// The elements at each node, compressed: elements of node v are at[start[v] .. start[v + 1]).
struct NodeElements {
  std::vector<long> start;
  std::vector<int> at;
  NodeElements(const Eigen::MatrixXi& C, long nv) : start(size_t(nv + 1), 0) {
    for (long e = 0; e < C.rows(); ++e)
      for (long a = 0; a < C.cols(); ++a)
        ++start[size_t(C(e, a)) + 1];
    for (long v = 0; v < nv; ++v)
      start[size_t(v + 1)] += start[size_t(v)];
    at.resize(size_t(start.back()));
    std::vector<long> fill(start.begin(), start.end() - 1);
    for (long e = 0; e < C.rows(); ++e)
      for (long a = 0; a < C.cols(); ++a)
        at[size_t(fill[size_t(C(e, a))]++)] = int(e);
  }
};

// Inputs:  C #C by k elements (any k), use #V flags (nodes to colour; others are skipped),
//          ne the elements at each node of C.
// Output:  the colour classes, each in increasing node order; deterministic.
inline std::vector<std::vector<int>>
colour_nodes(const Eigen::MatrixXi& C, const std::vector<char>& use, const NodeElements& ne) {
  const long nv = long(use.size());
  const std::vector<long>& start = ne.start;
  const std::vector<int>& at = ne.at;
  std::vector<int> colour(size_t(nv), -1);
  std::vector<std::vector<int>> classes;
  std::vector<char> taken;
  for (long v = 0; v < nv; ++v) {
    if (!use[size_t(v)])
      continue;
    taken.assign(classes.size() + 1, 0);
    for (long k = start[size_t(v)]; k < start[size_t(v + 1)]; ++k)
      for (long a = 0; a < C.cols(); ++a) {
        const int w = C(at[size_t(k)], a);
        if (colour[size_t(w)] >= 0)
          taken[size_t(colour[size_t(w)])] = 1;
      }
    const int c = int(std::find(taken.begin(), taken.end(), char(0)) - taken.begin());
    colour[size_t(v)] = c;
    if (c == int(classes.size()))
      classes.emplace_back();
    classes[size_t(c)].push_back(int(v));
  }
  return classes;
}

} // namespace interlin::detail
