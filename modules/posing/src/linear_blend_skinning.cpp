// Linear blend skinning (linear_blend_skinning.h).
#include "vesalius/posing/linear_blend_skinning.h"

#include "blending.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace vesalius::posing {

MatrixX3d linearBlendSkinning(const MatrixX3d& V, const Eigen::MatrixXd& W,
                              const std::vector<Eigen::Isometry3d>& transforms) {
  detail::checkSkinningInputs(V, W, transforms, "linear blend skinning");
  MatrixX3d posed(V.rows(), 3);
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, V.rows(), 1024), [&](const tbb::blocked_range<Eigen::Index>& r) {
    for (Eigen::Index i = r.begin(); i < r.end(); ++i) {
      Eigen::Matrix<double, 3, 4> blended = Eigen::Matrix<double, 3, 4>::Zero();
      for (Eigen::Index j = 0; j < W.cols(); ++j)
        if (W(i, j) != 0.0) blended += W(i, j) * transforms[std::size_t(j)].affine();
      posed.row(i) = (blended.leftCols<3>() * V.row(i).transpose() + blended.col(3)).transpose();
    }
  });
  return posed;
}

}  // namespace vesalius::posing
