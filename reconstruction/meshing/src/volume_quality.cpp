// Element quality of tetrahedra and hexahedra (Knupp's / Verdict's definitions).
#include "interlin/reconstruction/meshing/volume_quality.h"

#include "interlin/reconstruction/meshing/volume_smoothing.h"

#include "corner_jacobian.h"
#include "parallel.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace interlin {

namespace {

using Vec3 = Eigen::Vector3d;
constexpr double kPi = 3.14159265358979323846;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Vec3 pt(const Eigen::MatrixXd& P, int i) {
  return P.row(i).transpose();
}

// Interior dihedral angle (degrees) between two faces with outward normals n1, n2 (any length);
// 0 when a normal vanishes (a degenerate face: counted as the worst angle).
double dihedral(const Vec3& n1, const Vec3& n2) {
  const double l = n1.norm() * n2.norm();
  if (!(l > 0))
    return 0;
  return 180 - std::acos(std::clamp(n1.dot(n2) / l, -1.0, 1.0)) * 180 / kPi;
}

void tetrahedron(const Eigen::MatrixXd& P, ElementQuality& q) {
  const Vec3 p[4] = {pt(P, 0), pt(P, 1), pt(P, 2), pt(P, 3)};
  const double six_v = (p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0]);
  q.volume = six_v / 6;
  q.inverted = !(six_v > 0);
  // Outward face normals (face opposite vertex i), for a positive tetrahedron.
  constexpr int face[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  Vec3 n[4];
  double area = 0;
  for (int i = 0; i < 4; ++i) {
    n[i] = (p[face[i][1]] - p[face[i][0]]).cross(p[face[i][2]] - p[face[i][0]]);
    area += 0.5 * n[i].norm();
  }
  // Edge (a, b) lies on the faces opposite the two other vertices.
  q.min_dihedral_deg = 180, q.max_dihedral_deg = 0;
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b) {
      int o[2], k = 0;
      for (int c = 0; c < 4; ++c)
        if (c != a && c != b)
          o[k++] = c;
      const double d = dihedral(n[o[0]], n[o[1]]);
      q.min_dihedral_deg = std::min(q.min_dihedral_deg, d);
      q.max_dihedral_deg = std::max(q.max_dihedral_deg, d);
    }
  double longest_product = 0;
  for (int j = 0; j < 4; ++j) {
    double prod = 1;
    for (int k = 0; k < 4; ++k)
      if (k != j)
        prod *= (p[k] - p[j]).norm();
    longest_product = std::max(longest_product, prod);
  }
  q.scaled_jacobian = longest_product > 0 ? std::sqrt(2.0) * six_v / longest_product : 0;
  // r_in = 3 V / area; R = |a^2 (b x c) + b^2 (c x a) + c^2 (a x b)| / (12 V) with edges from p0.
  const Vec3 a = p[1] - p[0], b = p[2] - p[0], c = p[3] - p[0];
  const double R12V =
      (a.squaredNorm() * b.cross(c) + b.squaredNorm() * c.cross(a) + c.squaredNorm() * a.cross(b))
          .norm();
  // 3 r / R = 3 (3V / area) (12 V / R12V) = 108 V^2 / (area R12V) = 3 six_v^2 / (area R12V).
  q.radius_ratio = area > 0 && R12V > 0 ? 3 * six_v * six_v / (area * R12V) : 0;
  if (six_v <= 0)
    q.radius_ratio = 0;
}

