// What the three skinning methods share: checking their inputs, blending the bones' rotation quaternions in
// one hemisphere (DQS, Kavan et al. 2008; CoR, Le & Hodgins 2016), and the loop over vertices.
//
// Speed: vertices are skinned in blocks of kBlock. Within a block, one bone's weights are a contiguous piece
// of W's column (W is column-major), and each step is a plain loop over arrays of the block, which the
// compiler vectorises; blocks run in parallel. Every vertex is computed on its own, so the result does not
// depend on the number of threads.
#pragma once

#include "vesalius/core/error.h"
#include "vesalius/core/mesh.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <string>
#include <vector>

namespace vesalius::posing::detail {

constexpr Eigen::Index kBlock = 256;

// V: #V by 3, W: #V by #B, one transform per bone. Throws UsageError naming `method` on a mismatch.
inline void checkSkinningInputs(const MatrixX3d& V, const Eigen::MatrixXd& W,
                                const std::vector<Eigen::Isometry3d>& transforms, const std::string& method) {
  if (W.rows() != V.rows())
    throw UsageError(method + ": " + std::to_string(W.rows()) + " weight rows for " + std::to_string(V.rows()) +
                     " vertices");
  if (W.cols() != Eigen::Index(transforms.size()))
    throw UsageError(method + ": " + std::to_string(W.cols()) + " weight columns for " +
                     std::to_string(transforms.size()) + " bone transforms");
  if (W.cols() == 0 && V.rows() > 0) throw UsageError(method + ": no bones to follow");
}

// Unit rotation quaternion of each transform, as (x, y, z, w) coefficients.
inline std::vector<Eigen::Vector4d> rotationQuaternions(const std::vector<Eigen::Isometry3d>& transforms) {
  std::vector<Eigen::Vector4d> q;
  q.reserve(transforms.size());
  for (const auto& T : transforms) q.push_back(Eigen::Quaterniond(T.rotation()).normalized().coeffs());
  return q;
}

// Calls block(first, count) for consecutive blocks of at most kBlock of the n vertices, in parallel.
template <class Block>
void forEachBlock(Eigen::Index n, Block block) {
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, (n + kBlock - 1) / kBlock, 4),
                    [&](const tbb::blocked_range<Eigen::Index>& r) {
                      for (Eigen::Index b = r.begin(); b < r.end(); ++b)
                        block(b * kBlock, std::min(kBlock, n - b * kBlock));
                    });
}

// pivot[c][i]: component c of q_h, h the bone of largest weight of vertex first + i (the first one on a
// tie, as maxCoeff).
inline void heaviestQuaternions(const Eigen::MatrixXd& W, const std::vector<Eigen::Vector4d>& q, Eigen::Index first,
                                Eigen::Index count, double (*pivot)[kBlock]) {
  double best[kBlock];
  double *__restrict x = pivot[0], *__restrict y = pivot[1], *__restrict z = pivot[2], *__restrict s = pivot[3];
  std::copy_n(W.data() + first, count, best);
  std::fill_n(x, count, q[0][0]);
  std::fill_n(y, count, q[0][1]);
  std::fill_n(z, count, q[0][2]);
  std::fill_n(s, count, q[0][3]);
  for (Eigen::Index j = 1; j < W.cols(); ++j) {
    const double* __restrict w = W.data() + j * W.rows() + first;
    const double qx = q[std::size_t(j)][0], qy = q[std::size_t(j)][1], qz = q[std::size_t(j)][2],
                 qs = q[std::size_t(j)][3];
    // Branch-free, so that it vectorises: a strictly larger weight takes over (the first wins a tie).
    for (Eigen::Index i = 0; i < count; ++i) {
      const bool heavier = w[i] > best[i];
      best[i] = heavier ? w[i] : best[i];
      x[i] = heavier ? qx : x[i];
      y[i] = heavier ? qy : y[i];
      z[i] = heavier ? qz : z[i];
      s[i] = heavier ? qs : s[i];
    }
  }
}

// signedW[i] = ±W(first + i, j): the sign puts q_j in the hemisphere of the vertex's pivot, the heaviest
// bone's quaternion. q and -q are the same rotation, and blending across hemispheres would take the long
// way round.
inline void signedWeights(const Eigen::MatrixXd& W, const std::vector<Eigen::Vector4d>& q, Eigen::Index j,
                          Eigen::Index first, Eigen::Index count, const double (*pivot)[kBlock], double* signedW) {
  const double* w = W.data() + j * W.rows() + first;
  const Eigen::Vector4d& qj = q[std::size_t(j)];
  for (Eigen::Index i = 0; i < count; ++i) {
    const double dot = qj[0] * pivot[0][i] + qj[1] * pivot[1][i] + qj[2] * pivot[2][i] + qj[3] * pivot[3][i];
    signedW[i] = dot < 0.0 ? -w[i] : w[i];
  }
}

// Adds w[i] · (A x_i) to y_i for the block's points x (columns x0, x1, x2) and sums y (columns y0, y1, y2).
inline void addTransformed(const Eigen::Matrix<double, 3, 4>& A, const double* __restrict w,
                           const double* __restrict x0, const double* __restrict x1, const double* __restrict x2,
                           Eigen::Index count, double* __restrict y0, double* __restrict y1, double* __restrict y2) {
  for (Eigen::Index i = 0; i < count; ++i) {
    y0[i] += w[i] * (A(0, 0) * x0[i] + A(0, 1) * x1[i] + A(0, 2) * x2[i] + A(0, 3));
    y1[i] += w[i] * (A(1, 0) * x0[i] + A(1, 1) * x1[i] + A(1, 2) * x2[i] + A(1, 3));
    y2[i] += w[i] * (A(2, 0) * x0[i] + A(2, 1) * x1[i] + A(2, 2) * x2[i] + A(2, 3));
  }
}

// norm[i] = |(b[0][i], b[1][i], b[2][i], b[3][i])| (through Eigen's arrays, whose sqrt is vectorised even
// where std::sqrt must keep errno).
inline void norms(const double (*b)[kBlock], Eigen::Index count, double* norm) {
  using Column = Eigen::Map<const Eigen::ArrayXd>;
  Eigen::Map<Eigen::ArrayXd>(norm, count) = (Column(b[0], count).square() + Column(b[1], count).square() +
                                             Column(b[2], count).square() + Column(b[3], count).square()).sqrt();
}

// Rotates (v0, v1, v2) in place by the unit quaternion with vector part (x, y, z) and scalar part w, as
// Eigen's Quaternion * Vector3: u = 2 r × v, v' = v + w u + r × u.
inline void rotate(double x, double y, double z, double w, double& v0, double& v1, double& v2) {
  const double u0 = 2.0 * (y * v2 - z * v1), u1 = 2.0 * (z * v0 - x * v2), u2 = 2.0 * (x * v1 - y * v0);
  v0 += w * u0 + (y * u2 - z * u1);
  v1 += w * u1 + (z * u0 - x * u2);
  v2 += w * u2 + (x * u1 - y * u0);
}

}  // namespace vesalius::posing::detail
