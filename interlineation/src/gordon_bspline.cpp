// digest 001 §5.1 [SUPPLEMENT]: Gordon surface of B-spline curve networks as one B-spline.
#include "interlin/interlineation/gordon_bspline.h"

#include "interlin/interlineation/cardinal_splines.h"
#include "interlin/interlineation/spline_space.h"
#include "interlin/splines/knot_insertion.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// All curves of a family: same degree, clamped, same domain, 3-D.
void check_family(const std::vector<BSplineCurve>& cs, const char* name, double a, double b) {
  for (size_t k = 0; k < cs.size(); ++k) {
    const BSplineCurve& c = cs[k];
    const Index n = c.ctrl.rows();
    if (c.periodic || c.degree != cs[0].degree || c.ctrl.cols() != 3 ||
        c.knots.size() != n + c.degree + 1 || c.knots(c.degree) != a || c.knots(n) != b)
      throw std::invalid_argument(std::string("Gordon surface: ") + name + " " + std::to_string(k) +
                                  " must be a clamped 3-D curve of the family's degree on [" +
                                  std::to_string(a) + ", " + std::to_string(b) + "]");
  }
}

// Curves on their knot union: all refined to one knot vector (any dimensions). Knots of
// different curves closer than 1e-12 of the domain (the same value computed two ways, e.g. two
// averages of equal parameters) are first made equal: otherwise the union would hold spans of a
// few ulps, on which the explicit basis loses its accuracy (docs/formulas.md, span ratios); the
// curves move by far less than round-off of their values.
std::vector<BSplineCurve> on_union(std::vector<BSplineCurve> cs) {
  std::vector<double> all;
  for (const BSplineCurve& c : cs)
    all.insert(all.end(), c.knots.data(), c.knots.data() + c.knots.size());
  std::sort(all.begin(), all.end());
  const double tol = 1e-12 * (all.back() - all.front());
  for (BSplineCurve& c : cs)
    for (Index i = 0; i < c.knots.size(); ++i) {
      // Representative: the smallest value of the cluster (chain of gaps <= tol) holding knot i.
      auto it = std::lower_bound(all.begin(), all.end(), c.knots(i));
      while (it != all.begin() && *it - *(it - 1) <= tol)
        --it;
      c.knots(i) = *it;
    }
  std::vector<VectorXd> kv;
  for (const BSplineCurve& c : cs)
    kv.push_back(c.knots);
  const VectorXd U = knot_union(kv);
  for (BSplineCurve& c : cs) {
    std::vector<double> add;
    Index i = 0;
    for (Index j = 0; j < U.size(); ++j) {
      if (i < c.knots.size() && c.knots(i) == U(j))
        ++i;
      else
        add.push_back(U(j));
    }
    c = refine_knots(c, Eigen::Map<const VectorXd>(add.data(), static_cast<Index>(add.size())));
  }
  return cs;
}

} // namespace

