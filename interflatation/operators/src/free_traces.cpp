// Free traces of Theorems 4 and 5 by least squares or min-max (operators/free_traces.h).
#include "interlin/interflatation/operators/free_traces.h"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// Lawson iterations: the max-norm residual settles to a few per cent of its optimum in tens
// of steps; the best iterate is kept.
constexpr int kLawsonIterations = 40;
// Tikhonov weight relative to the mean squared column norm: keeps the coefficients of nodes
// whose hats barely meet G bounded without moving the fit (1e-8 of the data's scale).
constexpr double kRidge = 1e-8;

// The hat functions of the nodes of one axis that are nonzero at s: the cell's two nodes and
// their weights (the cell clamps to the grid).
struct Hat1 {
  Index i = 0;
  double w0 = 1, w1 = 0;
};

Hat1 hat(const VectorXd& v, double s) {
  const auto it = std::upper_bound(v.data(), v.data() + v.size(), s);
  Hat1 h;
  h.i = std::clamp<Index>(it - v.data() - 1, 0, v.size() - 2);
  const double t = std::clamp((s - v(h.i)) / (v(h.i + 1) - v(h.i)), 0.0, 1.0);
  h.w0 = 1 - t;
  h.w1 = t;
  return h;
}

// The nonzero hats of the tensor grid at p: node ids (x fastest) and weights.
template <int D>
void hats(const std::array<VectorXd, D>& nodes, const Eigen::Matrix<double, D, 1>& p,
          std::array<Index, (1 << D)>& id, std::array<double, (1 << D)>& weight) {
  std::array<Hat1, D> h;
  for (int a = 0; a < D; ++a)
    h[static_cast<size_t>(a)] = hat(nodes[static_cast<size_t>(a)], p(a));
  for (int corner = 0; corner < (1 << D); ++corner) {
    Index n = 0, stride = 1;
    double w = 1;
    for (int a = 0; a < D; ++a) {
      const bool one = (corner >> a) & 1;
      n += (h[static_cast<size_t>(a)].i + (one ? 1 : 0)) * stride;
      stride *= nodes[static_cast<size_t>(a)].size();
      w *= one ? h[static_cast<size_t>(a)].w1 : h[static_cast<size_t>(a)].w0;
    }
    id[static_cast<size_t>(corner)] = n;
    weight[static_cast<size_t>(corner)] = w;
  }
}

template <int D>
Index node_count(const std::array<VectorXd, D>& nodes) {
  Index n = 1;
  for (const VectorXd& v : nodes)
    n *= v.size();
  return n;
}

// u = w (1 + sum c_k phi_k).
template <int D>
std::function<double(const Eigen::Matrix<double, D, 1>&)>
modulated(std::function<double(const Eigen::Matrix<double, D, 1>&)> w,
          const std::array<VectorXd, D>& nodes, VectorXd c) {
  return [w = std::move(w), nodes, c = std::move(c)](const Eigen::Matrix<double, D, 1>& p) {
    std::array<Index, (1 << D)> id;
    std::array<double, (1 << D)> weight;
    hats<D>(nodes, p, id, weight);
    double f = 1;
    for (size_t k = 0; k < id.size(); ++k)
      f += c(id[k]) * weight[k];
    return w(p) * f;
  };
}

