// Closest point on a triangle mesh: an axis-aligned bounding-box tree over the triangles.
//
// Build once, query many times (thread-safe queries). Used for ICP markers, surface distances and
// mesh comparisons everywhere later.
#pragma once

#include "vesalius/core/box_tree.h"
#include "vesalius/core/mesh.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

namespace vesalius {

struct ClosestPoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  int face = -1;
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();  // weights of F(face, 0..2)
  double squaredDistance = 0.0;
};

class TriangleTree {
 public:
  // V: #V by 3, F: #F by 3 (F must be non-empty). The tree keeps copies of both.
  TriangleTree(const MatrixX3d& V, const MatrixX3i& F);

  ClosestPoint closest(const Eigen::Vector3d& p) const;
  // One query per row of P (#P by 3), in parallel.
  std::vector<ClosestPoint> closest(const MatrixX3d& P) const;

 private:
  MatrixX3d V_;
  MatrixX3i F_;
  BoxTree tree_;
};

// Closest point of triangle (a, b, c) to p, with its barycentric weights (Ericson, RTCD §5.1.5).
Eigen::Vector3d closestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                       const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                       Eigen::Vector3d& barycentric);

}  // namespace vesalius
