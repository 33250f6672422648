#include "surface_distance.h"

#include "interlin/reconstruction/meshing/parallel_for.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <vector>

namespace interlin::bench {

namespace {
using K = CGAL::Simple_cartesian<double>;
using Triangles = std::vector<K::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;
} // namespace

struct MeshDistance::Impl {
  Triangles triangles;
  Tree tree;
};

MeshDistance::MeshDistance(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F)
    : impl_(std::make_unique<Impl>()) {
  auto p = [&](Eigen::Index i) { return K::Point_3(V(i, 0), V(i, 1), V(i, 2)); };
  impl_->triangles.reserve(static_cast<size_t>(F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const K::Triangle_3 t(p(F(f, 0)), p(F(f, 1)), p(F(f, 2)));
    if (!t.is_degenerate())
      impl_->triangles.push_back(t);
  }
  impl_->tree.rebuild(impl_->triangles.cbegin(), impl_->triangles.cend());
  impl_->tree.accelerate_distance_queries();
}

MeshDistance::~MeshDistance() = default;

Eigen::VectorXd MeshDistance::operator()(const Eigen::MatrixX3d& P) const {
  Eigen::VectorXd d(P.rows());
  // The first query builds the tree's internal search structure; later ones only read it.
  if (P.rows() > 0)
    d(0) = std::sqrt(impl_->tree.squared_distance(K::Point_3(P(0, 0), P(0, 1), P(0, 2))));
  detail::parallel_for(static_cast<long>(P.rows()), 2, [&](long i, int) {
    d(i) = std::sqrt(impl_->tree.squared_distance(K::Point_3(P(i, 0), P(i, 1), P(i, 2))));
  });
  return d;
}

} // namespace interlin::bench
