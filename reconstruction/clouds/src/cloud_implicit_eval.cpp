// Evaluation of the partition-of-unity implicit (cloud_implicit.h): an octree rebuilt from the
// leaves' addresses, and per leaf the list of leaves whose support ball meets its cube.
#include "interlin/reconstruction/clouds/cloud_implicit.h"

#include "local_fit.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace interlin {

using Eigen::Index;
using Eigen::Vector3d;

double local_fit_value(const LocalFit& f, const Vector3d& x, Vector3d* gradient) {
  return detail::fit_value(f, x, gradient);
}

namespace {

// The fits' octree addresses must tile the root cube and every ball must cover its cell: then
// every point of the cube lies in some support ball. Throws std::invalid_argument otherwise (a
// model read from a file is checked before use).
void check_tiling(const CloudImplicit& m) {
  struct Node {
    int child = -1;
    bool leaf = false;
  };
  std::vector<Node> nodes(1);
  for (size_t i = 0; i < m.fits.size(); ++i) {
    const LocalFit& f = m.fits[i];
    const std::string which = "cloud implicit: leaf " + std::to_string(i);
    if (f.level < 0 || f.level > 30 || (f.cell < 0).any() || (f.cell >= (1 << f.level)).any())
      throw std::invalid_argument(which + " has an invalid octree address");
    const double side = m.size / double(1 << f.level);
    const Vector3d centre = m.origin + side * (f.cell.cast<double>() + 0.5).matrix();
    if (!(f.radius >= 0.5 * std::sqrt(3.0) * side * (1 - 1e-12)) ||
        (f.centre - centre).norm() > 1e-9 * side)
      throw std::invalid_argument(which + ": its ball does not cover its cell");
    size_t n = 0;
    for (int l = 0; l < f.level; ++l) {
      if (nodes[n].leaf)
        throw std::invalid_argument(which + " lies inside another leaf");
      if (nodes[n].child < 0) {
        nodes[n].child = static_cast<int>(nodes.size());
        nodes.resize(nodes.size() + 8);
      }
      const int shift = f.level - 1 - l;
      n = static_cast<size_t>(nodes[n].child + (((f.cell(0) >> shift) & 1) |
                                                (((f.cell(1) >> shift) & 1) << 1) |
                                                (((f.cell(2) >> shift) & 1) << 2)));
    }
    if (nodes[n].leaf || nodes[n].child >= 0)
      throw std::invalid_argument(which + " overlaps another leaf");
    nodes[n].leaf = true;
  }
  for (const Node& n : nodes)
    if (n.child < 0 && !n.leaf)
      throw std::invalid_argument("cloud implicit: the leaves do not tile the root cube");
}

// Evaluation: a lookup octree over the root cube whose leaves list the support balls meeting
// them. A lookup node is split while it meets more than kMaxList balls (down to a quarter of
// the smallest fit cell), so a point costs one descent and a short loop whatever the sizes of
// the fit cells around it. The descent starts from a table of the nodes of level kTableLevel
// (random points in the box otherwise miss the cache at every level of the tree).
class Evaluator {
public:
  explicit Evaluator(std::shared_ptr<const CloudImplicit> m) : m_(std::move(m)) {
    check_tiling(*m_);
    balls_.reserve(m_->fits.size());
    int finest = 0;
    for (const LocalFit& f : m_->fits) {
      balls_.push_back(
          {f.centre(0), f.centre(1), f.centre(2), f.radius * f.radius, 1 / (f.radius * f.radius)});
      finest = std::max(finest, f.level);
    }
    build_lookup(finest + 2);
    build_table();
  }

