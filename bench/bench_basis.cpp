// B-spline basis and curve evaluation: the explicit per-span form (seed 001: polynomial
// coefficients computed once, then one Horner pass per function) against the Cox–de Boor
// recursion (Piegl & Tiller A2.3), on the same random nonuniform knot vector and the same 10^6
// random parameters. Each benchmark iteration performs all 10^6 evaluations. Arguments:
// degree, and for the kernels a second one: 0 random order, 1 sorted (as when sampling a grid,
// where the span search is predictable and the arithmetic shows).
//
// Two levels: the library API (basis_derivatives, cox_de_boor_derivatives, evaluate), whose
// Eigen return values cost heap allocations (1 per call for basis_derivatives, 5 for
// cox_de_boor_derivatives), and allocation-free kernels written here from the same formulas
// (checked against the library before timing), which compare the operation counts alone.

#include "interlin/splines/bspline_curve.h"
#include "interlin/splines/cox_de_boor.h"
#include "interlin/splines/knots.h"
#include "interlin/splines/spline_basis.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

namespace {

using namespace interlin;
using Eigen::Index;

constexpr Index kEvaluations = 1000000;
constexpr Index kSpans = 64;

// Clamped knot vector on [0,1] with kSpans spans whose lengths are random in [0.5, 1.5] x mean
// (the same breakpoints for every degree: the seed is fixed), 10^6 uniform parameters, and a
// curve with random control points in [-1,1]^3.
struct BasisFixture {
  int degree = 0;
  Index num_ctrl = 0;
  Eigen::VectorXd knots, u, u_sorted;
  SplineBasis basis;
  BSplineCurve curve;
  PiecewiseCurve piecewise;
};

const BasisFixture& basis_fixture(int p) {
  static std::map<int, BasisFixture> cache;
  auto it = cache.find(p);
  if (it != cache.end())
    return it->second;
  BasisFixture f;
  std::mt19937_64 rng(20240601);
  std::uniform_real_distribution<double> len(0.5, 1.5), unit(0.0, 1.0), coord(-1.0, 1.0);
  Eigen::VectorXd breaks(kSpans + 1);
  breaks(0) = 0;
  for (Index j = 1; j <= kSpans; ++j)
    breaks(j) = breaks(j - 1) + len(rng);
  breaks /= breaks(kSpans);
  f.degree = p;
  f.num_ctrl = kSpans + p;
  f.knots.resize(f.num_ctrl + p + 1);
  for (int k = 0; k < p; ++k) {
    f.knots(k) = 0.0;
    f.knots(f.knots.size() - 1 - k) = 1.0;
  }
  f.knots.segment(p, kSpans + 1) = breaks;
  f.u.resize(kEvaluations);
  for (Index i = 0; i < kEvaluations; ++i)
    f.u(i) = unit(rng);
  f.u_sorted = f.u;
  std::sort(f.u_sorted.data(), f.u_sorted.data() + kEvaluations);
  f.basis = explicit_basis(f.knots, p);
  f.curve.degree = p;
  f.curve.knots = f.knots;
  f.curve.ctrl.resize(f.num_ctrl, 3);
  for (Index i = 0; i < f.curve.ctrl.size(); ++i)
    f.curve.ctrl(i) = coord(rng);
  f.piecewise = to_piecewise(f.curve);
  return cache.emplace(p, std::move(f)).first->second;
}

constexpr int kMaxDegree = 8;

// Explicit kernel: the span's (p+1) x (p+1) coefficient block, Horner on all p+1 rows at once
// (column by column, so the block is read contiguously). N: p+1 values.
void explicit_kernel(const SplineBasis& B, double u, double* N) {
  const int p = B.degree;
  const Index k = find_span(B.knots, p, B.num_ctrl, u);
  const double s = u - B.knots(k);
  const double* c = B.coeffs.data() + (k - p) * (p + 1); // column q at c + q * rows
  const Index rows = B.coeffs.rows();
  for (int r = 0; r <= p; ++r)
    N[r] = c[p * rows + r];
  for (int q = p - 1; q >= 0; --q)
    for (int r = 0; r <= p; ++r)
      N[r] = N[r] * s + c[q * rows + r];
}

// Cox–de Boor kernel: the triangular recursion N_{i,j} from N_{i,j-1} and N_{i+1,j-1} (de Boor
// 1972) in place, with the usual left/right knot differences, on stack arrays.
Index cox_kernel(const Eigen::VectorXd& t, int p, Index n, double u, double* N) {
  const Index k = find_span(t, p, n, u);
  double left[kMaxDegree + 1], right[kMaxDegree + 1];
  N[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - t(k + 1 - j);
    right[j] = t(k + j) - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = N[r] / (right[r + 1] + left[j - r]);
      N[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    N[j] = saved;
  }
  return k;
}

// Curve point from the per-span power form: span by binary search on the breaks, Horner on the
// span's (p+1) x 3 block.
Eigen::Vector3d piecewise_kernel(const PiecewiseCurve& c, double u) {
  const int p = c.degree;
  const Index s = c.breaks.size() - 1;
  const Index j = std::clamp<Index>(std::upper_bound(c.breaks.data(), c.breaks.data() + s + 1, u) -
                                        c.breaks.data() - 1,
                                    0, s - 1);
  const double h = u - c.breaks(j);
  Eigen::Vector3d x = c.coeffs.row(j * (p + 1) + p).transpose();
  for (int q = p - 1; q >= 0; --q)
    x = x * h + c.coeffs.row(j * (p + 1) + q).transpose();
  return x;
}

// The kernels must reproduce the library (1e-12: values of order 1, different round-off).
bool kernels_agree(const BasisFixture& f) {
  const int p = f.degree;
  double N[kMaxDegree + 1], M[kMaxDegree + 1];
  double err = 0;
  for (Index i = 0; i < 1000; ++i) {
    explicit_kernel(f.basis, f.u(i), N);
    const Index k = cox_kernel(f.knots, p, f.num_ctrl, f.u(i), M);
    const Eigen::MatrixXd R = cox_de_boor_derivatives(f.knots, p, f.num_ctrl, f.u(i), 0);
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int r = 0; r <= p; ++r) {
      err = std::max({err, std::abs(N[r] - R(0, r)), std::abs(M[r] - R(0, r))});
      x += M[r] * f.curve.ctrl.row(k - p + r).transpose();
    }
    err = std::max(err, (piecewise_kernel(f.piecewise, f.u(i)) - x).cwiseAbs().maxCoeff());
  }
  return err <= 1e-12;
}

void finish(benchmark::State& st) {
  st.SetItemsProcessed(static_cast<int64_t>(st.iterations()) * kEvaluations);
}

// All p+1 non-zero basis values at each u, explicit form (basis built once, outside the loop).
void BM_basis_explicit(benchmark::State& st) {
  const BasisFixture& f = basis_fixture(static_cast<int>(st.range(0)));
  for (auto _ : st) {
    double sink = 0;
    for (Index i = 0; i < kEvaluations; ++i)
      sink += basis_derivatives(f.basis, f.u(i), 0)(0, 0);
    benchmark::DoNotOptimize(sink);
  }
  finish(st);
}
BENCHMARK(BM_basis_explicit)->Arg(2)->Arg(3)->Arg(5)->Unit(benchmark::kMillisecond);

// The same values by the Cox–de Boor recursion.
void BM_basis_cox_de_boor(benchmark::State& st) {
  const BasisFixture& f = basis_fixture(static_cast<int>(st.range(0)));
  for (auto _ : st) {
    double sink = 0;
    for (Index i = 0; i < kEvaluations; ++i)
      sink += cox_de_boor_derivatives(f.knots, f.degree, f.num_ctrl, f.u(i), 0)(0, 0);
    benchmark::DoNotOptimize(sink);
  }
  finish(st);
}
BENCHMARK(BM_basis_cox_de_boor)->Arg(2)->Arg(3)->Arg(5)->Unit(benchmark::kMillisecond);

// Curve points C(u) (3D) at the 10^6 parameters: evaluate on the per-span power form
// (to_piecewise done once, outside the loop), one Horner pass per point.
void BM_curve_point_piecewise(benchmark::State& st) {
  const BasisFixture& f = basis_fixture(static_cast<int>(st.range(0)));
  for (auto _ : st) {
    Eigen::MatrixXd X = evaluate(f.piecewise, f.u);
    benchmark::DoNotOptimize(X.data());
  }
  finish(st);
}
BENCHMARK(BM_curve_point_piecewise)->Arg(2)->Arg(3)->Arg(5)->Unit(benchmark::kMillisecond);

// Curve points as sum_r N_r P_r with the basis values N_r(u) from `basis_at(u, span)`.
template <class BasisAt>
void curve_point_basis_sum(benchmark::State& st, const BasisFixture& f, BasisAt basis_at) {
  const int p = f.degree;
  for (auto _ : st) {
    Eigen::MatrixXd X(kEvaluations, 3);
    for (Index i = 0; i < kEvaluations; ++i) {
      Index k = 0;
      const Eigen::MatrixXd N = basis_at(f.u(i), k);
      X.row(i) = N.row(0) * f.curve.ctrl.middleRows(k - p, p + 1);
    }
    benchmark::DoNotOptimize(X.data());
  }
  finish(st);
}

// Curve points as the Cox–de Boor sum: basis values by the recursion, then sum_r N_r P_r.
void BM_curve_point_cox_de_boor(benchmark::State& st) {
  const BasisFixture& f = basis_fixture(static_cast<int>(st.range(0)));
  curve_point_basis_sum(st, f, [&](double u, Index& k) {
    return cox_de_boor_derivatives(f.knots, f.degree, f.num_ctrl, u, 0, &k);
  });
}
BENCHMARK(BM_curve_point_cox_de_boor)->Arg(2)->Arg(3)->Arg(5)->Unit(benchmark::kMillisecond);

// Curve points as the sum over explicit basis values (per-basis Horner, then sum_r N_r P_r):
// separates the gain of the per-span basis from that of the per-curve power form.
void BM_curve_point_explicit_basis_sum(benchmark::State& st) {
  const BasisFixture& f = basis_fixture(static_cast<int>(st.range(0)));
  curve_point_basis_sum(st, f,
                        [&](double u, Index& k) { return basis_derivatives(f.basis, u, 0, &k); });
}
BENCHMARK(BM_curve_point_explicit_basis_sum)->Arg(2)->Arg(3)->Arg(5)->Unit(benchmark::kMillisecond);

} // namespace