BSplineSurface gordon_bspline(const std::vector<BSplineCurve>& sections, const VectorXd& v,
                              const std::vector<BSplineCurve>& guides, const VectorXd& u,
                              int degree_v, bool closed_u, double tol, const VectorXd& knots_v) {
  const Index K = static_cast<Index>(sections.size()), L = static_cast<Index>(guides.size());
  if (K < 2 || v.size() != K)
    throw std::invalid_argument("Gordon surface: at least 2 sections, one parameter v_k each");
  if (u.size() != L)
    throw std::invalid_argument("Gordon surface: one parameter u_l per guide");
  if (degree_v < 1)
    throw std::invalid_argument("Gordon surface: blending degree must be >= 1");
  const int p = sections[0].degree;
  const Index n0 = sections[0].ctrl.rows();
  const double u0 = sections[0].knots(p), u1 = sections[0].knots(n0);
  check_family(sections, "section", u0, u1);
  check_family(guides, "guide", v(0), v(K - 1));
  for (Index l = 0; l < L; ++l)
    if (!(u(l) >= u0 && (closed_u ? u(l) < u1 : u(l) <= u1)))
      throw std::invalid_argument("Gordon surface: guide parameter u_" + std::to_string(l) +
                                  " lies outside the sections' domain");
  if (!closed_u && L >= 2 && (u(0) != u0 || u(L - 1) != u1))
    throw std::invalid_argument("Gordon surface: open sections need guides at both ends of the "
                                "sections' domain (u_0 = u0, u_last = u1)");

  // Intersection points Q_kl from both families, which must agree.
  MatrixXd Q(K * L, 3);
  for (Index l = 0; l < L; ++l) {
    const MatrixXd G = evaluate(guides[static_cast<size_t>(l)], v);
    for (Index k = 0; k < K; ++k) {
      const Eigen::RowVector3d c =
          evaluate(sections[static_cast<size_t>(k)], VectorXd::Constant(1, u(l))).row(0);
      const double gap = (c - G.row(k)).norm();
      if (gap > tol * std::max(1.0, c.norm()))
        throw std::invalid_argument(
            "Gordon surface: section " + std::to_string(k) + " and guide " + std::to_string(l) +
            " do not meet: " + "|C_k(u_l) - G_l(v_k)| = " + std::to_string(gap));
      Q.row(k + K * l) = 0.5 * (c + G.row(k));
    }
  }

  // Blending functions as curves with K (beta) and L (alpha) components, at the surface degrees.
  const int q = L > 0 ? std::max(guides[0].degree, std::min<int>(degree_v, K - 1))
                      : std::min<int>(degree_v, K - 1);
  const int qb = std::min<int>(degree_v, K - 1);
  const BSplineCurve beta = knots_v.size() == 0
                                ? cardinal_splines(v, qb).curve
                                : interpolate_in_space(MatrixXd::Identity(K, K), v, knots_v, qb);
  std::vector<BSplineCurve> vfam = {elevate_degree(beta, q)};
  for (const BSplineCurve& g : guides)
    vfam.push_back(elevate_degree(g, q));
  std::vector<BSplineCurve> ufam = sections;
  if (L > 0) {
    BSplineCurve alpha;
    if (closed_u) {
      alpha = periodic_cardinal_splines(u, u0, u1 - u0, p >= 3 ? 3 : 1).curve;
      alpha.knots.tail(alpha.degree + 1).setConstant(u1); // u0 + (u1 - u0) may round off u1
    } else if (L == 1) {
      alpha.degree = 1; // alpha_0 = 1
      alpha.knots.resize(4);
      alpha.knots << u0, u0, u1, u1;
      alpha.ctrl = MatrixXd::Ones(2, 1);
    } else {
      alpha = cardinal_splines(u, std::min<int>(p, L - 1)).curve;
    }
    ufam.push_back(elevate_degree(alpha, p));
  }
  ufam = on_union(ufam);
  vfam = on_union(vfam);
  const MatrixXd& B = vfam[0].ctrl; // nv by K: beta control values
  const Index nu = ufam[0].ctrl.rows(), nv = B.rows();

  // Net(i, j) = sum_k B(j,k) C_k(i) + sum_l A(i,l) G_l(j) - sum_{k,l} A(i,l) B(j,k) Q_kl.
  MatrixXd net = MatrixXd::Zero(nu * nv, 3);
  for (Index j = 0; j < nv; ++j)
    for (Index k = 0; k < K; ++k)
      net.middleRows(nu * j, nu) += B(j, k) * ufam[static_cast<size_t>(k)].ctrl;
  if (L > 0) {
    const MatrixXd& A = ufam[static_cast<size_t>(K)].ctrl; // nu by L
    for (Index l = 0; l < L; ++l) {
      const MatrixXd& G = vfam[static_cast<size_t>(l + 1)].ctrl; // nv by 3
      // The guide minus the v-blend of its intersection points, spread along u by alpha_l.
      MatrixXd D = G;
      for (Index k = 0; k < K; ++k)
        D -= B.col(k) * Q.row(k + K * l);
      for (Index j = 0; j < nv; ++j)
        net.middleRows(nu * j, nu) += A.col(l) * D.row(j);
    }
  }
  BSplineSurface S;
  S.degree_u = p;
  S.degree_v = q;
  S.knots_u = ufam[0].knots;
  S.knots_v = vfam[0].knots;
  S.num_u = nu;
  S.num_v = nv;
  S.ctrl = net;
  S.closed_u = closed_u;
  return S;
}

} // namespace interlin
