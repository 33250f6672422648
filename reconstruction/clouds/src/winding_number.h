#pragma once
// Private to reconstruction/clouds: the generalized winding number of an oriented point cloud
// (Barill, Dickson, Schmidt, Levin, Jacobson, "Fast winding numbers for soups and clouds", ACM
// Trans. Graph. 37(4), SIGGRAPH 2018, eq. 6 for points, §3.2 for the far-field expansion):
//
//   w(q) = sum_i a_i n_i . (p_i - q) / (4 pi |p_i - q|^3),
//
// the solid angle the oriented surface elements a_i n_i subtend at q over 4 pi: about 1 inside
// a closed cloud with outward normals, 0 outside, whatever the shape (thin walls included, where
// the nearest normals alone cannot tell the side). Clusters of a uniform grid farther than
// kFarRatio times their radius count as one dipole (sum of a_i n_i at their area centroid),
// Barill et al.'s first-order tree expansion on a two-level tree (clusters of 4 x 4 x 4 cells,
// then the cells).

#include <Eigen/Core>
#include <vector>

namespace interlin::detail {

class WindingNumber {
public:
  // P, N #P by 3 (unit outward normals), area #P: the surface area each point stands for.
  WindingNumber(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& N, const Eigen::VectorXd& area);
  double operator()(const Eigen::Vector3d& q) const;

private:
  struct Cluster {
    // area centroid, sum a_i n_i
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero(), dipole = Eigen::Vector3d::Zero();
    double area = 0, radius = 0; // sum a_i; largest distance of a member from the centroid
    int begin = 0, end = 0;      // members: rows [begin, end) of P_, D_ (of clusters_ for
                                 // a super-cluster)
  };
  std::vector<Cluster> clusters_; // grouped by super-cluster
  std::vector<Cluster> supers_;
  Eigen::MatrixX3d P_, D_; // points and a_i n_i, grouped by cluster
};

// The k of point_areas, for every caller's knn.
constexpr int kAreaNeighbours = 8;

// The area each point stands for: pi r^2 / k with r the distance to its k-th nearest neighbour
// (the disc through the k nearest points holds about k points' shares); knn: #P by
// kAreaNeighbours (or fewer for a tiny cloud).
Eigen::VectorXd point_areas(const Eigen::MatrixX3d& P, const Eigen::MatrixXi& knn);

// True when the normals N point into the body: outward normals make sum a_i n_i . (p_i - c) =
// 3 x the volume > 0 for any closed surface and any centre c (divergence theorem; c: the
// centroid, a: point_areas).
bool normals_inward(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& N,
                    const Eigen::VectorXd& area);

// The median of sqrt(area per point): the point spacing.
double median_spacing(const Eigen::VectorXd& area);

} // namespace interlin::detail