// Exact volume of the trilinear hexahedron: det J has degree <= 2 in each reference coordinate,
// so the 2-point Gauss rule per axis integrates it exactly.
double hex_volume(const Vec3 p[8]) {
  const double g[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
  constexpr int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  double v = 0;
  for (double x : g)
    for (double y : g)
      for (double z : g) {
        Vec3 d[3] = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
        for (int c = 0; c < 8; ++c) {
          const double w[3] = {corner[c][0] ? x : 1 - x, corner[c][1] ? y : 1 - y,
                               corner[c][2] ? z : 1 - z};
          const double s[3] = {corner[c][0] ? 1.0 : -1.0, corner[c][1] ? 1.0 : -1.0,
                               corner[c][2] ? 1.0 : -1.0};
          d[0] += s[0] * w[1] * w[2] * p[c];
          d[1] += s[1] * w[0] * w[2] * p[c];
          d[2] += s[2] * w[0] * w[1] * p[c];
        }
        v += d[0].cross(d[1]).dot(d[2]) / 8;
      }
  return v;
}

void hexahedron(const Eigen::MatrixXd& P, ElementQuality& q) {
  Vec3 p[8];
  for (int i = 0; i < 8; ++i)
    p[i] = pt(P, i);
  static const Eigen::MatrixXi T = corner_table(8);
  const detail::CornerJacobian corners = detail::corner_scaled_jacobian(p, T);
  q.scaled_jacobian = corners.min_scaled;
  // Centre: the principal axes (Verdict); folded there counts as inverted, as at a corner.
  const std::array<Vec3, 3> x = detail::centre_axes(p);
  const double l = x[0].norm() * x[1].norm() * x[2].norm();
  const double centre = x[0].cross(x[1]).dot(x[2]);
  q.scaled_jacobian = std::min(q.scaled_jacobian, l > 0 ? centre / l : 0.0);
  q.inverted = corners.inverted || !(centre > 0);
  q.volume = hex_volume(p);
  q.radius_ratio = kNaN;
  // Faces counter-clockwise seen from outside; each edge's two faces compared at both ends with
  // the faces' corner normals there (faces need not be planar).
  constexpr int face[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                              {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  auto corner_normal = [&](int f, int v) {
    int k = 0;
    while (face[f][k] != v)
      ++k;
    const Vec3& a = p[v];
    return Vec3((p[face[f][(k + 1) % 4]] - a).cross(p[face[f][(k + 3) % 4]] - a));
  };
  q.min_dihedral_deg = 180, q.max_dihedral_deg = 0;
  for (int f = 0; f < 6; ++f)
    for (int k = 0; k < 4; ++k) {
      const int a = face[f][k], b = face[f][(k + 1) % 4];
      for (int g = f + 1; g < 6; ++g) {
        bool has_a = false, has_b = false;
        for (int m = 0; m < 4; ++m)
          has_a = has_a || face[g][m] == a, has_b = has_b || face[g][m] == b;
        if (!has_a || !has_b)
          continue;
        for (int v : {a, b}) {
          const double d = dihedral(corner_normal(f, v), corner_normal(g, v));
          q.min_dihedral_deg = std::min(q.min_dihedral_deg, d);
          q.max_dihedral_deg = std::max(q.max_dihedral_deg, d);
        }
      }
    }
}

} // namespace

ElementQuality element_quality(const Eigen::MatrixXd& P) {
  if (P.cols() != 3 || (P.rows() != 4 && P.rows() != 8))
    throw std::invalid_argument("element_quality: P must be 4 by 3 or 8 by 3");
  ElementQuality q;
  if (P.rows() == 4)
    tetrahedron(P, q);
  else
    hexahedron(P, q);
  return q;
}

VolumeQuality volume_quality(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C, int threads,
                             std::vector<ElementQuality>* per_element) {
  if (V.cols() != 3 || (C.cols() != 4 && C.cols() != 8))
    throw std::invalid_argument("volume_quality: V must be #V by 3 and C #C by 4 or #C by 8");
  if (C.size() > 0 && (C.minCoeff() < 0 || C.maxCoeff() >= V.rows()))
    throw std::invalid_argument("volume_quality: element index out of range");
  std::vector<ElementQuality> local;
  std::vector<ElementQuality>& q = per_element ? *per_element : local;
  q.assign(size_t(C.rows()), ElementQuality{});
  constexpr long kChunk = 4096;
  detail::parallel_chunks(C.rows(), kChunk, threads, [&](long, long e0, long e1) {
    Eigen::MatrixXd P(C.cols(), 3);
    for (long e = e0; e < e1; ++e) {
      for (long j = 0; j < C.cols(); ++j)
        P.row(j) = V.row(C(e, j));
      q[size_t(e)] = element_quality(P);
    }
  });
  VolumeQuality s;
  s.elements = C.rows();
  if (C.rows() == 0)
    return s;
  s.min_dihedral_deg = 180, s.max_dihedral_deg = 0;
  s.min_scaled_jacobian = std::numeric_limits<double>::infinity();
  s.min_radius_ratio = C.cols() == 4 ? std::numeric_limits<double>::infinity() : kNaN;
  s.mean_radius_ratio = C.cols() == 4 ? 0 : kNaN;
  for (const ElementQuality& e : q) {
    s.inverted += e.inverted;
    s.volume += e.volume;
    s.min_dihedral_deg = std::min(s.min_dihedral_deg, e.min_dihedral_deg);
    s.max_dihedral_deg = std::max(s.max_dihedral_deg, e.max_dihedral_deg);
    s.outside_10_170 += e.min_dihedral_deg < 10 || e.max_dihedral_deg > 170;
    s.min_scaled_jacobian = std::min(s.min_scaled_jacobian, e.scaled_jacobian);
    s.mean_scaled_jacobian += e.scaled_jacobian / double(C.rows());
    if (C.cols() == 4) {
      s.min_radius_ratio = std::min(s.min_radius_ratio, e.radius_ratio);
      s.mean_radius_ratio += e.radius_ratio / double(C.rows());
    }
  }
  return s;
}

} // namespace interlin
