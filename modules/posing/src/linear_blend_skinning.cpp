// Linear blend skinning (linear_blend_skinning.h), by blocks of vertices (blending.h).
#include "vesalius/posing/linear_blend_skinning.h"

#include "blending.h"

namespace vesalius::posing {

void linearBlendSkinning(const MatrixX3d& V, const Eigen::MatrixXd& W,
                         const std::vector<Eigen::Isometry3d>& transforms, MatrixX3d& posed) {
  detail::checkSkinningInputs(V, W, transforms, "linear blend skinning");
  posed.resize(V.rows(), 3);
  detail::forEachBlock(V.rows(), [&](Eigen::Index first, Eigen::Index count) {
    double* out[3] = {posed.col(0).data() + first, posed.col(1).data() + first, posed.col(2).data() + first};
    for (double* column : out) std::fill(column, column + count, 0.0);
    for (Eigen::Index j = 0; j < W.cols(); ++j)
      detail::addTransformed(transforms[std::size_t(j)].affine(), W.col(j).data() + first, V.col(0).data() + first,
                             V.col(1).data() + first, V.col(2).data() + first, count, out[0], out[1], out[2]);
  });
}

MatrixX3d linearBlendSkinning(const MatrixX3d& V, const Eigen::MatrixXd& W,
                              const std::vector<Eigen::Isometry3d>& transforms) {
  MatrixX3d posed;
  linearBlendSkinning(V, W, transforms, posed);
  return posed;
}

}  // namespace vesalius::posing
