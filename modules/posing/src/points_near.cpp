#include "vesalius/posing/points_near.h"

#include "vesalius/core/box_tree.h"
#include "vesalius/core/triangle_tree.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace vesalius::posing {

MatrixX3d pointsNear(const MatrixX3d& A, const MatrixX3d& B, double distance) {
  if (A.rows() == 0 || B.rows() == 0) return MatrixX3d(0, 3);
  std::vector<Eigen::AlignedBox3d> boxes;
  for (Eigen::Index r = 0; r < B.rows(); ++r) boxes.emplace_back(B.row(r).transpose(), B.row(r).transpose());
  const BoxTree tree(boxes);
  std::vector<Eigen::Index> near;
  for (Eigen::Index r = 0; r < A.rows(); ++r) {
    bool found = false;
    // near() visits every element of a leaf whose box is within reach, so each is checked itself.
    tree.near(A.row(r).transpose(), distance * distance,
              [&](int b) { return found = (B.row(b) - A.row(r)).squaredNorm() <= distance * distance; });
    if (found) near.push_back(r);
  }
  return A(near, Eigen::all);
}

MatrixX3d pointsNear(const MatrixX3d& A, const TriMesh& B, double distance) {
  if (A.rows() == 0 || B.F.rows() == 0) return MatrixX3d(0, 3);
  const std::vector<ClosestPoint> closest = TriangleTree(B.V, B.F).closest(A);
  std::vector<Eigen::Index> near;
  for (Eigen::Index r = 0; r < A.rows(); ++r)
    if (closest[std::size_t(r)].squaredDistance <= distance * distance) near.push_back(r);
  return A(near, Eigen::all);
}

MatrixX3d pointsNearest(const MatrixX3d& A, const TriMesh& B, double reach) {
  if (A.rows() == 0 || B.F.rows() == 0) return MatrixX3d(0, 3);
  const std::vector<ClosestPoint> closest = TriangleTree(B.V, B.F).closest(A);
  double nearest = closest.front().squaredDistance;
  for (const ClosestPoint& c : closest) nearest = std::min(nearest, c.squaredDistance);
  const double within = std::sqrt(nearest) + reach;
  std::vector<Eigen::Index> near;
  for (Eigen::Index r = 0; r < A.rows(); ++r)
    if (closest[std::size_t(r)].squaredDistance <= within * within) near.push_back(r);
  return A(near, Eigen::all);
}

}  // namespace vesalius::posing
