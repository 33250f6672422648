// CGAL Mesh_3 on an implicit function (the baseline of bench/volume_mesh_baseline.cpp).
#include "cgal_mesh_3.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/make_mesh_3.h>

#include <map>

namespace interlin::bench {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Domain = CGAL::Labeled_mesh_domain_3<K>;
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;

} // namespace

void cgal_mesh_3(const std::function<double(double, double, double)>& F,
                 const Eigen::Vector3d& centre, double radius, const CgalMeshOptions& o,
                 Eigen::MatrixXd& V, Eigen::MatrixXi& T, Eigen::MatrixXi& B) {
  namespace p = CGAL::parameters;
  // CGAL's implicit domains are { G < 0 }: G = -F.
  auto G = [&F](const K::Point_3& q) { return K::FT(-F(q.x(), q.y(), q.z())); };
  const Domain domain = Domain::create_implicit_mesh_domain(
      G, K::Sphere_3(K::Point_3(centre(0), centre(1), centre(2)), radius * radius),
      p::relative_error_bound = 1e-9);
  const Criteria criteria(p::facet_angle = o.facet_angle, p::facet_size = o.size,
                          p::facet_distance = o.facet_distance,
                          p::cell_radius_edge_ratio = o.radius_edge, p::cell_size = o.size);
  const C3t3 c3t3 =
      o.optimise ? CGAL::make_mesh_3<C3t3>(domain, criteria, p::odt(), p::perturb(), p::exude())
                 : CGAL::make_mesh_3<C3t3>(domain, criteria, p::no_perturb(), p::no_exude());
  std::map<Tr::Vertex_handle, int> index;
  auto id = [&](Tr::Vertex_handle v) { return index.emplace(v, int(index.size())).first->second; };
  T.resize(long(c3t3.number_of_cells_in_complex()), 4);
  long t = 0;
  for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c, ++t)
    for (int j = 0; j < 4; ++j)
      T(t, j) = id(c->vertex(j));
  B.resize(long(c3t3.number_of_facets_in_complex()), 3);
  long b = 0;
  for (auto f = c3t3.facets_in_complex_begin(); f != c3t3.facets_in_complex_end(); ++f, ++b)
    for (int j = 0, k = 0; j < 4; ++j)
      if (j != f->second)
        B(b, k++) = id(f->first->vertex(j));
  V.resize(long(index.size()), 3);
  for (const auto& [v, i] : index)
    V.row(i) << v->point().x(), v->point().y(), v->point().z();
}

} // namespace interlin::bench
