// CoR skinning, interactive step (cor_skinning.h), by blocks of vertices (blending.h).
#include "vesalius/posing/cor_skinning.h"

#include "blending.h"

namespace vesalius::posing {

void corSkinning(const MatrixX3d& V, const Eigen::MatrixXd& W, const MatrixX3d& centres,
                 const std::vector<Eigen::Isometry3d>& transforms, MatrixX3d& posed) {
  detail::checkSkinningInputs(V, W, transforms, "CoR skinning");
  if (centres.rows() != V.rows())
    throw UsageError("CoR skinning: " + std::to_string(centres.rows()) + " centres for " + std::to_string(V.rows()) +
                     " vertices");
  const std::vector<Eigen::Vector4d> q = detail::rotationQuaternions(transforms);
  posed.resize(V.rows(), 3);
  detail::forEachBlock(V.rows(), [&](Eigen::Index first, Eigen::Index count) {
    double pivot[4][detail::kBlock], w[detail::kBlock], blend[4][detail::kBlock] = {}, moved[3][detail::kBlock] = {};
    const double* p[3] = {centres.col(0).data() + first, centres.col(1).data() + first, centres.col(2).data() + first};
    detail::heaviestQuaternions(W, q, first, count, pivot);
    for (Eigen::Index j = 0; j < W.cols(); ++j) {
      detail::signedWeights(W, q, j, first, count, pivot, w);
      for (int c = 0; c < 4; ++c)
        for (Eigen::Index i = 0; i < count; ++i) blend[c][i] += w[i] * q[std::size_t(j)][c];
      // The centre moved by linear blend skinning: Σ_j w_ij T_j p_i.
      detail::addTransformed(transforms[std::size_t(j)].affine(), W.col(j).data() + first, p[0], p[1], p[2], count,
                             moved[0], moved[1], moved[2]);
    }
    const double *__restrict x0 = V.col(0).data() + first, *__restrict x1 = V.col(1).data() + first,
                             *__restrict x2 = V.col(2).data() + first;
    double *__restrict y0 = posed.col(0).data() + first, *__restrict y1 = posed.col(1).data() + first,
                       *__restrict y2 = posed.col(2).data() + first;
    double norm[detail::kBlock];
    detail::norms(blend, count, norm);
    for (Eigen::Index i = 0; i < count; ++i) {
      double v0 = x0[i] - p[0][i], v1 = x1[i] - p[1][i], v2 = x2[i] - p[2][i];
      const double n = norm[i];
      detail::rotate(blend[0][i] / n, blend[1][i] / n, blend[2][i] / n, blend[3][i] / n, v0, v1, v2);
      y0[i] = v0 + moved[0][i];
      y1[i] = v1 + moved[1][i];
      y2[i] = v2 + moved[2][i];
    }
  });
}

MatrixX3d corSkinning(const MatrixX3d& V, const Eigen::MatrixXd& W, const MatrixX3d& centres,
                      const std::vector<Eigen::Isometry3d>& transforms) {
  MatrixX3d posed;
  corSkinning(V, W, centres, transforms, posed);
  return posed;
}

}  // namespace vesalius::posing
