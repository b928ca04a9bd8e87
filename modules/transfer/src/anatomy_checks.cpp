// Anatomical rules as numbers (anatomy_checks.h).
#include "vesalius/transfer/anatomy_checks.h"

#include "vesalius/core/error.h"
#include "vesalius/core/grid_sampling.h"
#include "vesalius/core/principal_axes.h"
#include "vesalius/core/triangle_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace vesalius::transfer {

double centreLineDeviation(const MatrixX3d& reference, const MatrixX3d& V, int slices) {
  if (reference.rows() < 8 || slices < 5) throw UsageError("centre-line deviation needs 8 vertices and 5 slices");
  if (V.rows() != reference.rows()) throw UsageError("centre-line deviation: the moved bone has other vertices");
  const PrincipalAxes referenceAxes = principalAxes(reference);
  const Eigen::Vector3d axis = referenceAxes.axes.col(0), centroid = referenceAxes.centroid;
  const Eigen::VectorXd along = (reference.rowwise() - centroid.transpose()) * axis;
  const double low = along.minCoeff(), length = along.maxCoeff() - low;
  if (!(length > 0)) return 0;
  std::vector<Eigen::Vector3d> sums(slices, Eigen::Vector3d::Zero());
  std::vector<int> counts(slices, 0);
  for (Eigen::Index r = 0; r < V.rows(); ++r) {
    const double s = (along[r] - low) / length;
    if (s < 0.1 || s > 0.9) continue;
    const int slab = std::min(slices - 1, int(s * slices));
    sums[slab] += V.row(r).transpose(), ++counts[slab];
  }
  std::vector<Eigen::Vector3d> centres;
  for (int s = 0; s < slices; ++s)
    if (counts[s] > 0) centres.push_back(sums[s] / counts[s]);
  if (centres.size() < 3) return 0;
  Eigen::MatrixX3d C(Eigen::Index(centres.size()), 3);
  for (std::size_t s = 0; s < centres.size(); ++s) C.row(Eigen::Index(s)) = centres[s].transpose();
  const PrincipalAxes line = principalAxes(C);
  const Eigen::Vector3d lineAxis = line.axes.col(0), linePoint = line.centroid;
  const Eigen::VectorXd movedAlong = (V.rowwise() - linePoint.transpose()) * lineAxis;
  double worst = 0;
  for (Eigen::Index r = 0; r < C.rows(); ++r) {
    const Eigen::Vector3d d = C.row(r).transpose() - linePoint;
    worst = std::max(worst, (d - d.dot(lineAxis) * lineAxis).norm());
  }
  return worst / (movedAlong.maxCoeff() - movedAlong.minCoeff());
}

bool isLongBone(const MatrixX3d& V, double minElongation) {
  if (V.rows() < 2) return false;
  const PrincipalAxes axes = principalAxes(V);
  const MatrixX3d local = (V.rowwise() - axes.centroid.transpose()) * axes.axes;
  const Eigen::Vector3d extent = local.colwise().maxCoeff() - local.colwise().minCoeff();
  return extent[0] >= minElongation * std::max(extent[1], extent[2]);
}

double mirrorAsymmetry(const MatrixX3d& V, const MatrixX3i& F, const Plane& plane) {
  const Eigen::Vector3d n = plane.normal.normalized();
  const Eigen::VectorXd side = (V.rowwise() - plane.point.transpose()) * n;
  const MatrixX3d mirrored = V - 2.0 * side * n.transpose();
  const TriangleTree tree(V, F);
  double sum = 0;
  for (const ClosestPoint& c : tree.closest(mirrored)) sum += std::sqrt(c.squaredDistance);
  return sum / double(V.rows());
}

Eigen::VectorXd sampleSignedDistance(const Grid<float>& distance, const MatrixX3d& V, double offGrid) {
  Eigen::VectorXd d(V.rows());
  for (Eigen::Index r = 0; r < V.rows(); ++r) {
    const Eigen::Vector3d index = distance.geometry.worldToIndex(V.row(r).transpose());
    d[r] = insideVoxels(index, distance.geometry.size) ? sampleTrilinear(distance, index) : offGrid;
  }
  return d;
}

SkinDistances sampleSkinDistances(const Grid<float>& distance, const MatrixX3d& V) {
  const double offGrid = std::numeric_limits<double>::quiet_NaN();
  SkinDistances out{sampleSignedDistance(distance, V, offGrid), MatrixX3d::Zero(V.rows(), 3)};
  const double h = 0.5 * distance.geometry.spacing.minCoeff();
  MatrixX3d gradient(V.rows(), 3);
  for (int k = 0; k < 3; ++k) {
    const MatrixX3d step = (h * Eigen::Vector3d::Unit(k)).transpose().replicate(V.rows(), 1);
    gradient.col(k) =
        (sampleSignedDistance(distance, V + step, offGrid) - sampleSignedDistance(distance, V - step, offGrid)) / (2 * h);
  }
  for (Eigen::Index r = 0; r < V.rows(); ++r) {
    if (!std::isfinite(out.distance[r]) || !gradient.row(r).allFinite()) {
      out.distance[r] = 0.0;
      continue;
    }
    if (gradient.row(r).norm() > 1e-9) out.outward.row(r) = gradient.row(r).normalized();
  }
  return out;
}

}  // namespace vesalius::transfer