  // F (and its gradient when g is not null) at x.
  double value(const Vector3d& x, Vector3d* g) const {
    const Vector3d lo = m_->origin, hi = lo + Vector3d::Constant(m_->size);
    const Vector3d c = x.cwiseMax(lo).cwiseMin(hi);
    if (c == x)
      return inside(x, g);
    // Outside the root cube: F(x') - |x - x'| (continuous, decreasing away from the cube).
    const Vector3d d = x - c;
    const double dist = d.norm();
    const double f = inside(c, g) - dist;
    if (g) {
      for (int a = 0; a < 3; ++a)
        if (d(a) != 0)
          (*g)(a) = 0; // F(x') does not change along the clamped axes
      *g -= d / dist;
    }
    return f;
  }

  // +1 (-1) when F is certainly > 0 (< 0) on the closed box B, else 0: F is a weighted mean of
  // the local functions whose support balls contain the point (positive weights), so it has the
  // sign that all the local functions meeting B certainly have on B. Outside the root cube
  // F(x) = F(x') - |x - x'| keeps only a negative sign.
  int sign_on(const Eigen::AlignedBox3d& B) const {
    const Eigen::AlignedBox3d cube(m_->origin, m_->origin + Vector3d::Constant(m_->size));
    const Eigen::AlignedBox3d C = B.intersection(cube);
    if (C.isEmpty())
      return 0;
    // A ball listed by several lookup leaves is bounded once: marked with this call's stamp.
    thread_local std::vector<unsigned> seen;
    thread_local unsigned stamp = 0;
    if (seen.size() < balls_.size() || ++stamp == 0) {
      seen.assign(std::max(seen.size(), balls_.size()), 0);
      stamp = 1;
    }
    int sign = 0;
    // stops at the first fit without a sign or with the other one
    const bool one_sign = visit(0, m_->origin, m_->size, C, [&](int j) {
      if (seen[size_t(j)] == stamp)
        return true;
      seen[size_t(j)] = stamp;
      const Ball& b = balls_[static_cast<size_t>(j)];
      const Vector3d c(b.x, b.y, b.z);
      if (C.squaredExteriorDistance(c) >= b.r2)
        return true; // the ball misses C: its weight is 0 there
      // the fit's weight is 0 outside its ball: its sign matters on C and the ball's cube only
      const Vector3d r = Vector3d::Constant(std::sqrt(b.r2));
      const Eigen::AlignedBox3d D = C.intersection(Eigen::AlignedBox3d(c - r, c + r));
      const int s = detail::fit_sign_on_box(m_->fits[static_cast<size_t>(j)], D);
      if (s == 0 || (sign != 0 && s != sign))
        return false;
      sign = s;
      return true;
    });
    if (!one_sign)
      return 0;
    return sign < 0 || cube.contains(B) ? sign : 0;
  }

private:
  // 32: the valve's 88,000 fits made 930,000 lookup nodes at 16 (their build 8 % of the fit and
  // mesh time); at 32 fit + mesh take 0.91 x (the plate 0.88 x) for a few more distance tests per
  // point; 48 gains no more (docs/benchmarks.md, session 12).
  static constexpr size_t kMaxList = 32;
  static constexpr int kTableLevel = 5; // 32^3 entries
  struct Ball {
    double x, y, z, r2, inv_r2;
  };
  struct Node {
    int child = -1;         // first of 8 children (octant bits x | y << 1 | z << 2), -1: a leaf
    int begin = 0, end = 0; // a leaf's balls: list_[begin, end)
  };
  std::shared_ptr<const CloudImplicit> m_;
  std::vector<Ball> balls_; // centre and squared radius of every support ball, packed
  std::vector<Node> nodes_;
  std::vector<int> list_;
  std::vector<int> table_; // node of level kTableLevel (or a leaf above it) per table cell

  // The closed cube [lo, lo + side]^3 meets the ball (with a relative margin of 1e-9 so that a
  // point on a shared face finds its ball from either side whatever the rounding of lo).
  static bool meets(const Ball& b, const Vector3d& lo, double side) {
    const Vector3d c(b.x, b.y, b.z);
    const Vector3d q = c.cwiseMax(lo).cwiseMin(lo + Vector3d::Constant(side));
    return (q - c).squaredNorm() < b.r2 * (1 + 1e-9);
  }