// The fit for an operator type Op (its u member swapped per column; O is linear in u). A sample
// only meets the hats of its cell's nodes: the traces on a piece's sides lie in its cell, and
// the zero substitution at chord ends on dG sees u = w phi = 0 there.
template <int D, class Op>
Op fit(const Op& O, const std::array<VectorXd, D>& nodes,
       const std::function<double(const Eigen::Matrix<double, D, 1>&)>& w,
       const Eigen::Matrix<double, Eigen::Dynamic, D>& samples, TraceCriterion criterion,
       VectorXd* coefficients) {
  const Index S = samples.rows(), K = node_count<D>(nodes);
  MatrixXd A = MatrixXd::Zero(S, K);
  VectorXd r(S);
  Op Ok = O;
  for (Index i = 0; i < S; ++i) {
    const Eigen::Matrix<double, D, 1> p = samples.row(i).transpose();
    Ok.u = w;
    r(i) = w(p) - evaluate(Ok, p);
    std::array<Index, (1 << D)> id;
    std::array<double, (1 << D)> weight;
    hats<D>(nodes, p, id, weight);
    for (const Index k : id) {
      Ok.u = [&w, &nodes, k](const Eigen::Matrix<double, D, 1>& q) {
        std::array<Index, (1 << D)> qid;
        std::array<double, (1 << D)> qw;
        hats<D>(nodes, q, qid, qw);
        double phi = 0;
        for (size_t j = 0; j < qid.size(); ++j)
          phi += qid[j] == k ? qw[j] : 0.0;
        return phi == 0 ? 0.0 : w(q) * phi;
      };
      A(i, k) = evaluate(Ok, p);
    }
  }
  const VectorXd c = fit_trace_coefficients(A, r, criterion);
  if (coefficients)
    *coefficients = c;
  Op out = O;
  out.u = modulated<D>(w, nodes, c);
  return out;
}

VectorXd weighted_least_squares(const MatrixXd& A, const VectorXd& r, const VectorXd& v,
                                double ridge) {
  const Index K = A.cols();
  MatrixXd M(A.rows() + K, K);
  VectorXd b(A.rows() + K);
  M.topRows(A.rows()) = v.cwiseSqrt().asDiagonal() * A;
  M.bottomRows(K) = std::sqrt(ridge) * MatrixXd::Identity(K, K);
  b.head(A.rows()) = v.cwiseSqrt().cwiseProduct(r);
  b.tail(K).setZero();
  return M.colPivHouseholderQr().solve(b);
}

} // namespace

VectorXd fit_trace_coefficients(const MatrixXd& A, const VectorXd& r, TraceCriterion criterion) {
  if (A.rows() != r.size() || A.rows() == 0)
    throw std::invalid_argument("fit_trace_coefficients: A and r need the same, nonzero rows");
  const double scale = A.squaredNorm() / std::max<Index>(1, A.cols());
  const double ridge = kRidge * (scale > 0 ? scale : 1.0);
  VectorXd v = VectorXd::Constant(A.rows(), 1.0);
  VectorXd c = weighted_least_squares(A, r, v, ridge);
  if (criterion == TraceCriterion::least_squares)
    return c;
  // Lawson: weights grow where the residual is large; the best max-norm iterate is kept
  // (c = 0 included, so the naive choice bounds it on the samples).
  VectorXd best = VectorXd::Zero(A.cols());
  double best_max = r.cwiseAbs().maxCoeff();
  for (int it = 0; it < kLawsonIterations; ++it) {
    const VectorXd e = (A * c - r).cwiseAbs();
    if (e.maxCoeff() < best_max) {
      best_max = e.maxCoeff();
      best = c;
    }
    const VectorXd next = v.cwiseProduct(e);
    if (!(next.sum() > 0))
      break;
    v = next / next.sum() * static_cast<double>(A.rows());
    c = weighted_least_squares(A, r, v, ridge);
  }
  return best;
}

RegionInterlineation fit_free_traces(const RegionInterlineation& O,
                                     const std::function<double(const Eigen::Vector2d&)>& w,
                                     const Eigen::MatrixX2d& samples, TraceCriterion criterion,
                                     VectorXd* coefficients) {
  return fit<2>(O, {O.x, O.y}, w, samples, criterion, coefficients);
}

SolidInterflatation fit_free_traces(const SolidInterflatation& O,
                                    const std::function<double(const Eigen::Vector3d&)>& w,
                                    const Eigen::MatrixX3d& samples, TraceCriterion criterion,
                                    VectorXd* coefficients) {
  return fit<3>(O, O.nodes, w, samples, criterion, coefficients);
}

} // namespace interlin
