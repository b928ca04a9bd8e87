// Co-rotational linear FEM posing (corotational_fem.h).
#include "vesalius/posing/corotational_fem.h"

#include "vesalius/posing/bone_weights.h"
#include "vesalius/posing/linear_blend_skinning.h"

#include "vesalius/core/error.h"
#include "vesalius/linalg/sparse_cholesky.h"

#include <tbb/parallel_for.h>

#include <Eigen/LU>
#include <Eigen/SVD>
#include <Eigen/SparseCore>

#include <algorithm>
#include <string>
#include <vector>

namespace vesalius::posing {
namespace {

using Eigen::Index;
using SpMat = Eigen::SparseMatrix<double>;
using Gradients = Eigen::Matrix<double, 4, 3>;  // row a: gradient of corner a's barycentric function

void checkInputs(const MatrixX3d& V, const MatrixX4i& T, const Eigen::VectorXi& boneOfVertex,
                 const std::vector<Eigen::Isometry3d>& transforms, const CorotationalFemOptions& options) {
  if (boneOfVertex.size() != V.rows())
    throw BadInput("", "co-rotational FEM: boneOfVertex has " + std::to_string(boneOfVertex.size()) +
                           " entries for " + std::to_string(V.rows()) + " vertices");
  if (T.size() > 0 && (T.minCoeff() < 0 || T.maxCoeff() >= V.rows()))
    throw BadInput("", "co-rotational FEM: a tet refers to a vertex that does not exist");
  if (V.rows() == 0 || boneOfVertex.maxCoeff() < 0) throw BadInput("", "co-rotational FEM: no vertex is a bone");
  if (Index(transforms.size()) <= boneOfVertex.maxCoeff())
    throw BadInput("", "co-rotational FEM: " + std::to_string(transforms.size()) + " transforms for " +
                           std::to_string(boneOfVertex.maxCoeff() + 1) + " bones");
  if (!(options.poissonRatio > -1 && options.poissonRatio < 0.5) || !(options.tolerance > 0) || options.maxIterations < 1)
    throw BadInput("", "co-rotational FEM: an option is out of range");
}

// The rest mesh's constant data: gradients and volumes of the P1 basis, Lamé parameters (E = 1) and the
// numbering of the free vertices' unknowns.
struct Model {
  std::vector<Gradients> G;
  Eigen::VectorXd volume;
  double mu = 0, lambda = 0;
  std::vector<int> freeIndex;  // #V: position among the free vertices, -1 for bone vertices
  Index freeCount = 0;
};

Model restModel(const MatrixX3d& V, const MatrixX4i& T, const Eigen::VectorXi& boneOfVertex, double nu) {
  Model m;
  m.mu = 1 / (2 * (1 + nu));
  m.lambda = nu / ((1 + nu) * (1 - 2 * nu));
  m.G.resize(std::size_t(T.rows()));
  m.volume.resize(T.rows());
  tbb::parallel_for(Index(0), T.rows(), [&](Index t) {
    Eigen::Matrix3d E;
    for (int k = 0; k < 3; ++k) E.col(k) = (V.row(T(t, k + 1)) - V.row(T(t, 0))).transpose();
    m.volume[t] = E.determinant() / 6;
    if (!(m.volume[t] > 0)) throw BadInput("", "co-rotational FEM: tet " + std::to_string(t) + " is flat or inverted");
    Gradients& G = m.G[std::size_t(t)];
    G.bottomRows<3>() = E.inverse();
    G.row(0) = -G.bottomRows<3>().colwise().sum();
  });
  m.freeIndex.assign(std::size_t(V.rows()), -1);
  for (Index v = 0; v < V.rows(); ++v)
    if (boneOfVertex[v] < 0) m.freeIndex[std::size_t(v)] = int(m.freeCount++);
  return m;
}

// 3 by 3 block of the small-strain stiffness coupling corners a and b: the force on a per displacement
// of b, vol (μ (g_a·g_b) I + μ g_b g_aᵀ + λ g_a g_bᵀ).
Eigen::Matrix3d stiffnessBlock(const Model& m, Index t, int a, int b) {
  const Gradients& G = m.G[std::size_t(t)];
  const Eigen::Vector3d ga = G.row(a).transpose(), gb = G.row(b).transpose();
  return m.volume[t] * (m.mu * ga.dot(gb) * Eigen::Matrix3d::Identity() + m.mu * gb * ga.transpose() +
                        m.lambda * ga * gb.transpose());
}

// Pattern of the free-free stiffness, 3 unknowns per free vertex, 3 by 3 blocks for every tet edge.
SpMat freePattern(const MatrixX4i& T, const Model& m) {
  std::vector<Eigen::Triplet<double>> blocks;
  for (Index t = 0; t < T.rows(); ++t)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        const int fa = m.freeIndex[std::size_t(T(t, a))], fb = m.freeIndex[std::size_t(T(t, b))];
        if (fa >= 0 && fb >= 0) blocks.emplace_back(fa, fb, 0.0);
      }
  SpMat vertexPattern(m.freeCount, m.freeCount);
  vertexPattern.setFromTriplets(blocks.begin(), blocks.end());
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(std::size_t(9 * vertexPattern.nonZeros()));
  for (Index c = 0; c < vertexPattern.outerSize(); ++c)
    for (SpMat::InnerIterator it(vertexPattern, c); it; ++it)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) entries.emplace_back(3 * it.row() + i, 3 * c + j, 0.0);
  SpMat K(3 * m.freeCount, 3 * m.freeCount);
  K.setFromTriplets(entries.begin(), entries.end());
  return K;
}

