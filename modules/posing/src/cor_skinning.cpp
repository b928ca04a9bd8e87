// CoR skinning, interactive step (cor_skinning.h).
#include "vesalius/posing/cor_skinning.h"

#include "blending.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace vesalius::posing {

MatrixX3d corSkinning(const MatrixX3d& V, const Eigen::MatrixXd& W, const MatrixX3d& centres,
                      const std::vector<Eigen::Isometry3d>& transforms) {
  detail::checkSkinningInputs(V, W, transforms, "CoR skinning");
  if (centres.rows() != V.rows())
    throw UsageError("CoR skinning: " + std::to_string(centres.rows()) + " centres for " + std::to_string(V.rows()) +
                     " vertices");
  const std::vector<Eigen::Vector4d> q = detail::rotationQuaternions(transforms);
  MatrixX3d posed(V.rows(), 3);
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, V.rows(), 1024), [&](const tbb::blocked_range<Eigen::Index>& r) {
    for (Eigen::Index i = r.begin(); i < r.end(); ++i) {
      Eigen::Index heaviest = 0;
      W.row(i).maxCoeff(&heaviest);
      Eigen::Vector4d blend = Eigen::Vector4d::Zero();
      Eigen::Matrix<double, 3, 4> lbs = Eigen::Matrix<double, 3, 4>::Zero();
      for (Eigen::Index j = 0; j < W.cols(); ++j) {
        if (W(i, j) == 0.0) continue;
        blend += W(i, j) * detail::hemisphereSign(q[std::size_t(j)], q[std::size_t(heaviest)]) * q[std::size_t(j)];
        lbs += W(i, j) * transforms[std::size_t(j)].affine();
      }
      const Eigen::Matrix3d R = Eigen::Quaterniond(blend.normalized()).toRotationMatrix();
      const Eigen::Vector3d p = centres.row(i).transpose();
      const Eigen::Vector3d t = lbs.leftCols<3>() * p + lbs.col(3) - R * p;
      posed.row(i) = (R * V.row(i).transpose() + t).transpose();
    }
  });
  return posed;
}

}  // namespace vesalius::posing
