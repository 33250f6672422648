#include "interlin/splines/bspline_surface.h"

#include "interlin/splines/knots.h"
#include "interlin/splines/spline_basis.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

void check_surface(const BSplineSurface& s) {
  check_knots(s.knots_u, s.degree_u, s.num_u);
  check_knots(s.knots_v, s.degree_v, s.num_v);
  if (s.ctrl.rows() != s.num_u * s.num_v || s.ctrl.cols() != 3)
    throw std::invalid_argument("surface control net must be (num_u*num_v) by 3");
  if (!s.ctrl.allFinite())
    throw std::invalid_argument("surface control points must be finite");
}

namespace {

std::vector<Index> nonempty_spans(const VectorXd& t, int p, Index n) {
  std::vector<Index> spans;
  for (Index k = p; k < n; ++k)
    if (t(k) < t(k + 1))
      spans.push_back(k);
  return spans;
}

VectorXd breaks_of(const VectorXd& t, const std::vector<Index>& spans, Index n) {
  VectorXd b(static_cast<Index>(spans.size()) + 1);
  for (size_t j = 0; j < spans.size(); ++j)
    b(static_cast<Index>(j)) = t(spans[j]);
  b(b.size() - 1) = t(n);
  return b;
}

// Patch index along one direction and the local coordinate.
Index locate(const VectorXd& breaks, bool wrap, double& x) {
  const Index s = breaks.size() - 1;
  const double a = breaks(0), b = breaks(s);
  if (wrap && (x < a || x >= b))
    x = a + (x - a) - (b - a) * std::floor((x - a) / (b - a));
  if (!(x > a)) // NaN too: its span would be past the last one (upper_bound finds no break)
    return 0;
  if (x >= b)
    return s - 1;
  return std::upper_bound(breaks.data(), breaks.data() + s + 1, x) - breaks.data() - 1;
}

// d-th derivative factor q!/(q-d)!.
double falling(int q, int d) {
  double f = 1;
  for (int m = 0; m < d; ++m)
    f *= q - m;
  return f;
}

} // namespace

PiecewiseSurface to_piecewise(const BSplineSurface& s) {
  check_surface(s);
  const int pu = s.degree_u, pv = s.degree_v;
  const SplineBasis Bu = explicit_basis(s.knots_u, pu), Bv = explicit_basis(s.knots_v, pv);
  const std::vector<Index> su = nonempty_spans(s.knots_u, pu, s.num_u);
  const std::vector<Index> sv = nonempty_spans(s.knots_v, pv, s.num_v);
  PiecewiseSurface ps;
  ps.degree_u = pu;
  ps.degree_v = pv;
  ps.closed_u = s.closed_u;
  ps.breaks_u = breaks_of(s.knots_u, su, s.num_u);
  ps.breaks_v = breaks_of(s.knots_v, sv, s.num_v);
  const Index nb = (pu + 1) * (pv + 1);
  ps.coeffs.resize(static_cast<Index>(su.size() * sv.size()) * nb, 3);
  MatrixXd tmp((pu + 1) * (pv + 1), 3);
  for (size_t a = 0; a < su.size(); ++a) {
    const auto Au = Bu.coeffs.middleRows((su[a] - pu) * (pu + 1), pu + 1); // row r, col i
    for (size_t b = 0; b < sv.size(); ++b) {
      const auto Av = Bv.coeffs.middleRows((sv[b] - pv) * (pv + 1), pv + 1); // row s, col j
      // tmp(r, j) = sum_s Av(s, j) P(ku-pu+r, kv-pv+s)
      for (int r = 0; r <= pu; ++r)
        for (int j = 0; j <= pv; ++j) {
          Eigen::RowVector3d acc = Eigen::RowVector3d::Zero();
          for (int q = 0; q <= pv; ++q)
            acc += Av(q, j) * s.ctrl.row((su[a] - pu + r) + s.num_u * (sv[b] - pv + q));
          tmp.row(r * (pv + 1) + j) = acc;
        }
      const Index base = static_cast<Index>(a * sv.size() + b) * nb;
      for (int i = 0; i <= pu; ++i)
        for (int j = 0; j <= pv; ++j) {
          Eigen::RowVector3d acc = Eigen::RowVector3d::Zero();
          for (int r = 0; r <= pu; ++r)
            acc += Au(r, i) * tmp.row(r * (pv + 1) + j);
          ps.coeffs.row(base + i * (pv + 1) + j) = acc;
        }
    }
  }
  return ps;
}

