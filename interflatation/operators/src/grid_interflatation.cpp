// Boolean-sum interflatation on a grid of planes (operators/grid_interflatation.h).
#include "interlin/interflatation/operators/grid_interflatation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace interlin {

using Eigen::Vector3d;

namespace {

// The other two axes of a plane normal to `axis`, in increasing order.
std::array<int, 2> other_axes(int axis) {
  return axis == 0 ? std::array<int, 2>{1, 2}
                   : (axis == 1 ? std::array<int, 2>{0, 2} : std::array<int, 2>{0, 1});
}

// u at q through the trace of plane `i` normal to `axis` (q lies on it).
double on_plane(const PlaneTraces& t, int axis, Eigen::Index i, const Vector3d& q) {
  const auto [a, b] = other_axes(axis);
  return t.traces[axis][static_cast<size_t>(i)](q(a), q(b));
}

} // namespace

PlaneTraces plane_traces(const std::function<double(const Vector3d&)>& u,
                         const std::array<Eigen::VectorXd, 3>& nodes) {
  PlaneTraces t;
  t.nodes = nodes;
  for (int axis = 0; axis < 3; ++axis)
    for (Eigen::Index i = 0; i < nodes[axis].size(); ++i) {
      const double c = nodes[axis](i);
      const auto [a, b] = other_axes(axis);
      // Init-captures: clang before 16 cannot capture structured bindings by name.
      t.traces[axis].push_back([u, axis, s_axis = a, r_axis = b, c](double s, double r) {
        Vector3d q;
        q(axis) = c;
        q(s_axis) = s;
        q(r_axis) = r;
        return u(q);
      });
    }
  return t;
}

double plane_trace_mismatch(const PlaneTraces& t, int samples) {
  double worst = 0;
  // Planes i (normal to k) and j (normal to l) cross on the line along the third axis m.
  for (int k = 0; k < 3; ++k)
    for (int l = k + 1; l < 3; ++l) {
      const int m = 3 - k - l;
      const double lo = t.nodes[m](0), hi = t.nodes[m](t.nodes[m].size() - 1);
      for (Eigen::Index i = 0; i < t.nodes[k].size(); ++i)
        for (Eigen::Index j = 0; j < t.nodes[l].size(); ++j)
          for (int s = 0; s < samples; ++s) {
            Vector3d q;
            q(k) = t.nodes[k](i);
            q(l) = t.nodes[l](j);
            q(m) = lo + (hi - lo) * s / std::max(1, samples - 1);
            worst = std::max(worst, std::abs(on_plane(t, k, i, q) - on_plane(t, l, j, q)));
          }
    }
  return worst;
}

GridInterflatation grid_interflatation(const PlaneTraces& traces, int degree) {
  if (degree != 1 && degree != 3)
    throw std::invalid_argument("grid_interflatation: degree must be 1 or 3");
  GridInterflatation O;
  O.traces = traces;
  for (int k = 0; k < 3; ++k) {
    if (traces.nodes[k].size() < 2 ||
        traces.traces[k].size() != static_cast<size_t>(traces.nodes[k].size()))
      throw std::invalid_argument("grid_interflatation: need >= 2 planes per axis, one trace each");
    O.blend[k] = cardinal_splines(traces.nodes[k], degree);
  }
  return O;
}

double evaluate(const GridInterflatation& O, const Vector3d& p) {
  std::array<Eigen::VectorXd, 3> w;
  for (int k = 0; k < 3; ++k)
    w[k] = evaluate(O.blend[k], p(k)).row(0).transpose();
  double sum = 0;
  // Every non-empty set S of axes (bit k = axis k): (-1)^{|S|+1} P_S u, where P_S replaces p_k
  // by the nodes of every k in S, weighted by the cardinal functions; u there is read from the
  // trace of the first axis of S (the points lie on its planes; compatibility makes the choice
  // immaterial).
  for (int S = 1; S < 8; ++S) {
    const int first = (S & 1) ? 0 : ((S & 2) ? 1 : 2);
    std::array<Eigen::Index, 3> count{1, 1, 1};
    for (int k = 0; k < 3; ++k)
      if (S & (1 << k))
        count[k] = w[k].size();
    double part = 0;
    for (Eigen::Index i0 = 0; i0 < count[0]; ++i0)
      for (Eigen::Index i1 = 0; i1 < count[1]; ++i1)
        for (Eigen::Index i2 = 0; i2 < count[2]; ++i2) {
          const std::array<Eigen::Index, 3> idx{i0, i1, i2};
          double weight = 1;
          Vector3d q = p;
          for (int k = 0; k < 3; ++k)
            if (S & (1 << k)) {
              weight *= w[k](idx[k]);
              q(k) = O.traces.nodes[k](idx[k]);
            }
          if (weight != 0) // local support (degree 1): most weights vanish
            part += weight * on_plane(O.traces, first, idx[first], q);
        }
    const int size = (S & 1) + ((S >> 1) & 1) + ((S >> 2) & 1);
    sum += (size % 2 == 1 ? 1 : -1) * part;
  }
  return sum;
}

double box_interflatation(const std::function<double(const Vector3d&)>& u, const Vector3d& lo,
                          const Vector3d& hi, const Vector3d& p) {
  std::array<Eigen::VectorXd, 3> nodes;
  for (int k = 0; k < 3; ++k)
    nodes[k] = Eigen::Vector2d(lo(k), hi(k));
  return evaluate(grid_interflatation(plane_traces(u, nodes), 1), p);
}

} // namespace interlin