// Rotation of the polar decomposition of each tet's deformation gradient at positions x; an inverted tet's
// reflection is flipped about the axis of least stretch, which gives the nearest rotation.
std::vector<Eigen::Matrix3d> tetRotations(const Model& m, const MatrixX4i& T, const MatrixX3d& x) {
  std::vector<Eigen::Matrix3d> R(std::size_t(T.rows()));
  tbb::parallel_for(Index(0), T.rows(), [&](Index t) {
    Eigen::Matrix3d F = Eigen::Matrix3d::Zero();
    for (int a = 0; a < 4; ++a) F += x.row(T(t, a)).transpose() * m.G[std::size_t(t)].row(a);
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d U = svd.matrixU();
    if ((U * svd.matrixV().transpose()).determinant() < 0) U.col(2) *= -1;  // singular values come sorted
    R[std::size_t(t)] = U * svd.matrixV().transpose();
  });
  return R;
}

// K's values become the free-free blocks of Σ_t R_t K_t R_tᵀ; returns the right-hand side Σ_t R_t K_t X_t
// less the forces that the placed bone vertices (their rows of x) exert on the free ones.
Eigen::VectorXd assemble(const Model& m, const MatrixX3d& V, const MatrixX4i& T, const MatrixX3d& x,
                         const std::vector<Eigen::Matrix3d>& R, SpMat& K) {
  std::fill(K.valuePtr(), K.valuePtr() + K.nonZeros(), 0.0);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(K.rows());
  for (Index t = 0; t < T.rows(); ++t) {
    const Eigen::Matrix3d& Rt = R[std::size_t(t)];
    for (int a = 0; a < 4; ++a) {
      const int fa = m.freeIndex[std::size_t(T(t, a))];
      if (fa < 0) continue;
      for (int b = 0; b < 4; ++b) {
        const Eigen::Matrix3d Kab = stiffnessBlock(m, t, a, b), rotated = Rt * Kab * Rt.transpose();
        rhs.segment<3>(3 * fa) += Rt * Kab * V.row(T(t, b)).transpose();
        const int fb = m.freeIndex[std::size_t(T(t, b))];
        if (fb < 0) {
          rhs.segment<3>(3 * fa) -= rotated * x.row(T(t, b)).transpose();
          continue;
        }
        for (int j = 0; j < 3; ++j) {  // column 3 fb + j holds rows 3 fa .. 3 fa + 2 consecutively
          const int* begin = K.innerIndexPtr() + K.outerIndexPtr()[3 * fb + j];
          const int* end = K.innerIndexPtr() + K.outerIndexPtr()[3 * fb + j + 1];
          double* value = K.valuePtr() + (std::lower_bound(begin, end, 3 * fa) - K.innerIndexPtr());
          for (int i = 0; i < 3; ++i) value[i] += rotated(i, j);
        }
      }
    }
  }
  return rhs;
}

}  // namespace

CorotationalFemResult corotationalFem(const MatrixX3d& V, const MatrixX4i& T, const Eigen::VectorXi& boneOfVertex,
                                      const std::vector<Eigen::Isometry3d>& transforms,
                                      const CorotationalFemOptions& options) {
  checkInputs(V, T, boneOfVertex, transforms, options);
  const Model m = restModel(V, T, boneOfVertex, options.poissonRatio);
  CorotationalFemResult result;
  const Eigen::MatrixXd W = computeBoneWeights(V, T, boneOfVertex);
  result.V = linearBlendSkinning(V, W, std::vector<Eigen::Isometry3d>(transforms.begin(), transforms.begin() + W.cols()));
  for (Index v = 0; v < V.rows(); ++v)  // exactly where their bone puts them, not a blend's rounding of it
    if (boneOfVertex[v] >= 0) result.V.row(v) = (transforms[std::size_t(boneOfVertex[v])] * V.row(v).transpose()).transpose();
  if (m.freeCount == 0) {
    result.converged = true;
    return result;
  }
  const double diagonal = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  SpMat K = freePattern(T, m);
  SparseCholesky cholesky;  // analyses K's pattern on the first factor, refactors numerically afterwards
  while (result.iterations < options.maxIterations && !result.converged) {
    const Eigen::VectorXd rhs = assemble(m, V, T, result.V, tetRotations(m, T, result.V), K);
    cholesky.factor(K);
    const Eigen::VectorXd x = cholesky.solve(rhs);
    result.residual = 0;
    for (Index v = 0; v < V.rows(); ++v) {
      const int f = m.freeIndex[std::size_t(v)];
      if (f < 0) continue;
      result.residual = std::max(result.residual, (x.segment<3>(3 * f).transpose() - result.V.row(v)).norm());
      result.V.row(v) = x.segment<3>(3 * f).transpose();
    }
    ++result.iterations;
    result.converged = result.residual <= options.tolerance * diagonal;
  }
  return result;
}

}  // namespace vesalius::posing
