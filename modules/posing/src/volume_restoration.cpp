// Volume restoration of a skinned tet mesh (volume_restoration.h): Gauss-Newton on the soft regions' squared
// relative volume errors plus α times the displacement's Dirichlet energy, each step by conjugate gradients
// preconditioned with the rest stiffness matrix of the free vertices, factored once.
#include "vesalius/posing/volume_restoration.h"

#include "rest_rig.h"

#include "vesalius/core/error.h"
#include "vesalius/linalg/sparse_cholesky.h"
#include "vesalius/posing/bone_weights.h"

#include <tbb/parallel_for.h>

#include <Eigen/SparseCore>

#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <string>
#include <tuple>

namespace vesalius::posing {

struct VolumeRestorer::Stiffness {
  Eigen::SparseMatrix<double> K;  // #free by #free
  SparseCholesky factor;
};

namespace {

using Corners = Eigen::Matrix<double, 4, 3>;

// Each tet's volume and its gradient with respect to its four corners (row c: ∂V/∂x_c).
struct TetVolumes {
  Eigen::VectorXd volume;
  std::vector<Corners> gradient;
};

TetVolumes tetVolumesAndGradients(const MatrixX3d& V, const MatrixX4i& T) {
  TetVolumes out{Eigen::VectorXd(T.rows()), std::vector<Corners>(std::size_t(T.rows()))};
  tbb::parallel_for(Eigen::Index(0), T.rows(), [&](Eigen::Index t) {
    const Eigen::RowVector3d a = V.row(T(t, 0)), e1 = V.row(T(t, 1)) - a, e2 = V.row(T(t, 2)) - a,
                             e3 = V.row(T(t, 3)) - a;
    Corners& g = out.gradient[std::size_t(t)];
    g.row(1) = e2.cross(e3) / 6;
    g.row(2) = e3.cross(e1) / 6;
    g.row(3) = e1.cross(e2) / 6;
    g.row(0) = -(g.row(1) + g.row(2) + g.row(3));
    out.volume[t] = e1.dot(g.row(1));
  });
  return out;
}

// The soft regions: per node of a grid of side `size` (over the rest mesh's bounding box) the trilinear hat
// function of that node at each tet's rest centroid; #regions by #T, each column summing to 1. Nodes that
// hold no tet are dropped.
Eigen::SparseMatrix<double> gridRegions(const MatrixX3d& V, const MatrixX4i& T, double size) {
  const Eigen::RowVector3d origin = V.colwise().minCoeff();
  std::map<std::array<long, 3>, int> nodes;
  std::vector<Eigen::Triplet<double>> weights;
  for (Eigen::Index t = 0; t < T.rows(); ++t) {
    const Eigen::RowVector3d g =
        ((V.row(T(t, 0)) + V.row(T(t, 1)) + V.row(T(t, 2)) + V.row(T(t, 3))) / 4 - origin) / size;
    const std::array<long, 3> cell{long(std::floor(g.x())), long(std::floor(g.y())), long(std::floor(g.z()))};
    const Eigen::RowVector3d f = g - Eigen::RowVector3d(double(cell[0]), double(cell[1]), double(cell[2]));
    for (int corner = 0; corner < 8; ++corner) {
      double w = 1;
      std::array<long, 3> node = cell;
      for (int k = 0; k < 3; ++k) {
        const bool upper = corner >> k & 1;
        w *= upper ? f[k] : 1 - f[k];
        node[std::size_t(k)] += upper;
      }
      if (w > 0) weights.emplace_back(nodes.emplace(node, int(nodes.size())).first->second, int(t), w);
    }
  }
  Eigen::SparseMatrix<double> P(Eigen::Index(nodes.size()), T.rows());
  P.setFromTriplets(weights.begin(), weights.end());
  return P;
}

// Σ over the tets of a free vertex of s_t times the tet's volume gradient at that vertex: Gᵀ s restricted
// to the free vertices. Serial, tet after tet: the tets and their gradients are read in order and the sums
// (#free by 3) stay in cache; a parallel gather per vertex was 10 times slower.
Eigen::MatrixX3d gatherFree(const std::vector<int>& freeIndex, Eigen::Index freeCount, const MatrixX4i& T,
                            const std::vector<Corners>& gradient, const Eigen::VectorXd& s) {
  Eigen::MatrixX3d out = Eigen::MatrixX3d::Zero(freeCount, 3);
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    for (int c = 0; c < 4; ++c) {
      const int f = freeIndex[std::size_t(T(t, c))];
      if (f >= 0) out.row(f) += s[t] * gradient[std::size_t(t)].row(c);
    }
  return out;
}

// G u per tet: the first-order volume change of each tet under the displacement u of the free vertices.
Eigen::VectorXd volumeChangeOf(const std::vector<int>& freeIndex, const MatrixX4i& T,
                               const std::vector<Corners>& gradient, const Eigen::MatrixX3d& u) {
  Eigen::VectorXd change(T.rows());
  tbb::parallel_for(Eigen::Index(0), T.rows(), [&](Eigen::Index t) {
    double sum = 0;
    for (int c = 0; c < 4; ++c) {
      const int f = freeIndex[std::size_t(T(t, c))];
      if (f >= 0) sum += gradient[std::size_t(t)].row(c).dot(u.row(f));
    }
    change[t] = sum;
  });
  return change;
}

double dot(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b) { return (a.array() * b.array()).sum(); }

}  // namespace

VolumeRestorer::VolumeRestorer(const MatrixX3d& restV, const MatrixX4i& T, const Eigen::VectorXi& boneOfVertex,
                               const VolumeRestoreOptions& options)
    : T_(T), freeIndex_(std::size_t(restV.rows()), -1), options_(options) {
  const VolumeRestoreOptions& o = options;
  if (!(o.regionSize >= 0) || !(o.smoothness > 0) || o.iterations < 0 || o.cgIterations < 1 || !(o.cgTolerance > 0))
    throw UsageError("volume restoration: options out of range (region size >= 0, smoothness > 0, iterations >= "
                     "0, CG iterations >= 1, CG tolerance > 0)");
  restVolume_ = checkedRestVolumes("volume restoration", restV, T, boneOfVertex);
  if (restV.rows() > 0 && boneOfVertex.maxCoeff() < 0) throw BadInput("", "volume restoration: no bone vertex");
  const double size = o.regionSize > 0 ? o.regionSize
                                        : (restV.colwise().maxCoeff() - restV.colwise().minCoeff()).norm() / 20;
  regions_ = gridRegions(restV, T, size);
  regionRestVolume_ = regions_ * restVolume_;
  for (Eigen::Index v = 0; v < restV.rows(); ++v)
    if (boneOfVertex[v] < 0) {
      freeIndex_[std::size_t(v)] = int(freeVertices_.size());
      freeVertices_.push_back(int(v));
    }
  stiffness_ = freeStiffness(restV, T);
}

// The stiffness matrix restricted to the free vertices, factored.
std::shared_ptr<const VolumeRestorer::Stiffness> VolumeRestorer::freeStiffness(const MatrixX3d& restV,
                                                                               const MatrixX4i& T) const {
  const Eigen::SparseMatrix<double> K = stiffnessMatrix(restV, T);
  std::vector<Eigen::Triplet<double>> entries;
  for (int v : freeVertices_)
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, v); it; ++it)
      if (freeIndex_[std::size_t(it.row())] >= 0)
        entries.emplace_back(freeIndex_[std::size_t(it.row())], freeIndex_[std::size_t(v)], it.value());
  auto stiffness = std::make_shared<Stiffness>();
  stiffness->K.resize(freeCount(), freeCount());
  stiffness->K.setFromTriplets(entries.begin(), entries.end());
  if (freeCount() == 0) return stiffness;
  try {
    stiffness->factor.factor(stiffness->K);
  } catch (const NumericalFailure&) {
    throw BadInput("", "volume restoration: some free vertices are in no part of the tet mesh that touches a bone");
  }
  return stiffness;
}

