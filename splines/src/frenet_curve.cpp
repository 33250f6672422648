// seed 004 §2.4 (digest 004 §2.3, §4.3): Frenet integration with piecewise-linear k(s), tau(s).
#include "interlin/splines/frenet_curve.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace interlin {

using Eigen::Index;
using Eigen::Vector3d;
using Eigen::VectorXd;
using State = Eigen::Matrix<double, 12, 1>; // r, t, n, b

namespace {

void check_law(const PiecewiseLinearLaw& L, const char* name) {
  const std::string n(name);
  if (L.s.size() < 1 || L.s.size() != L.value.size())
    throw std::invalid_argument(n + " law: need as many values as breaks (at least 1)");
  if (!L.s.allFinite() || !L.value.allFinite())
    throw std::invalid_argument(n + " law: breaks and values must be finite");
  for (Index i = 1; i < L.s.size(); ++i)
    if (!(L.s(i) > L.s(i - 1)))
      throw std::invalid_argument(n + " law: breaks must increase strictly");
}

double value_at(const PiecewiseLinearLaw& L, double s) {
  const Index n = L.s.size();
  if (n == 1 || s <= L.s(0))
    return L.value(0);
  if (s >= L.s(n - 1))
    return L.value(n - 1);
  const Index i = std::upper_bound(L.s.data(), L.s.data() + n, s) - L.s.data() - 1;
  const double w = (s - L.s(i)) / (L.s(i + 1) - L.s(i));
  return (1 - w) * L.value(i) + w * L.value(i + 1);
}

// Right-hand side of the Frenet system (13 equations of the book without the s counter).
State rhs(const PiecewiseLinearLaw& k, const PiecewiseLinearLaw& tau, double s, const State& y) {
  const double kk = value_at(k, s), tt = value_at(tau, s);
  State f;
  f.segment<3>(0) = y.segment<3>(3);
  f.segment<3>(3) = kk * y.segment<3>(6);
  f.segment<3>(6) = -kk * y.segment<3>(3) + tt * y.segment<3>(9);
  f.segment<3>(9) = -tt * y.segment<3>(6);
  return f;
}

State rk4_step(const PiecewiseLinearLaw& k, const PiecewiseLinearLaw& tau, double s, const State& y,
               double h) {
  const State k1 = rhs(k, tau, s, y);
  const State k2 = rhs(k, tau, s + h / 2, y + h / 2 * k1);
  const State k3 = rhs(k, tau, s + h / 2, y + h / 2 * k2);
  const State k4 = rhs(k, tau, s + h, y + h * k3);
  return y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
}

// Dormand–Prince 5(4): the 5th-order solution and the error estimate.
State dopri_step(const PiecewiseLinearLaw& k, const PiecewiseLinearLaw& tau, double s,
                 const State& y, double h, double& err) {
  const State k1 = rhs(k, tau, s, y);
  const State k2 = rhs(k, tau, s + h / 5, y + h * (k1 / 5));
  const State k3 = rhs(k, tau, s + 3 * h / 10, y + h * (3 * k1 / 40 + 9 * k2 / 40));
  const State k4 = rhs(k, tau, s + 4 * h / 5, y + h * (44 * k1 / 45 - 56 * k2 / 15 + 32 * k3 / 9));
  const State k5 =
      rhs(k, tau, s + 8 * h / 9,
          y + h * (19372 * k1 / 6561 - 25360 * k2 / 2187 + 64448 * k3 / 6561 - 212 * k4 / 729));
  const State k6 = rhs(k, tau, s + h,
                       y + h * (9017 * k1 / 3168 - 355 * k2 / 33 + 46732 * k3 / 5247 +
                                49 * k4 / 176 - 5103 * k5 / 18656));
  const State y5 =
      y + h * (35 * k1 / 384 + 500 * k3 / 1113 + 125 * k4 / 192 - 2187 * k5 / 6784 + 11 * k6 / 84);
  const State k7 = rhs(k, tau, s + h, y5);
  const State e = h * ((35.0 / 384 - 5179.0 / 57600) * k1 + (500.0 / 1113 - 7571.0 / 16695) * k3 +
                       (125.0 / 192 - 393.0 / 640) * k4 + (-2187.0 / 6784 + 92097.0 / 339200) * k5 +
                       (11.0 / 84 - 187.0 / 2100) * k6 - k7 / 40);
  err = e.cwiseAbs().maxCoeff();
  return y5;
}

} // namespace

double evaluate(const PiecewiseLinearLaw& law, double s) {
  check_law(law, "piecewise-linear");
  return value_at(law, s);
}

std::vector<FrenetFrame> integrate_frenet(const PiecewiseLinearLaw& k,
                                          const PiecewiseLinearLaw& tau, const VectorXd& s,
                                          const FrenetFrame& start, const FrenetOptions& o) {
  check_law(k, "curvature");
  check_law(tau, "torsion");
  const Eigen::Matrix3d F = (Eigen::Matrix3d() << start.t, start.n, start.b).finished();
  if (!start.r.allFinite() || !F.allFinite() ||
      (F.transpose() * F - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-12 ||
      F.determinant() < 0)
    throw std::invalid_argument("Frenet start frame must be finite, orthonormal, right-handed");
  if (o.method == FrenetIntegrator::rk4 && !(o.step > 0 && std::isfinite(o.step)))
    throw std::invalid_argument("Frenet RK4 step must be > 0");
  if (o.method == FrenetIntegrator::adaptive && !(o.tolerance > 0))
    throw std::invalid_argument("Frenet tolerance must be > 0");
  for (Index i = 0; i < s.size(); ++i)
    if (!std::isfinite(s(i)) || s(i) < 0 || (i > 0 && s(i) < s(i - 1)))
      throw std::invalid_argument("Frenet output arc lengths must be finite, >= 0, non-decreasing");

  State y;
  y << start.r, start.t, start.n, start.b;
  std::vector<FrenetFrame> out;
  double pos = 0, h = o.method == FrenetIntegrator::rk4 ? o.step : 1e-2;
  for (Index i = 0; i < s.size(); ++i) {
    // Stops: the breaks of k and tau between the current position and the next output.
    std::vector<double> stops;
    for (const VectorXd* br : {&k.s, &tau.s})
      for (Index j = 0; j < br->size(); ++j)
        if ((*br)(j) > pos && (*br)(j) < s(i))
          stops.push_back((*br)(j));
    std::sort(stops.begin(), stops.end());
    stops.push_back(s(i));
    for (double stop : stops) {
      const double len = stop - pos;
      if (len <= 0)
        continue;
      if (o.method == FrenetIntegrator::rk4) {
        const int n = static_cast<int>(std::ceil(len / o.step - 1e-12));
        for (int m = 0; m < n; ++m)
          y = rk4_step(k, tau, pos + len * m / n, y, len / n);
      } else {
        double at = pos;
        while (at < stop) {
          const double step = std::min(h, stop - at);
          double err = 0;
          const State next = dopri_step(k, tau, at, y, step, err);
          const double allowed = o.tolerance * step;
          if (err <= allowed || step < 1e-12 * std::max(1.0, stop)) {
            y = next;
            at += step;
          }
          const double factor = err > 0 ? 0.9 * std::pow(allowed / err, 0.2) : 5.0;
          h = step * std::clamp(factor, 0.2, 5.0);
        }
      }
      pos = stop;
    }
    FrenetFrame f;
    f.r = y.segment<3>(0);
    f.t = y.segment<3>(3);
    f.n = y.segment<3>(6);
    f.b = y.segment<3>(9);
    out.push_back(f);
  }
  return out;
}

} // namespace interlin
