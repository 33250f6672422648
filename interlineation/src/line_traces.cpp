// Traces on grid lines and their compatibility at the crossings.
#include "interlin/interlineation/line_traces.h"

#include "interlin/splines/interpolate_curve.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::RowVectorXd;
using Eigen::VectorXd;

Trace spline_trace(const BSplineCurve& c) {
  const PiecewiseCurve pc = to_piecewise(c);
  return [pc](double s, int d) -> RowVectorXd {
    return evaluate(pc, VectorXd::Constant(1, s), d).row(0);
  };
}

Trace sampled_trace(const VectorXd& s, const MatrixXd& values, int degree) {
  if (values.rows() != s.size())
    throw std::invalid_argument("sampled_trace: one row of values per sample expected");
  return spline_trace(interpolate_open(values, s, degree));
}

namespace {

void check_lines(const VectorXd& s, size_t count, const char* name) {
  if (static_cast<size_t>(s.size()) != count)
    throw std::invalid_argument(std::string("line traces: ") + std::to_string(s.size()) +
                                " lines " + name + " but " + std::to_string(count) + " traces");
  for (Index i = 0; i < s.size(); ++i)
    if (!std::isfinite(s(i)) || (i > 0 && !(s(i) > s(i - 1))))
      throw std::invalid_argument(std::string("line traces: the lines ") + name +
                                  " must be finite and increasing (line " + std::to_string(i) +
                                  ")");
}

} // namespace

MatrixXd crossing_values(const std::vector<Trace>& a, const VectorXd& s_b, int deriv_a,
                         const std::vector<Trace>& b, const VectorXd& s_a, int deriv_b,
                         double tolerance, const std::string& what) {
  const Index na = static_cast<Index>(a.size()), nb = static_cast<Index>(b.size());
  MatrixXd out;
  for (Index j = 0; j < nb; ++j)
    for (Index i = 0; i < na; ++i) {
      const RowVectorXd fa = a[static_cast<size_t>(i)](s_b(j), deriv_a);
      const RowVectorXd fb = b[static_cast<size_t>(j)](s_a(i), deriv_b);
      if (out.size() == 0)
        out.resize(na * nb, fa.size());
      if (fa.size() != out.cols() || fb.size() != out.cols())
        throw std::invalid_argument("line traces: all traces must have the same dimension");
      if (!fa.allFinite() || !fb.allFinite())
        throw std::invalid_argument("line traces: non-finite " + what + " at crossing (" +
                                    std::to_string(i) + ", " + std::to_string(j) + ")");
      const double gap = (fa - fb).cwiseAbs().maxCoeff();
      const double scale = std::max({1.0, fa.cwiseAbs().maxCoeff(), fb.cwiseAbs().maxCoeff()});
      if (gap > tolerance * scale) {
        std::ostringstream m;
        m.precision(6);
        m << "line traces are not compatible: the " << what << " at crossing (" << i << ", " << j
          << ") = (" << s_a(i) << ", " << s_b(j) << ") differs by " << gap
          << " between the two lines (tolerance " << tolerance * scale << ")";
        throw std::invalid_argument(m.str());
      }
      out.row(i + na * j) = 0.5 * (fa + fb);
    }
  return out;
}

MatrixXd crossing_values(const LineTraces& t, double tolerance) {
  check_lines(t.x, t.on_x.size(), "x = x_i");
  check_lines(t.y, t.on_y.size(), "y = y_j");
  return crossing_values(t.on_x, t.y, 0, t.on_y, t.x, 0, tolerance, "value");
}

} // namespace interlin