namespace {

// Allocation-free kernels (see the top of the file): basis values, explicit form.
void BM_basis_kernel_explicit(benchmark::State& st) {
  const BasisFixture& f = basis_fixture(static_cast<int>(st.range(0)));
  const Eigen::VectorXd& u = st.range(1) ? f.u_sorted : f.u;
  if (!kernels_agree(f))
    st.SkipWithError("kernels disagree with the library");
  double N[kMaxDegree + 1];
  for (auto _ : st) {
    double sink = 0;
    for (Index i = 0; i < kEvaluations; ++i) {
      explicit_kernel(f.basis, u(i), N);
      sink += N[0];
    }
    benchmark::DoNotOptimize(sink);
  }
  finish(st);
}
BENCHMARK(BM_basis_kernel_explicit)
    ->ArgsProduct({{2, 3, 5}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

// Allocation-free kernels: basis values, Cox–de Boor recursion.
void BM_basis_kernel_cox_de_boor(benchmark::State& st) {
  const BasisFixture& f = basis_fixture(static_cast<int>(st.range(0)));
  const Eigen::VectorXd& u = st.range(1) ? f.u_sorted : f.u;
  double N[kMaxDegree + 1];
  for (auto _ : st) {
    double sink = 0;
    for (Index i = 0; i < kEvaluations; ++i) {
      cox_kernel(f.knots, f.degree, f.num_ctrl, u(i), N);
      sink += N[0];
    }
    benchmark::DoNotOptimize(sink);
  }
  finish(st);
}
BENCHMARK(BM_basis_kernel_cox_de_boor)
    ->ArgsProduct({{2, 3, 5}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

// Allocation-free kernels: curve points, Horner on the per-span power form.
void BM_curve_point_kernel_piecewise(benchmark::State& st) {
  const BasisFixture& f = basis_fixture(static_cast<int>(st.range(0)));
  const Eigen::VectorXd& u = st.range(1) ? f.u_sorted : f.u;
  for (auto _ : st) {
    Eigen::MatrixXd X(kEvaluations, 3);
    for (Index i = 0; i < kEvaluations; ++i)
      X.row(i) = piecewise_kernel(f.piecewise, u(i)).transpose();
    benchmark::DoNotOptimize(X.data());
  }
  finish(st);
}
BENCHMARK(BM_curve_point_kernel_piecewise)
    ->ArgsProduct({{2, 3, 5}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

// Allocation-free kernels: curve points as the Cox–de Boor sum sum_r N_r P_r.
void BM_curve_point_kernel_cox_de_boor(benchmark::State& st) {
  const BasisFixture& f = basis_fixture(static_cast<int>(st.range(0)));
  const Eigen::VectorXd& u = st.range(1) ? f.u_sorted : f.u;
  const int p = f.degree;
  double N[kMaxDegree + 1];
  for (auto _ : st) {
    Eigen::MatrixXd X(kEvaluations, 3);
    for (Index i = 0; i < kEvaluations; ++i) {
      const Index k = cox_kernel(f.knots, p, f.num_ctrl, u(i), N);
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      for (int r = 0; r <= p; ++r)
        x += N[r] * f.curve.ctrl.row(k - p + r).transpose();
      X.row(i) = x.transpose();
    }
    benchmark::DoNotOptimize(X.data());
  }
  finish(st);
}
BENCHMARK(BM_curve_point_kernel_cox_de_boor)
    ->ArgsProduct({{2, 3, 5}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

} // namespace