  void build_lookup(int max_level) {
    std::vector<int> all(balls_.size());
    for (size_t i = 0; i < all.size(); ++i)
      all[i] = static_cast<int>(i);
    struct Task {
      int node, level;
      Vector3d lo;
      std::vector<int> balls;
    };
    nodes_.push_back({});
    std::vector<Task> stack{{0, 0, m_->origin, std::move(all)}};
    while (!stack.empty()) {
      Task t = std::move(stack.back());
      stack.pop_back();
      if (t.balls.size() <= kMaxList || t.level >= max_level) {
        Node& n = nodes_[static_cast<size_t>(t.node)];
        n.begin = static_cast<int>(list_.size());
        list_.insert(list_.end(), t.balls.begin(), t.balls.end());
        n.end = static_cast<int>(list_.size());
        continue;
      }
      nodes_[static_cast<size_t>(t.node)].child = static_cast<int>(nodes_.size());
      const double h = m_->size / double(1 << (t.level + 1));
      std::array<Vector3d, 8> lo;
      std::array<std::vector<int>, 8> sub;
      for (int o = 0; o < 8; ++o)
        lo[size_t(o)] = t.lo + h * Vector3d(o & 1, (o >> 1) & 1, (o >> 2) & 1);
      const Vector3d mid = t.lo + Vector3d::Constant(h);
      for (int b : t.balls) {
        // only the octants the ball's bounding cube reaches (widened past meets' margin) are
        // tested: most balls are small and meet one
        const Ball& ball = balls_[static_cast<size_t>(b)];
        const double r = std::sqrt(ball.r2) * (1 + 1e-8);
        const Vector3d c(ball.x, ball.y, ball.z);
        for (int o = 0; o < 8; ++o) {
          bool reach = true;
          for (int a = 0; a < 3 && reach; ++a)
            reach = (o >> a) & 1 ? c(a) + r >= mid(a) : c(a) - r <= mid(a);
          if (reach && meets(ball, lo[size_t(o)], h))
            sub[size_t(o)].push_back(b);
        }
      }
      for (int o = 0; o < 8; ++o) {
        nodes_.push_back({});
        stack.push_back({static_cast<int>(nodes_.size()) - 1, t.level + 1, lo[size_t(o)],
                         std::move(sub[size_t(o)])});
      }
    }
  }

  void build_table() {
    const int G = 1 << kTableLevel;
    table_.resize(static_cast<size_t>(G) * G * G);
    for (int k = 0; k < G; ++k)
      for (int j = 0; j < G; ++j)
        for (int i = 0; i < G; ++i) {
          int n = 0;
          for (int l = 0; l < kTableLevel && nodes_[static_cast<size_t>(n)].child >= 0; ++l) {
            const int s = kTableLevel - 1 - l;
            n = nodes_[static_cast<size_t>(n)].child + ((i >> s) & 1) + (((j >> s) & 1) << 1) +
                (((k >> s) & 1) << 2);
          }
          table_[static_cast<size_t>((k * G + j) * G + i)] = n;
        }
  }

  // The lookup leaf holding x (x inside the root cube): the table, then descent. Always the same
  // leaf and list order for the same point, so values are bit-identical in every batch
  // (implicit_mesh relies on it).
  const Node& locate(const Vector3d& x) const {
    const int G = 1 << kTableLevel;
    double side = m_->size / G;
    Eigen::Array3i c = ((x - m_->origin) / side).array().floor().cast<int>();
    c = c.max(0).min(G - 1);
    int k = table_[static_cast<size_t>((c(2) * G + c(1)) * G + c(0))];
    Vector3d lo = m_->origin + side * c.cast<double>().matrix();
    while (nodes_[static_cast<size_t>(k)].child >= 0) {
      side *= 0.5;
      const Vector3d mid = lo.array() + side;
      const int o = int(x(0) >= mid(0)) + (int(x(1) >= mid(1)) << 1) + (int(x(2) >= mid(2)) << 2);
      lo += side * Vector3d(o & 1, (o >> 1) & 1, (o >> 2) & 1);
      k = nodes_[static_cast<size_t>(k)].child + o;
    }
    return nodes_[static_cast<size_t>(k)];
  }

