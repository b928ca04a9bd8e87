// Bone registration (bone_registration.h).
#include "vesalius/transfer/bone_registration.h"

#include "vesalius/core/error.h"
#include "vesalius/linalg/similarity_transform.h"

#include <Eigen/Dense>

#include <string>

namespace vesalius::transfer {

namespace {

void checkPairs(const MatrixX3d& P, const MatrixX3d& Q, const Eigen::VectorXd& weights) {
  if (P.rows() != Q.rows() || P.rows() != weights.size())
    throw BadInput("", "bone registration: " + std::to_string(P.rows()) + " bone points but " +
                           std::to_string(Q.rows()) + " attractors and " + std::to_string(weights.size()) + " weights");
  if (P.rows() < 4) throw BadInput("", "bone registration needs at least 4 points on a bone");
  if (!P.allFinite() || !Q.allFinite()) throw BadInput("", "bone registration: a point is not finite");
  if (!weights.allFinite() || !(weights.minCoeff() > 0))
    throw BadInput("", "bone registration: a weight is not positive and finite");
}

Eigen::RowVectorXd weightedMean(const Eigen::MatrixXd& X, const Eigen::VectorXd& weights) {
  return weights.transpose() * X / weights.sum();
}

// The ridge-regularized weighted least-squares linear map X ↦ Y of centred point sets (rows), see the
// header: M = (Yᵀ W X + λ s I)(Xᵀ W X + λ I)⁻¹, W = diag(weights), for any dimension.
Eigen::MatrixXd ridgeLinearFit(const Eigen::MatrixXd& X, const Eigen::MatrixXd& Y, const Eigen::VectorXd& weights) {
  const Eigen::VectorXd root = weights.cwiseSqrt();
  const Eigen::MatrixXd WX = root.asDiagonal() * X, WY = root.asDiagonal() * Y;
  const Eigen::MatrixXd XX = WX.transpose() * WX;
  const double trace = XX.trace();
  if (!(trace > 0)) throw BadInput("", "bone registration: all points of a bone coincide");
  const double lambda = 1e-6 * trace;
  const double scale = std::sqrt(WY.squaredNorm() / WX.squaredNorm());
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(X.cols(), X.cols());
  const Eigen::MatrixXd lhs = XX + lambda * I;
  const Eigen::MatrixXd rhs = WY.transpose() * WX + lambda * scale * I;
  return lhs.ldlt().solve(rhs.transpose()).transpose();  // lhs is symmetric
}

// Orthonormal frame with the plane's normal as first column.
Eigen::Matrix3d planeFrame(const Plane& plane) {
  const Eigen::Vector3d n = plane.normal.normalized();
  const Eigen::Vector3d helper = std::abs(n.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d u = helper.cross(n).normalized();
  Eigen::Matrix3d R;
  R << n, u, n.cross(u);
  return R;
}

}  // namespace

MatrixX3d AffineMap::apply(const MatrixX3d& P) const {
  return (P * A.transpose()).rowwise() + t.transpose();
}

AffineMap fitAffineMap(const MatrixX3d& P, const MatrixX3d& Q) {
  return fitAffineMap(P, Q, Eigen::VectorXd::Ones(P.rows()));
}

AffineMap fitAffineMap(const MatrixX3d& P, const MatrixX3d& Q, const Eigen::VectorXd& weights) {
  checkPairs(P, Q, weights);
  const Eigen::RowVector3d cp = weightedMean(P, weights), cq = weightedMean(Q, weights);
  AffineMap map;
  map.A = ridgeLinearFit(P.rowwise() - cp, Q.rowwise() - cq, weights);
  map.t = cq.transpose() - map.A * cp.transpose();
  return map;
}

AffineMap fitLongBoneMap(const MatrixX3d& P, const MatrixX3d& Q) {
  return fitLongBoneMap(P, Q, Eigen::VectorXd::Ones(P.rows()));
}

// Alternating from the least-squares similarity (fitSimilarity, Umeyama): the rotation by weighted
// Procrustes of the scaled bone D X onto Y, then the two scales in closed form given the rotation (with
// z = Rᵀ y: s_along = Σ w (a·x)(a·z) / Σ w (a·x)², s_across = Σ w x⊥·z⊥ / Σ w |x⊥|², or one scale for
// both, the similarity's, where s_across would exceed s_along).
AffineMap fitLongBoneMap(const MatrixX3d& P, const MatrixX3d& Q, const Eigen::VectorXd& weights) {
  checkPairs(P, Q, weights);
  const Eigen::RowVector3d cp = weightedMean(P, weights), cq = weightedMean(Q, weights);
  const MatrixX3d X = P.rowwise() - cp, Y = Q.rowwise() - cq;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> spread(X.transpose() * weights.asDiagonal() * X);
  const Eigen::Vector3d axis = spread.eigenvectors().col(2);  // eigenvalues ascending
  const Eigen::VectorXd along = X * axis;
  const MatrixX3d across = X - along * axis.transpose();
  const double alongSpread = along.cwiseAbs2().dot(weights), acrossSpread = across.rowwise().squaredNorm().dot(weights);
  const SimilarityTransform similarity = fitSimilarity(X, Y, weights, true);
  Eigen::Matrix3d R = similarity.rotation, A = similarity.scale * R;
  for (int iteration = 0; iteration < 50; ++iteration) {
    const MatrixX3d Z = Y * R;  // rows Rᵀ y
    const Eigen::VectorXd zAlong = Z * axis;
    const double alongFit = along.cwiseProduct(zAlong).dot(weights);
    const double acrossFit = across.cwiseProduct(Z - zAlong * axis.transpose()).rowwise().sum().dot(weights);
    double sAlong = alongFit / alongSpread, sAcross = acrossSpread > 0 ? acrossFit / acrossSpread : sAlong;
    if (sAcross > sAlong) sAlong = sAcross = (alongFit + acrossFit) / (alongSpread + acrossSpread);
    const Eigen::Matrix3d D = sAlong * axis * axis.transpose() + sAcross * (Eigen::Matrix3d::Identity() - axis * axis.transpose());
    R = fitSimilarity(X * D, Y, weights, false).rotation;
    const Eigen::Matrix3d previous = A;
    A = R * D;
    if ((A - previous).norm() < 1e-12 * A.norm()) break;
  }
  AffineMap map;
  map.A = A;
  map.t = cq.transpose() - A * cp.transpose();
  return map;
}

AffineMap fitSymmetricAffineMap(const MatrixX3d& P, const MatrixX3d& Q, const Plane& reference,
                                const Plane& target) {
  return fitSymmetricAffineMap(P, Q, Eigen::VectorXd::Ones(P.rows()), reference, target);
}

AffineMap fitSymmetricAffineMap(const MatrixX3d& P, const MatrixX3d& Q, const Eigen::VectorXd& weights,
                                const Plane& reference, const Plane& target) {
  checkPairs(P, Q, weights);
  const Eigen::Matrix3d Rr = planeFrame(reference), Rt = planeFrame(target);
  // Local coordinates: first axis the normal, origin on the plane.
  const Eigen::MatrixXd p = (P.rowwise() - reference.point.transpose()) * Rr;
  const Eigen::MatrixXd q = (Q.rowwise() - target.point.transpose()) * Rt;
  // Normal axis: x' = a x (no offset, or the plane would move).
  const Eigen::MatrixXd a = ridgeLinearFit(p.col(0), q.col(0), weights);
  // In-plane axes: a 2-D affine map.
  const Eigen::RowVector2d cp = weightedMean(p.rightCols<2>(), weights), cq = weightedMean(q.rightCols<2>(), weights);
  const Eigen::MatrixXd B =
      ridgeLinearFit(p.rightCols<2>().rowwise() - cp, q.rightCols<2>().rowwise() - cq, weights);
  const Eigen::Vector2d b = cq.transpose() - B * cp.transpose();
  Eigen::Matrix3d local = Eigen::Matrix3d::Zero();
  local(0, 0) = a(0, 0);
  local.bottomRightCorner<2, 2>() = B;
  AffineMap map;
  map.A = Rt * local * Rr.transpose();
  map.t = target.point + Rt * Eigen::Vector3d(0, b.x(), b.y()) - map.A * reference.point;
  return map;
}

Plane mapPlane(const AffineMap& map, const Plane& reference) {
  Plane plane;
  plane.point = map.apply(reference.point);
  plane.normal = map.A.inverse().transpose() * reference.normal;
  const double length = plane.normal.norm();
  if (!(length > 0) || !plane.normal.allFinite())
    throw NumericalFailure("bone registration: the trunk's affine map is singular");
  plane.normal /= length;
  return plane;
}

}  // namespace vesalius::transfer
