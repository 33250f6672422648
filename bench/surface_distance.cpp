#include "surface_distance.h"

#include "interlin/reconstruction/meshing/parallel_for.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Simple_cartesian.h>

#include <vector>

namespace interlin::bench {

namespace {
using K = CGAL::Simple_cartesian<double>;
using Triangles = std::vector<K::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;
using Search = CGAL::Orthogonal_k_neighbor_search<CGAL::Search_traits_3<K>>;
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

Eigen::MatrixX3d MeshDistance::closest(const Eigen::MatrixX3d& P) const {
  Eigen::MatrixX3d C(P.rows(), 3);
  auto one = [&](long i) {
    const K::Point_3 c = impl_->tree.closest_point(K::Point_3(P(i, 0), P(i, 1), P(i, 2)));
    C.row(i) << c.x(), c.y(), c.z();
  };
  if (P.rows() > 0) // builds the search structure, as in operator()
    one(0);
  detail::parallel_for(static_cast<long>(P.rows()), 2, [&](long i, int) { one(i); });
  return C;
}

struct PointSetDistance::Impl {
  Search::Tree tree;
};

PointSetDistance::PointSetDistance(const Eigen::MatrixX3d& S) : impl_(std::make_unique<Impl>()) {
  for (Eigen::Index i = 0; i < S.rows(); ++i)
    impl_->tree.insert(K::Point_3(S(i, 0), S(i, 1), S(i, 2)));
  impl_->tree.build();
}

PointSetDistance::~PointSetDistance() = default;

Eigen::VectorXd PointSetDistance::operator()(const Eigen::MatrixX3d& P) const {
  Eigen::VectorXd d(P.rows());
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const Search search(impl_->tree, K::Point_3(P(i, 0), P(i, 1), P(i, 2)), 1);
    d(i) = std::sqrt(search.begin()->second);
  }
  return d;
}

} // namespace interlin::bench