  // Calls op(ball) for the balls listed by the lookup leaves that meet the box C (node: lo,
  // side) while op returns true; false when op did.
  template <class Op>
  bool visit(int node, const Vector3d& lo, double side, const Eigen::AlignedBox3d& C,
             Op&& op) const {
    const Eigen::AlignedBox3d cube(lo, lo + Vector3d::Constant(side));
    if (!cube.intersects(C))
      return true;
    const Node& n = nodes_[static_cast<size_t>(node)];
    if (n.child < 0) {
      for (int t = n.begin; t < n.end; ++t)
        if (!op(list_[static_cast<size_t>(t)]))
          return false;
      return true;
    }
    const double h = 0.5 * side;
    for (int o = 0; o < 8; ++o)
      if (!visit(n.child + o, lo + h * Vector3d(o & 1, (o >> 1) & 1, (o >> 2) & 1), h, C, op))
        return false;
    return true;
  }

  double inside(const Vector3d& x, Vector3d* g) const {
    const Node& leaf = locate(x);
    double sw = 0, swq = 0;
    Vector3d sgw = Vector3d::Zero(), sgq = Vector3d::Zero();
    for (int t = leaf.begin; t < leaf.end; ++t) {
      const int j = list_[static_cast<size_t>(t)];
      const Ball& b = balls_[static_cast<size_t>(j)];
      const double dx = x(0) - b.x, dy = x(1) - b.y, dz = x(2) - b.z;
      const double d2 = dx * dx + dy * dy + dz * dz;
      if (d2 >= b.r2)
        continue;
      const double r = std::sqrt(d2 * b.inv_r2);
      const double w = detail::wendland(r);
      Vector3d gq;
      const double q = detail::fit_value(m_->fits[static_cast<size_t>(j)], x, g ? &gq : nullptr);
      sw += w;
      swq += w * q;
      if (g) {
        const double a = (1 - r);
        const Vector3d gw =
            -20.0 * a * a * a * b.inv_r2 * Vector3d(dx, dy, dz); // grad psi(|x-c|/R)
        sgw += gw;
        sgq += gw * q + w * gq;
      }
    }
    if (!(sw > 0)) // cannot happen for a tiling model: the leaf's own ball covers its cube
      throw std::logic_error("cloud implicit: a point is covered by no support ball");
    const double F = swq / sw;
    if (g)
      *g = (sgq - F * sgw) / sw;
    return F;
  }
};

} // namespace

ImplicitFunction cloud_implicit_function(std::shared_ptr<const CloudImplicit> model) {
  if (!model || model->fits.empty())
    throw std::invalid_argument("cloud implicit: empty model");
  auto e = std::make_shared<const Evaluator>(model);
  ImplicitFunction f;
  f.box = model->box;
  f.value = [e](const Eigen::Ref<const Points3>& P, Eigen::Ref<Eigen::VectorXd> F) {
    for (Index i = 0; i < P.rows(); ++i)
      F(i) = e->value(P.row(i).transpose(), nullptr);
  };
  f.gradient = [e](const Eigen::Ref<const Points3>& P, Eigen::Ref<Eigen::VectorXd> F,
                   Eigen::Ref<Points3> G) {
    for (Index i = 0; i < P.rows(); ++i) {
      Vector3d g;
      F(i) = e->value(P.row(i).transpose(), &g);
      G.row(i) = g.transpose();
    }
  };
  f.sign_on_box = [e](const Eigen::AlignedBox3d& B) { return e->sign_on(B); };
  f.sample_spacing = model->spacing;
  return f;
}

} // namespace interlin
