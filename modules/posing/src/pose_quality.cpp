#include "vesalius/posing/pose_quality.h"

#include "vesalius/core/mesh_measures.h"

#include <Eigen/LU>

#include <algorithm>
#include <filesystem>

namespace vesalius::posing {

namespace {

long leftOutside(const MatrixX3d& posedTets, const TetEmbedding& e, const MatrixX3d& carried) {
  long count = 0;
  for (Eigen::Index p = 0; p < carried.rows(); ++p) {
    if (e.barycentric.row(p).minCoeff() < -QualityMeter::kTolerance) continue;  // outside at rest: carried by its nearest tet
    const Eigen::RowVector3d a = posedTets.row(e.corners(p, 0));
    Eigen::Matrix3d edges;
    for (int k = 0; k < 3; ++k) edges.col(k) = (posedTets.row(e.corners(p, k + 1)) - a).transpose();
    const Eigen::Vector3d w = edges.inverse() * (carried.row(p) - a).transpose();
    const Eigen::Vector4d weights(1 - w.sum(), w[0], w[1], w[2]);
    if (!(weights.minCoeff<Eigen::PropagateNaN>() >= -QualityMeter::kTolerance)) ++count;  // NaN (a flat tet) counts as left
  }
  return count;
}

}  // namespace

QualityMeter::QualityMeter(const AnatomyRig& rig, const std::vector<TriMesh>& meshes,
                           const std::vector<TetEmbedding>& embeddings)
    : T_(rig.tets.T), restVolumes_(tetVolumes(rig.tets.V, rig.tets.T)), embeddings_(embeddings) {
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    rigid_.push_back(rig.jointOfMesh(m) >= 0);
    if (std::filesystem::path(rig.meshes[m]).stem() == "skin") {
      skin_ = int(m);
      skinF_ = meshes[m].F;
      restSkinVolume_ = enclosedVolume(meshes[m].V, meshes[m].F);
    }
  }
  for (std::size_t m = 0; m < embeddings.size(); ++m)
    if (!rigid_[m]) inside_ += (embeddings[m].barycentric.rowwise().minCoeff().array() >= -kTolerance).count();
}

PoseQuality QualityMeter::operator()(const MatrixX3d& posedTets, const std::vector<MatrixX3d>& carried) const {
  PoseQuality q;
  const Eigen::ArrayXd volumes = tetVolumes(posedTets, T_).array();
  q.inverted = (volumes <= 0).count();
  q.minVolumeRatio = (volumes / restVolumes_.array()).minCoeff();
  q.tetVolumeChangePct = 100 * (volumes.sum() / restVolumes_.sum() - 1);
  if (skin_ >= 0) q.skinVolumeChangePct = 100 * (enclosedVolume(carried[skin_], skinF_) / restSkinVolume_ - 1);
  double gapSum = 0;
  long gapCount = 0;
  MatrixX3d byTets;
  for (std::size_t m = 0; m < carried.size(); ++m) {
    if (!rigid_[m]) {
      q.leftOutside += leftOutside(posedTets, embeddings_[m], carried[m]);
      continue;
    }
    embeddings_[m].apply(posedTets, byTets);
    const Eigen::VectorXd gap = (carried[m] - byTets).rowwise().norm();
    for (Eigen::Index p = 0; p < gap.size(); ++p) {
      if (embeddings_[m].barycentric.row(p).minCoeff() < -kTolerance) continue;  // outside the rest tets
      q.boneMeshGapMax = std::max(q.boneMeshGapMax, gap[p]);
      gapSum += gap[p];
      ++gapCount;
    }
  }
  if (gapCount > 0) q.boneMeshGapMean = gapSum / double(gapCount);
  return q;
}

}  // namespace vesalius::posing
