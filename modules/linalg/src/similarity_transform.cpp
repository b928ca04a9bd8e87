#include "vesalius/linalg/similarity_transform.h"

#include "vesalius/core/error.h"

#include <Eigen/SVD>

namespace vesalius {

MatrixX3d SimilarityTransform::apply(const MatrixX3d& P) const {
  MatrixX3d Q = (scale * P * rotation.transpose()).rowwise() + translation.transpose();
  return Q;
}

SimilarityTransform fitSimilarity(const MatrixX3d& from, const MatrixX3d& to, const Eigen::VectorXd& weights,
                                  bool allowScale) {
  if (from.rows() != to.rows()) throw UsageError("similarity fit: point sets differ in size");
  if (from.rows() < 3) throw BadInput("", "at least 3 point pairs are needed to place the template");
  const Eigen::VectorXd w = weights.size() ? Eigen::VectorXd(weights / weights.sum())
                                            : Eigen::VectorXd::Constant(from.rows(), 1.0 / double(from.rows()));
  const Eigen::RowVector3d muFrom = w.transpose() * from, muTo = w.transpose() * to;
  const MatrixX3d a = from.rowwise() - muFrom, b = to.rowwise() - muTo;
  const Eigen::Matrix3d covariance = b.transpose() * w.asDiagonal() * a;  // Σ w (to − μ)(from − μ)ᵀ
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(covariance, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d sigma = svd.singularValues();
  if (sigma[1] <= 1e-12 * std::max(sigma[0], 1e-300))
    throw BadInput("", "the paired points are collinear: the rotation is undetermined");
  Eigen::Vector3d signs(1, 1, (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1 : 1);
  SimilarityTransform t;
  t.rotation = svd.matrixU() * signs.asDiagonal() * svd.matrixV().transpose();
  if (allowScale) {
    const double varianceFrom = (a.array().square().rowwise().sum().matrix().transpose() * w)(0);
    t.scale = sigma.dot(signs) / varianceFrom;
  }
  t.translation = muTo.transpose() - t.scale * t.rotation * muFrom.transpose();
  return t;
}

}  // namespace vesalius
