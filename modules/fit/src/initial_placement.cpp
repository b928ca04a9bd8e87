#include "vesalius/fit/initial_placement.h"

#include "vesalius/core/error.h"
#include "vesalius/core/triangle_tree.h"

#include "vesalius/core/principal_axes.h"

#include <cmath>
#include <limits>

namespace vesalius::fit {
namespace {

// Similarity ICP from `start`: markers pulled to their closest surface points, the similarity refitted
// to those pairs, until the RMS distance stops improving.
Placement icpFrom(const TriMesh& surface, const MatrixX3d& icp, const SimilarityTransform& start) {
  Placement best{start, std::numeric_limits<double>::infinity(), 0};
  SimilarityTransform current = start;
  for (int it = 0; it < 100; ++it) {
    const TriangleTree tree(current.apply(surface.V), surface.F);
    const std::vector<ClosestPoint> hits = tree.closest(icp);
    MatrixX3d material(icp.rows(), 3);
    double sum = 0;
    for (Eigen::Index i = 0; i < icp.rows(); ++i) {
      const ClosestPoint& h = hits[std::size_t(i)];
      material.row(i).setZero();
      for (int j = 0; j < 3; ++j) material.row(i) += h.barycentric[j] * surface.V.row(surface.F(h.face, j));
      sum += h.squaredDistance;
    }
    const double rms = std::sqrt(sum / double(icp.rows()));
    if (rms > best.rmsError * (1 - 1e-6)) break;
    best = {current, rms, it};
    current = fitSimilarity(material, icp, Eigen::VectorXd(), true);
  }
  return best;
}

}  // namespace

Placement placeTemplate(const TriMesh& surface, const MatrixX3d& templateLandmarks, const MatrixX3d& scanLandmarks,
                        const MatrixX3d& icp) {
  if (templateLandmarks.rows() >= 3) {
    Placement p;
    p.transform = fitSimilarity(templateLandmarks, scanLandmarks, Eigen::VectorXd(), true);
    p.rmsError = std::sqrt((p.transform.apply(templateLandmarks) - scanLandmarks).rowwise().squaredNorm().mean());
    return p;
  }
  if (icp.rows() < 3) throw BadInput("", "placing the template needs 3 landmark pairs or 3 ICP markers");
  const PrincipalAxes from = principalAxes(surface.V), to = principalAxes(icp);
  Placement best;
  best.rmsError = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& signs : {Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(-1, -1, 1),
                                      Eigen::Vector3d(-1, 1, -1), Eigen::Vector3d(1, -1, -1)}) {
    SimilarityTransform start;
    start.rotation = to.axes * signs.asDiagonal() * from.axes.transpose();
    start.scale = std::sqrt(to.variances.sum() / from.variances.sum());
    start.translation = to.centroid - start.scale * start.rotation * from.centroid;
    const Placement p = icpFrom(surface, icp, start);
    if (p.rmsError < best.rmsError) best = p;
  }
  return best;
}

}  // namespace vesalius::fit
