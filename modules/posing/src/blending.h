// What the three skinning methods share: checking their inputs, and blending the bones' rotation
// quaternions in one hemisphere (DQS, Kavan et al. 2008; CoR, Le & Hodgins 2016).
#pragma once

#include "vesalius/core/error.h"
#include "vesalius/core/mesh.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace vesalius::posing::detail {

// V: #V by 3, W: #V by #B, one transform per bone. Throws UsageError naming `method` on a mismatch.
inline void checkSkinningInputs(const MatrixX3d& V, const Eigen::MatrixXd& W,
                                const std::vector<Eigen::Isometry3d>& transforms, const std::string& method) {
  if (W.rows() != V.rows())
    throw UsageError(method + ": " + std::to_string(W.rows()) + " weight rows for " + std::to_string(V.rows()) +
                     " vertices");
  if (W.cols() != Eigen::Index(transforms.size()))
    throw UsageError(method + ": " + std::to_string(W.cols()) + " weight columns for " +
                     std::to_string(transforms.size()) + " bone transforms");
}

// Unit rotation quaternion of each transform, as (x, y, z, w) coefficients.
inline std::vector<Eigen::Vector4d> rotationQuaternions(const std::vector<Eigen::Isometry3d>& transforms) {
  std::vector<Eigen::Vector4d> q;
  q.reserve(transforms.size());
  for (const auto& T : transforms) q.push_back(Eigen::Quaterniond(T.rotation()).normalized().coeffs());
  return q;
}

// ±1: the sign that puts q in the hemisphere of `pivot`, the heaviest bone's quaternion. q and -q are the
// same rotation, and blending across hemispheres would take the long way round.
inline double hemisphereSign(const Eigen::Vector4d& q, const Eigen::Vector4d& pivot) {
  return q.dot(pivot) < 0.0 ? -1.0 : 1.0;
}

}  // namespace vesalius::posing::detail