MatrixX3d VolumeRestorer::displaced(const MatrixX3d& posed, const Eigen::MatrixX3d& u) const {
  MatrixX3d moved = posed;
  for (std::size_t i = 0; i < freeVertices_.size(); ++i) moved.row(freeVertices_[i]) += u.row(Eigen::Index(i));
  return moved;
}

// Per region r, its volume error over its rest volume e_r; ∂E/∂V_t = Σ_r φ_r(c_t) e_r.
Eigen::VectorXd VolumeRestorer::relativeErrors(const Eigen::VectorXd& tetVolume) const {
  return (regions_ * tetVolume - regionRestVolume_).cwiseQuotient(regionRestVolume_);
}

std::pair<double, double> VolumeRestorer::volumeErrors(const Eigen::VectorXd& tetVolume) const {
  const double rest = restVolume_.sum();
  const Eigen::VectorXd e = relativeErrors(tetVolume);
  return {tetVolume.sum() / rest - 1, std::sqrt((e.array().square() * regionRestVolume_.array()).sum() / rest)};
}

double VolumeRestorer::energy(const MatrixX3d& posed, const Eigen::MatrixX3d& u, Eigen::MatrixX3d* gradient) const {
  const MatrixX3d moved = displaced(posed, u);
  const Eigen::MatrixX3d Ku = stiffness_->K * u;
  const double smooth = 0.5 * options_.smoothness * dot(u, Ku);
  if (!gradient) {
    const Eigen::VectorXd e = relativeErrors(tetVolumes(moved, T_));
    return 0.5 * (e.array().square() * regionRestVolume_.array()).sum() + smooth;
  }
  const TetVolumes current = tetVolumesAndGradients(moved, T_);
  const Eigen::VectorXd e = relativeErrors(current.volume);
  *gradient = gatherFree(freeIndex_, freeCount(), T_, current.gradient, regions_.transpose() * e) +
              options_.smoothness * Ku;
  return 0.5 * (e.array().square() * regionRestVolume_.array()).sum() + smooth;
}

