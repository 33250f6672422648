#include "interlin/interflatation/operators/cubic_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace interlin {

namespace {

// Coefficients c_{-1..m} of the uniform cubic spline through f_0..f_{m-1}:
// f_i = (c_{i-1} + 4 c_i + c_{i+1}) / 6 and c_{-1} - 2 c_0 + c_1 = 0 (natural end), which give
// c_0 = f_0, c_{m-1} = f_{m-1} and a tridiagonal system for the rest (Thomas algorithm).
// In/out: c points at c_{-1}; m + 2 values spaced by `stride`; on input c_i holds f_i.
void interpolate_line(double* c, long m, long stride, std::vector<double>& work) {
  auto at = [&](long i) -> double& { return c[(i + 1) * stride]; };
  if (m > 2) {
    // Unknowns c_1..c_{m-2}: c_{i-1} + 4 c_i + c_{i+1} = 6 f_i, ends known.
    const long k = m - 2;
    work.assign(static_cast<size_t>(k), 0.0);
    std::vector<double> rhs(static_cast<size_t>(k));
    for (long i = 0; i < k; ++i)
      rhs[static_cast<size_t>(i)] = 6 * at(i + 1);
    rhs[0] -= at(0);
    rhs[static_cast<size_t>(k - 1)] -= at(m - 1);
    // Forward sweep of the Thomas algorithm on diagonal 4, off-diagonals 1.
    double diag = 4;
    work[0] = 1 / diag;
    for (long i = 1; i < k; ++i) {
      diag = 4 - work[static_cast<size_t>(i - 1)];
      work[static_cast<size_t>(i)] = 1 / diag;
      rhs[static_cast<size_t>(i)] -=
          rhs[static_cast<size_t>(i - 1)] * work[static_cast<size_t>(i - 1)];
    }
    rhs[static_cast<size_t>(k - 1)] *= work[static_cast<size_t>(k - 1)];
    for (long i = k - 2; i >= 0; --i)
      rhs[static_cast<size_t>(i)] =
          (rhs[static_cast<size_t>(i)] - rhs[static_cast<size_t>(i + 1)]) *
          work[static_cast<size_t>(i)];
    for (long i = 0; i < k; ++i)
      at(i + 1) = rhs[static_cast<size_t>(i)];
  }
  at(-1) = 2 * at(0) - at(1);
  at(m) = 2 * at(m - 1) - at(m - 2);
}

// Uniform cubic B-spline weights at local coordinate s in [0, 1] (and their derivatives).
inline void weights(double s, double w[4], double d[4]) {
  const double t = 1 - s, s2 = s * s;
  w[0] = t * t * t / 6;
  w[1] = (3 * s2 * s - 6 * s2 + 4) / 6;
  w[2] = (-3 * s2 * s + 3 * s2 + 3 * s + 1) / 6;
  w[3] = s2 * s / 6;
  d[0] = -t * t / 2;
  d[1] = (3 * s2 - 4 * s) / 2;
  d[2] = (-3 * s2 + 2 * s + 1) / 2;
  d[3] = s2 / 2;
}

} // namespace

CubicGrid cubic_grid(const std::vector<double>& values, const Eigen::Vector3d& origin, double h,
                     const Eigen::Array3i& n) {
  if ((n < 2).any())
    throw std::invalid_argument("cubic_grid: at least 2 nodes per axis");
  if (!(h > 0) || !origin.allFinite())
    throw std::invalid_argument("cubic_grid: spacing must be > 0 and the origin finite");
  const long n0 = n(0), n1 = n(1), n2 = n(2);
  if (static_cast<long>(values.size()) != n0 * n1 * n2)
    throw std::invalid_argument("cubic_grid: expected n0*n1*n2 node values");
  CubicGrid G;
  G.origin = origin;
  G.h = h;
  G.n = n;
  const long m0 = n0 + 2, m1 = n1 + 2, m2 = n2 + 2;
  G.coeffs.assign(static_cast<size_t>(m0 * m1 * m2), 0.0);
  auto idx = [&](long i, long j, long k) {
    return static_cast<size_t>((i + 1) + m0 * ((j + 1) + m1 * (k + 1)));
  };
  for (long k = 0; k < n2; ++k)
    for (long j = 0; j < n1; ++j)
      for (long i = 0; i < n0; ++i)
        G.coeffs[idx(i, j, k)] = values[static_cast<size_t>(i + n0 * (j + n1 * k))];
  std::vector<double> work;
  double* c = G.coeffs.data();
  for (long k = 0; k < n2; ++k) // along x
    for (long j = 0; j < n1; ++j)
      interpolate_line(c + idx(-1, j, k), n0, 1, work);
  for (long k = 0; k < n2; ++k) // along y, every x coefficient
    for (long i = -1; i <= n0; ++i)
      interpolate_line(c + idx(i, -1, k), n1, m0, work);
  for (long j = -1; j <= n1; ++j) // along z, every (x, y) coefficient
    for (long i = -1; i <= n0; ++i)
      interpolate_line(c + idx(i, j, -1), n2, m0 * m1, work);
  return G;
}

double evaluate(const CubicGrid& G, const Eigen::Vector3d& p, Eigen::Vector3d* gradient) {
  double w[3][4], d[3][4];
  long cell[3];
  for (int a = 0; a < 3; ++a) {
    const double t = (p(a) - G.origin(a)) / G.h;
    const long c = std::clamp(static_cast<long>(std::floor(t)), 0L, static_cast<long>(G.n(a)) - 2);
    cell[a] = c;
    weights(t - static_cast<double>(c), w[a], d[a]);
  }
  const long m0 = G.n(0) + 2, m1 = G.n(1) + 2;
  const double* C = G.coeffs.data() + cell[0] + m0 * (cell[1] + m1 * cell[2]);
  double f = 0, fx = 0, fy = 0, fz = 0;
  for (int k = 0; k < 4; ++k) {
    double gy = 0, gyx = 0, gyy = 0;
    for (int j = 0; j < 4; ++j) {
      const double* row = C + m0 * (j + m1 * k);
      const double rx = w[0][0] * row[0] + w[0][1] * row[1] + w[0][2] * row[2] + w[0][3] * row[3];
      gy += w[1][j] * rx;
      gyy += d[1][j] * rx;
      if (gradient)
        gyx +=
            w[1][j] * (d[0][0] * row[0] + d[0][1] * row[1] + d[0][2] * row[2] + d[0][3] * row[3]);
    }
    f += w[2][k] * gy;
    fx += w[2][k] * gyx;
    fy += w[2][k] * gyy;
    fz += d[2][k] * gy;
  }
  if (gradient)
    *gradient = Eigen::Vector3d(fx, fy, fz) / G.h;
  return f;
}

Eigen::Vector3d grid_max(const CubicGrid& G) {
  return G.origin + G.h * (G.n - 1).cast<double>().matrix();
}

} // namespace interlin
