// Dual quaternion skinning (dual_quaternion_skinning.h), by blocks of vertices (blending.h).
#include "vesalius/posing/dual_quaternion_skinning.h"

#include "blending.h"

namespace vesalius::posing {
namespace {

// Dual parts ½ t_j q_j, as (x, y, z, w) coefficients.
std::vector<Eigen::Vector4d> dualParts(const std::vector<Eigen::Isometry3d>& transforms,
                                       const std::vector<Eigen::Vector4d>& real) {
  std::vector<Eigen::Vector4d> dual;
  for (std::size_t j = 0; j < transforms.size(); ++j) {
    const Eigen::Vector3d t = transforms[j].translation();
    const Eigen::Quaterniond q(real[j]);
    dual.push_back(0.5 * (Eigen::Quaterniond(0.0, t.x(), t.y(), t.z()) * q).coeffs());
  }
  return dual;
}

// The blended dual quaternions of a block: real part b0 and dual part be, by (x, y, z, w) component.
struct Blend {
  double b0[4][detail::kBlock] = {}, be[4][detail::kBlock] = {};
};

// Writes v' = rigid motion of (b0, be) / |b0| applied to v, for each vertex of the block.
void applyBlend(const Blend& b, const MatrixX3d& V, Eigen::Index first, Eigen::Index count, MatrixX3d& posed) {
  const double *__restrict x0 = V.col(0).data() + first, *__restrict x1 = V.col(1).data() + first,
                           *__restrict x2 = V.col(2).data() + first;
  double *__restrict y0 = posed.col(0).data() + first, *__restrict y1 = posed.col(1).data() + first,
                     *__restrict y2 = posed.col(2).data() + first;
  double norm[detail::kBlock];
  detail::norms(b.b0, count, norm);
  for (Eigen::Index i = 0; i < count; ++i) {
    const double n = norm[i];
    const double x = b.b0[0][i] / n, y = b.b0[1][i] / n, z = b.b0[2][i] / n, w = b.b0[3][i] / n;
    const double ex = b.be[0][i] / n, ey = b.be[1][i] / n, ez = b.be[2][i] / n, ew = b.be[3][i] / n;
    double v0 = x0[i], v1 = x1[i], v2 = x2[i];
    detail::rotate(x, y, z, w, v0, v1, v2);
    // Translation 2 (w d − ew r + r × d) of the unit dual quaternion, r = (x, y, z), d = (ex, ey, ez).
    y0[i] = v0 + 2.0 * (w * ex - ew * x + (y * ez - z * ey));
    y1[i] = v1 + 2.0 * (w * ey - ew * y + (z * ex - x * ez));
    y2[i] = v2 + 2.0 * (w * ez - ew * z + (x * ey - y * ex));
  }
}

}  // namespace

void dualQuaternionSkinning(const MatrixX3d& V, const Eigen::MatrixXd& W,
                            const std::vector<Eigen::Isometry3d>& transforms, MatrixX3d& posed) {
  detail::checkSkinningInputs(V, W, transforms, "dual quaternion skinning");
  const std::vector<Eigen::Vector4d> real = detail::rotationQuaternions(transforms);
  const std::vector<Eigen::Vector4d> dual = dualParts(transforms, real);
  posed.resize(V.rows(), 3);
  detail::forEachBlock(V.rows(), [&](Eigen::Index first, Eigen::Index count) {
    double pivot[4][detail::kBlock], w[detail::kBlock];
    Blend b;
    detail::heaviestQuaternions(W, real, first, count, pivot);
    for (Eigen::Index j = 0; j < W.cols(); ++j) {
      detail::signedWeights(W, real, j, first, count, pivot, w);
      const Eigen::Vector4d& q = real[std::size_t(j)];
      const Eigen::Vector4d& d = dual[std::size_t(j)];
      for (int c = 0; c < 4; ++c)
        for (Eigen::Index i = 0; i < count; ++i) {
          b.b0[c][i] += w[i] * q[c];
          b.be[c][i] += w[i] * d[c];
        }
    }
    applyBlend(b, V, first, count, posed);
  });
}

MatrixX3d dualQuaternionSkinning(const MatrixX3d& V, const Eigen::MatrixXd& W,
                                 const std::vector<Eigen::Isometry3d>& transforms) {
  MatrixX3d posed;
  dualQuaternionSkinning(V, W, transforms, posed);
  return posed;
}

}  // namespace vesalius::posing