// The Gauss-Newton system (Σ_r G_rᵀ G_r / V0_r + α K) δ = −g, G_r the gradient of region r's volume at
// `posed`, by conjugate gradients preconditioned with K: K⁻¹ times the matrix is the identity plus a rank of
// at most #regions. Counts the iterations into `iterations`.
Eigen::MatrixX3d VolumeRestorer::gaussNewtonStep(const MatrixX3d& posed, const Eigen::MatrixX3d& g,
                                                 int& iterations) const {
  const TetVolumes current = tetVolumesAndGradients(posed, T_);
  const auto apply = [&](const Eigen::MatrixX3d& d) -> Eigen::MatrixX3d {
    const Eigen::VectorXd change = regions_ * volumeChangeOf(freeIndex_, T_, current.gradient, d);
    return gatherFree(freeIndex_, freeCount(), T_, current.gradient,
                      regions_.transpose() * change.cwiseQuotient(regionRestVolume_)) +
           options_.smoothness * (stiffness_->K * d);
  };
  Eigen::MatrixX3d delta = Eigen::MatrixX3d::Zero(freeCount(), 3), r = -g;
  Eigen::MatrixX3d z = stiffness_->factor.solve(Eigen::MatrixXd(r)), p = z;
  double rz = dot(r, z);
  const double rz0 = rz, tolerance = options_.cgTolerance * options_.cgTolerance;
  for (int k = 0; k < options_.cgIterations && rz > tolerance * rz0; ++k, ++iterations) {
    const Eigen::MatrixX3d Ap = apply(p);
    const double alpha = rz / dot(p, Ap);
    delta += alpha * p;
    r -= alpha * Ap;
    z = stiffness_->factor.solve(Eigen::MatrixXd(r));
    const double rzNext = dot(r, z);
    p = z + (rzNext / rz) * p;
    rz = rzNext;
  }
  return delta;
}

VolumeRestoreResult VolumeRestorer::operator()(MatrixX3d& posedV) const {
  if (posedV.rows() != Eigen::Index(freeIndex_.size()) || posedV.cols() != 3)
    throw UsageError("volume restoration: " + std::to_string(posedV.rows()) + " posed vertices for " +
                     std::to_string(freeIndex_.size()) + " rest vertices");
  const auto start = std::chrono::steady_clock::now();
  const VolumeRestoreOptions& o = options_;
  VolumeRestoreResult result;
  const Eigen::VectorXd skinnedVolume = tetVolumes(posedV, T_);
  std::tie(result.volumeChangeBefore, result.errorBefore) = volumeErrors(skinnedVolume);
  Eigen::MatrixX3d u = Eigen::MatrixX3d::Zero(freeCount(), 3), g;
  double E = energy(posedV, u, &g);
  for (int step = 0; step < o.iterations && freeCount() > 0; ++step) {
    const Eigen::MatrixX3d delta = gaussNewtonStep(displaced(posedV, u), g, result.cgIterations);
    // Backtracking until E decreases enough (Armijo).
    const double slope = dot(g, delta);
    if (!(slope < 0)) break;
    bool accepted = false;
    for (double s = 1; s > 1e-3 && !accepted; s *= 0.5) {
      const Eigen::MatrixX3d trial = u + s * delta;
      Eigen::MatrixX3d gTrial;
      const double ETrial = energy(posedV, trial, &gTrial);
      if (ETrial <= E + 1e-4 * s * slope) {
        u = trial;
        g = gTrial;
        E = ETrial;
        accepted = true;
      }
    }
    if (!accepted) break;
    ++result.iterations;
  }
  posedV = displaced(posedV, u);
  std::tie(result.volumeChangeAfter, result.errorAfter) = volumeErrors(tetVolumes(posedV, T_));
  result.maxMove = freeCount() > 0 ? u.rowwise().norm().maxCoeff() : 0.0;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace vesalius::posing
