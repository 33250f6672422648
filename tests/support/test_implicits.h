#pragma once
// Implicit test bodies in closed form (F > 0 inside), written inline with R-functions, for the
// implicit -> mesh tests: sphere and torus (known volume and area), an R0 cube (sharp edges), and
// seed 003's test body (11). Also meshing with the check report, and the mesh comparison "equal
// up to vertex order".

#include "interlin/interflatation/implicit_function.h"
#include "interlin/reconstruction/meshing/implicit_mesh.h"
#include "interlin/reconstruction/meshing/mesh_check.h"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace interlin::test {

// An ImplicitFunction from a point callable double(double x, double y, double z).
template <class Fn>
ImplicitFunction implicit(Fn fn, const Eigen::AlignedBox3d& box) {
  ImplicitFunction f;
  f.value = [fn](const Eigen::Ref<const Points3>& P, Eigen::Ref<Eigen::VectorXd> F) {
    for (Eigen::Index i = 0; i < P.rows(); ++i)
      F(i) = fn(P(i, 0), P(i, 1), P(i, 2));
  };
  f.box = box;
  return f;
}

inline Eigen::AlignedBox3d cube_box(double a) {
  return {Eigen::Vector3d::Constant(-a), Eigen::Vector3d::Constant(a)};
}

// Seed 003's R0 operations (digest §3.1).
inline double r0_and(double a, double b) {
  return a + b - std::sqrt(a * a + b * b);
}
inline double r0_or(double a, double b) {
  return a + b + std::sqrt(a * a + b * b);
}

// A thin wall: the slab |n . p| <= T / 2 (n a unit normal) AND the unit ball (R0); box +-1.1.
inline ImplicitFunction thin_disc(const Eigen::Vector3d& n, double T) {
  return implicit(
      [n, T](double x, double y, double z) {
        const double s = n.dot(Eigen::Vector3d(x, y, z));
        return r0_and(T * T / 4 - s * s, 1 - x * x - y * y - z * z);
      },
      cube_box(1.1));
}

// thin_disc's exact volume, pi (T - T^3 / 12) (the ball's slice between -T/2 and T/2).
inline double thin_disc_volume(double T) {
  return M_PI * (T - T * T * T / 12);
}

// Ball of radius r at the origin: 1 - |p|^2 / r^2, with its exact gradient; box +-1.1 r.
inline ImplicitFunction sphere(double r) {
  ImplicitFunction f =
      implicit([r](double x, double y, double z) { return 1 - (x * x + y * y + z * z) / (r * r); },
               cube_box(1.1 * r));
  f.gradient = [r](const Eigen::Ref<const Points3>& P, Eigen::Ref<Eigen::VectorXd> F,
                   Eigen::Ref<Points3> G) {
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      F(i) = 1 - P.row(i).squaredNorm() / (r * r);
      G.row(i) = -2 * P.row(i) / (r * r);
    }
  };
  return f;
}

// Torus about z, radii R > r: r^2 - (sqrt(x^2 + y^2) - R)^2 - z^2. Volume 2 pi^2 R r^2, area
// 4 pi^2 R r, genus 1.
inline ImplicitFunction torus(double R, double r) {
  return implicit(
      [R, r](double x, double y, double z) {
        const double q = std::sqrt(x * x + y * y) - R;
        return r * r - q * q - z * z;
      },
      Eigen::AlignedBox3d(Eigen::Vector3d(-R - 1.2 * r, -R - 1.2 * r, -1.2 * r),
                          Eigen::Vector3d(R + 1.2 * r, R + 1.2 * r, 1.2 * r)));
}

// Cube [-a, a]^3 as the R0 conjunction of three slabs (sharp edges and corners).
inline ImplicitFunction r0_cube(double a) {
  return implicit(
      [a](double x, double y, double z) {
        return r0_and(r0_and(a * a - x * x, a * a - y * y), a * a - z * z);
      },
      cube_box(1.2 * a));
}

// Seed 003 example (11) (digest §5.2, seed code's script): cuboid(2,2,2) AND sphere(R) minus the
// three cylinders of radius 0.5 along the axes, R0 operations, band(x, w) = 1 - 4x^2/w^2, left
// folds as in the seed's con/diff. R = 1.3 reproduces the published counts. Genus 5.
inline double body11(double x, double y, double z, double R = 1.3) {
  auto band = [](double t, double w) { return 1 - 4 * t * t / (w * w); };
  const double cuboid = r0_and(r0_and(band(x, 2), band(y, 2)), band(z, 2));
  double w = r0_and(cuboid, 1 - (x * x + y * y + z * z) / (R * R));
  w = r0_and(w, -(0.25 - x * x - y * y));
  w = r0_and(w, -(0.25 - x * x - z * z));
  return r0_and(w, -(0.25 - y * y - z * z));
}

inline ImplicitFunction body11_function(double R = 1.3) {
  return implicit([R](double x, double y, double z) { return body11(x, y, z, R); }, cube_box(1.0));
}

// implicit_mesh of f with options o, its info, and check_mesh of the result.
struct CheckedMesh {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  ImplicitMeshInfo info;
  MeshReport report;
};

inline CheckedMesh checked_mesh(const ImplicitFunction& f, const ImplicitMeshOptions& o) {
  CheckedMesh m;
  implicit_mesh(f, o, m.V, m.F, &m.info);
  m.report = check_mesh(m.V, m.F);
  return m;
}

// The default options with `resolution` cells along the box's longest side.
inline ImplicitMeshOptions at_resolution(int resolution) {
  ImplicitMeshOptions o;
  o.resolution = resolution;
  return o;
}

// Triangle meshes equal up to a renumbering of the vertices (positions compared exactly) and
// the order of the faces (each face compared as an oriented cycle).
inline bool same_mesh_up_to_order(const Eigen::MatrixXd& V1, const Eigen::MatrixXi& F1,
                                  const Eigen::MatrixXd& V2, const Eigen::MatrixXi& F2) {
  if (V1.rows() != V2.rows() || F1.rows() != F2.rows())
    return false;
  using P3 = std::array<double, 3>;
  auto faces = [](const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
    std::vector<std::array<P3, 3>> out;
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      std::array<P3, 3> t;
      for (int j = 0; j < 3; ++j)
        t[size_t(j)] = {V(F(f, j), 0), V(F(f, j), 1), V(F(f, j), 2)};
      std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
      out.push_back(t);
    }
    std::sort(out.begin(), out.end());
    return out;
  };
  auto points = [](const Eigen::MatrixXd& V) {
    std::vector<P3> out;
    for (Eigen::Index i = 0; i < V.rows(); ++i)
      out.push_back({V(i, 0), V(i, 1), V(i, 2)});
    std::sort(out.begin(), out.end());
    return out;
  };
  return points(V1) == points(V2) && faces(V1, F1) == faces(V2, F2);
}

} // namespace interlin::test
