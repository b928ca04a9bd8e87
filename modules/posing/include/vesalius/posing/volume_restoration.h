// Volume restoration of a skinned tet mesh: the volume skinning squeezes out of a bent joint (or adds to its
// stretched side) put back where it was lost, by a smooth displacement of the tissue vertices. Our addition
// to Sujar et al. 2018, whose skinning (§3.5) keeps volume only as far as DQS or CoR do: on MakeHuman's body in the
// deepest crouches of the CMU walk the belly and the groin, squeezed between the flexed spine, hips and
// knees, lose 4-5 % of the body's volume with every method, the FEM reference too (docs/methods/posing.md).
//
// Method: soft regions, one per node r of a grid of side regionSize, weight each tet by the trilinear hat
// function φ_r of the node at the tet's rest centroid (a partition of unity: Σ_r φ_r = 1). With u the
// displacement of the free (non-bone) vertices from their skinned positions x, minimise
//   E(u) = ½ Σ_r (V_r(x + u) − V0_r)² / V0_r + ½ α Σ_c u_cᵀ K u_c,   V_r = Σ_t φ_r(c_t) V_t,
// the volume-weighted squared relative volume error of every region plus
// α times the Dirichlet energy ∫|∇u|² of the displacement (K: the P1 stiffness matrix of the rest mesh,
// bone_weights.h; u = 0 at bone vertices). Both terms are volumes, so α is dimensionless; at α = 0.01 a
// region's error is all but removed. Where no region changed volume, u = 0: the skin is not inflated where
// volume is kept. Each Gauss-Newton step solves (Σ_r G_rᵀ G_r / V0_r + α K) δ = −∇E, G_r the gradient of
// region r's volume at x + u, by conjugate gradients preconditioned with K (factored once at rest; one
// back-solve of three columns per iteration; K⁻¹ times the matrix is the identity plus a rank of at most
// #regions, so few iterations are needed), then backtracks until E decreases.
// Regions rather than single tets: skinning also moves volume from tet to tet within a few centimetres
// (shear at a joint), which sums to nothing; giving every tet its own volume back (tried: one region per
// tet) moved the body's tissue in the crouches by up to 45 mm (8 mm in the median), against 24 mm (2.7 mm)
// for these regions. Soft rather than hard regions (the grid cell of each centroid): a hard region's volume
// gradient sits on its jagged boundary faces; the hats spread it over the cells.
// This is the linearised incompressibility (pressure) projection of fluid solvers, on coarse soft cells and
// with a penalty instead of a hard constraint. Restoring volume after skinning is done for surfaces by von
// Funck, Theisel and Seidel, "Volume-preserving mesh skinning" (VMV 2008) and Rohmer, Hahmann and Cani,
// "Exact volume preserving skinning with shape control" (SCA 2009); neither was followed here.
// The displacement may flatten or invert tets that were nearly flat; the untangler (untangle_tets.h) runs
// after it.
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <memory>
#include <utility>
#include <vector>

namespace vesalius::posing {

struct VolumeRestoreOptions {
  double regionSize = 0;      // side of the grid cells that group the tets, units of V; 0: bounding box diagonal / 20
  double smoothness = 0.01;   // α: weight of the displacement's Dirichlet energy against the volume errors
  int iterations = 2;         // Gauss-Newton steps
  int cgIterations = 40;      // conjugate gradient iterations per step at most
  double cgTolerance = 0.1;   // stop CG when the preconditioned residual falls below this fraction of the first
};

struct VolumeRestoreResult {
  double volumeChangeBefore = 0;  // (Σ V_t − Σ V0_t) / Σ V0_t of the skinned tets
  double volumeChangeAfter = 0;   // and after the restoration
  double errorBefore = 0;         // sqrt(Σ_r (V_r − V0_r)² / V0_r / Σ_r V0_r): the regions' volume-weighted RMS
                                  // relative error
  double errorAfter = 0;
  int iterations = 0;             // Gauss-Newton steps taken (a step that does not lower E ends the loop)
  int cgIterations = 0;           // over all steps
  double maxMove = 0;             // largest distance a vertex moved, units of V (mm)
  double seconds = 0;             // wall time, for reports
};

// Built once per rig (one factorization); restores frame after frame.
class VolumeRestorer {
 public:
  // restV: #V by 3 rest positions, T: #T by 4 positively oriented tets, boneOfVertex: #V, −1 for a free vertex
  // and ≥ 0 for a bone vertex (never moved). Throws BadInput if a tet refers to a missing vertex or is flat
  // or inverted at rest, boneOfVertex is not #V long, there is no bone vertex, or the factorization of K
  // fails (free vertices in no part of the mesh that touches a bone); UsageError for options out of range.
  VolumeRestorer(const MatrixX3d& restV, const MatrixX4i& T, const Eigen::VectorXi& boneOfVertex,
                 const VolumeRestoreOptions& options = {});

  // posedV: #V by 3 posed positions, restored in place (bone vertices untouched). Throws UsageError if it is
  // not #V by 3.
  VolumeRestoreResult operator()(MatrixX3d& posedV) const;

  // E(u) of the header for posed positions x + u (posed: #V by 3, its bone rows as skinned) and the
  // displacement u of the free vertices (#free by 3, in vertex order); its gradient with respect to u if
  // `gradient` is given.
  double energy(const MatrixX3d& posed, const Eigen::MatrixX3d& u, Eigen::MatrixX3d* gradient = nullptr) const;

  Eigen::Index freeCount() const { return Eigen::Index(freeVertices_.size()); }
  Eigen::Index regionCount() const { return regions_.rows(); }

 private:
  struct Stiffness;  // K of the free vertices and its factor (fem's SparseCholesky, private to the module)
  std::shared_ptr<const Stiffness> freeStiffness(const MatrixX3d& restV, const MatrixX4i& T) const;
  MatrixX3d displaced(const MatrixX3d& posed, const Eigen::MatrixX3d& u) const;
  Eigen::VectorXd relativeErrors(const Eigen::VectorXd& tetVolume) const;
  std::pair<double, double> volumeErrors(const Eigen::VectorXd& tetVolume) const;
  Eigen::MatrixX3d gaussNewtonStep(const MatrixX3d& posed, const Eigen::MatrixX3d& g, int& iterations) const;

  MatrixX4i T_;
  Eigen::VectorXd restVolume_;
  Eigen::SparseMatrix<double> regions_;  // #regions by #T: each tet's share in each region
  Eigen::VectorXd regionRestVolume_;
  std::vector<int> freeVertices_;  // ascending
  std::vector<int> freeIndex_;     // per vertex its row in u, −1 for a bone vertex
  std::shared_ptr<const Stiffness> stiffness_;
  VolumeRestoreOptions options_;
};

}  // namespace vesalius::posing