Vector3d evaluate(const PiecewiseSurface& s, double u, double v, int du, int dv) {
  if (du < 0 || dv < 0)
    throw std::invalid_argument("derivative orders must be >= 0");
  const int pu = s.degree_u, pv = s.degree_v;
  if (du > pu || dv > pv)
    return Vector3d::Zero();
  const Index a = locate(s.breaks_u, s.closed_u, u), b = locate(s.breaks_v, false, v);
  const double hu = u - s.breaks_u(a), hv = v - s.breaks_v(b);
  const Index sv = s.breaks_v.size() - 1, stride = s.coeffs.rows();
  // Horner in v, then in u, on the patch's coefficients (plain scalars: Eigen temporaries of
  // 3-vectors in this inner loop cost several times the arithmetic).
  const double* C = s.coeffs.data() + (a * sv + b) * (pu + 1) * (pv + 1);
  double out[3] = {0, 0, 0};
  for (int i = pu; i >= du; --i) {
    double row[3] = {0, 0, 0}; // the coefficient of (u - u_a)^i
    for (int j = pv; j >= dv; --j) {
      const double f = falling(j, dv);
      const double* c = C + i * (pv + 1) + j;
      for (int k = 0; k < 3; ++k)
        row[k] = row[k] * hv + f * c[k * stride];
    }
    const double f = falling(i, du);
    for (int k = 0; k < 3; ++k)
      out[k] = out[k] * hu + f * row[k];
  }
  return {out[0], out[1], out[2]};
}

SurfaceJet evaluate_jet(const PiecewiseSurface& s, double u, double v) {
  const int pu = s.degree_u, pv = s.degree_v;
  const Index a = locate(s.breaks_u, s.closed_u, u), b = locate(s.breaks_v, false, v);
  const double hu = u - s.breaks_u(a), hv = v - s.breaks_v(b);
  const Index sv = s.breaks_v.size() - 1;
  const double* C = s.coeffs.data();
  const Index stride = s.coeffs.rows(); // column-major: component c of row r is C[r + c * stride]
  const Index base = (a * sv + b) * (pu + 1) * (pv + 1);
  SurfaceJet J;
  for (int c = 0; c < 3; ++c) {
    double S = 0, Su = 0, Sv = 0, Suu = 0, Suv = 0, Svv = 0;
    for (int i = pu; i >= 0; --i) {
      // r0, r1, r2: the coefficient of (u - u_a)^i and its first and second v-derivatives
      double r0 = 0, r1 = 0, r2 = 0;
      const double* row = C + base + i * (pv + 1) + c * stride;
      for (int j = pv; j >= 0; --j) {
        r2 = r2 * hv + r1 * 2;
        r1 = r1 * hv + r0;
        r0 = r0 * hv + row[j];
      }
      Suu = Suu * hu + Su * 2;
      Su = Su * hu + S;
      S = S * hu + r0;
      Suv = Suv * hu + Sv;
      Sv = Sv * hu + r1;
      Svv = Svv * hu + r2;
    }
    J.S(c) = S, J.Su(c) = Su, J.Sv(c) = Sv, J.Suu(c) = Suu, J.Suv(c) = Suv, J.Svv(c) = Svv;
  }
  return J;
}

MatrixXd evaluate_grid(const PiecewiseSurface& s, const VectorXd& u, const VectorXd& v) {
  MatrixXd out(u.size() * v.size(), 3);
  for (Index j = 0; j < v.size(); ++j)
    for (Index i = 0; i < u.size(); ++i)
      out.row(i + u.size() * j) = evaluate(s, u(i), v(j)).transpose();
  return out;
}

Eigen::Vector4d domain(const PiecewiseSurface& s) {
  return {s.breaks_u(0), s.breaks_u(s.breaks_u.size() - 1), s.breaks_v(0),
          s.breaks_v(s.breaks_v.size() - 1)};
}

} // namespace interlin
