// Local untangling of a skinned tet mesh: inverted or flat tets repaired by moving the free vertices around
// them. Our addition to Sujar et al. 2018, whose skinning (§3.5) has no collision response: where a bent elbow or hip
// folds the inside of the joint into itself, small tets invert, and the tissue they carry (tet_affine_maps.h)
// is mirrored.
//
// Method: Garanzha, Kaporin, Kudryavtseva, Protais, Ray, Sokolov, "Foldover-free maps in 50 lines of code",
// ACM TOG 40(4) 2021, §3-4, in 3D. With J the map of a tet from its rest to its posed shape and D = det J (the
// posed/rest volume ratio), each tet's energy, weighted by its rest volume, is
//   (1 − θ) tr(JᵀJ) / χ(D, ε)^(2/3) + θ (D² + 1) / χ(D, ε),   χ(D, ε) = (D + sqrt(ε² + D²)) / 2,
// a shape term (conformal distortion) and a volume term. χ is a smooth positive stand-in for D that is finite
// for inverted tets, so minimising works from a tangled start; ε decreases from round to round by the paper's
// rule (ε ← 2 sqrt(μ(μ − D_min)), μ = (1 − σ) χ(D_min, ε), σ = max(1 − E/E_prev, 0.1)) until the barrier is
// exact. Each round is an L-BFGS minimisation (as in the paper) over the free vertices.
//
// Deviations: the paper untangles a whole mesh with its boundary locked; here only regions are solved: the
// vertices of the bad tets grown by `rings` rings of tets, less the bone vertices (they move rigidly with their
// bone), with every other vertex held at its skinned position, so the repair stays local and the skinned shape
// is kept outside it. The mesh boundary inside a region is free (the fold is pushed out of the joint). The
// reference shape is the rest tet (the skinned one is itself inverted). A region still bad after its solve is
// grown by one ring and solved again, up to `maxRings`. The rounds stop as soon as every tet of the region
// reaches minVolumeRatio, within a round if need be; then `maxIterations` L-BFGS iterations with the exact
// barrier (ε → 0) give the region back the volume the early rounds took: while ε is large, shrunken tets
// cost least, and a region left there had lost several per cent of a limb's cross-section (the paper
// iterates with decreasing ε to convergence instead, which would pull the whole region towards the rest
// shapes). A tet still bad at
// maxRings lies in a fold pressed between bone vertices (a sharply bent elbow brings the bone regions of the
// tets, which are coarser than the bones, close enough that no place of the free vertices between them is
// valid): the bone vertices of its corners are freed and its region solved again, up to `releaseRounds` times.
// Those vertices are on the rim of a bone region, so the bone's inner vertices still move rigidly; the result
// reports how many were freed and how far they moved.
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/core/tet_adjacency.h"

#include <Eigen/Core>

#include <vector>

namespace vesalius::posing {

struct UntangleOptions {
  // A tet whose posed/rest volume is below this is "inverted or flat" and is repaired; it is also the goal for
  // every tet of a region. Any ratio above 0 is far from tet_quality.h's flat (|volume| ≤ 1e-12 longest edge³).
  double minVolumeRatio = 0.05;
  int rings = 2;          // rings of tets around the bad tets' vertices whose vertices are free
  int maxRings = 6;       // a region still bad is grown by one ring at a time up to this many
  double theta = 0.5;     // weight of the volume term against the shape term (the paper's 3D value)
  int maxRounds = 40;     // ε steps per region solve
  int maxIterations = 50;   // L-BFGS iterations per round
  int history = 8;        // L-BFGS pairs kept
  int releaseRounds = 6;  // times the bone corners of tets still bad at maxRings are freed (0: never)
};

struct UntangleResult {
  long badBefore = 0;      // tets below minVolumeRatio before the repair
  long badAfter = 0;       // and after it (0 unless a region could not be repaired or fixedBad > 0)
  long fixedBad = 0;       // bad tets whose four corners are bone vertices: nothing to move, left as they are
  long regions = 0;        // region solves (connected groups of free vertices), over all ring sizes
  long movedVertices = 0;  // vertices that moved
  double maxMove = 0;      // largest distance a vertex moved, units of V (mm)
  long releasedBoneVertices = 0;  // bone vertices freed because a fold pressed between bones needed them
  double maxBoneMove = 0;         // largest distance one of those moved (mm); 0 if none was freed
  double seconds = 0;      // wall time of the repair, for reports
};

// Built once per rig; repairs frame after frame. Regions are solved in parallel (each writes only its own
// free vertices); the result does not depend on the number of threads.
class TetUntangler {
 public:
  // restV: #V by 3 rest positions, T: #T by 4 positively oriented tets, boneOfVertex: #V, −1 for a free vertex
  // and ≥ 0 for a bone vertex (moved only when freed, see releaseRounds). Throws BadInput if a tet refers to a
  // missing vertex or is flat or inverted at rest, or boneOfVertex is not #V long; UsageError for options out
  // of range.
  TetUntangler(const MatrixX3d& restV, const MatrixX4i& T, const Eigen::VectorXi& boneOfVertex,
               const UntangleOptions& options = {});

  // posedV: #V by 3 posed positions, repaired in place. Throws UsageError if it is not #V by 3.
  UntangleResult operator()(MatrixX3d& posedV) const;

  // The energy of one tet (times its rest volume) at posed corners `posed` (4 by 3, a corner per row) against
  // rest corners `rest`, and its gradient with respect to the posed corners (4 by 3) if `gradient` is given.
  static double tetEnergy(const Eigen::Matrix<double, 4, 3>& rest, const Eigen::Matrix<double, 4, 3>& posed,
                          double epsilon, double theta, Eigen::Matrix<double, 4, 3>* gradient = nullptr);

 private:
  std::vector<std::vector<int>> freeRegions(const std::vector<int>& bad, int rings,
                                            const std::vector<bool>& fixed) const;

  MatrixX3d restV_;
  MatrixX4i T_;
  std::vector<bool> fixed_;
  Eigen::VectorXd restVolume_;
  VertexTets tetsOf_;
  UntangleOptions options_;
};

}  // namespace vesalius::posing
