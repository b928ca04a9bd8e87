// What no similarity change of a bone (bones_inside_skin.h) brings inside the skin, bent inside: a
// smooth displacement of the bones' space, zero beyond a radius of the vertices still outside, that moves
// each of them a margin inside. For a reference anatomy built from a generic skeleton and a skin of other
// proportions (rules R5, R6 for the reference itself, Dicko et al. 2013, §3): Rajagopal's clavicles and lower back
// ribs lie a few mm outside MakeHuman's neutral skin wherever the rest of the rib cage and its joints
// allow it to sit, the toes and calcanei at the foot's sides (docs/methods/skeleton-alignment.md).
// Not in the papers.
//
// Method: rounds of kernel ridge regression. In each round the vertices outside the skin (distance d_i > 0)
// ask to move by δ_i = −(d_i − w_i) n_i, n_i their outward direction and w_i the depth wanted (−m, the
// margin, unless given per vertex); the displacement
// u(x) = Σ_i φ(|x − x_i|) c_i with Wendland's compactly supported C² kernel φ(r) = (1 − r/R)⁴ (4r/R + 1)
// takes c from (Φ + λ I) c = δ over those vertices (λ = 1: a lone vertex moves half its way in one round,
// a cluster nearly all of it; no overshoot between close centres, as exact interpolation would have). The
// rounds compose until no vertex is outside or `rounds` is reached, and the rounds up to the one that
// left the least outside are kept: the fewest vertices, and of as many the smallest sum of their
// distances from the depth wanted (between two sides of the skin, as between toes, later rounds can undo
// earlier gains; a last vertex wedged between two tissues comes out by steps that leave the count as it
// is). Then the same at a shorter reach from where that left the bones: a bend as long
// as a limb bone cannot tell the two sides of a toe apart, one as long as a toe can (MakeHuman's toes
// are apart where Rajagopal's five toes are one mesh). u is smooth (C²) and fades to nothing at R from
// every vertex that was outside, so a bone is bent, not dented, and its far parts stay.
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/transfer/bones_inside_skin.h"

#include <Eigen/Core>

#include <vector>

namespace vesalius::transfer {

struct InsideSkinWarpOptions {
  double marginMm = 1.5;   // how far inside every vertex should end (unless given per vertex)
  // R: the kernel's support, how far the bend reaches along a bone; one stage of rounds per reach, coarse
  // to fine
  std::vector<double> radiiMm{60.0, 15.0};
  int rounds = 20;  // at most, per stage (each round measures the distances once)
  // The stages again, from where the last left off, while vertices are still outside: a vertex pushed out
  // of one side into another at a fine reach is taken up at the coarse reach again.
  int passes = 1;
};

// The displacement, one round after another; apply() carries any point (a bone's vertices, the points
// fixed to the bone) through all of them.
struct InsideSkinWarp {
  std::vector<double> radiiMm;          // per round: R
  std::vector<MatrixX3d> centres;       // per round, #A by 3: the vertices that were outside
  std::vector<MatrixX3d> coefficients;  // per round, #A by 3: c
  long outsideBefore = 0, outsideAfter = 0;
  double largestMoveMm = 0;             // the largest displacement of a vertex of V
  MatrixX3d apply(const MatrixX3d& P) const;  // #P by 3 → #P by 3
};

// V: the bones' vertices (#V by 3, world mm). wantedDepth: per row of V, the signed distance a row that
// ends outside should be moved to (at most 0), or +∞ for a row to leave alone; the rows left alone are not
// counted in outsideBefore, outsideAfter. Throws UsageError for no vertices, a wantedDepth of other
// length or above 0 (but +∞), or options out of range.
InsideSkinWarp warpIntoSkin(const MatrixX3d& V, const SkinDistanceFunction& skin, const Eigen::VectorXd& wantedDepth,
                            const InsideSkinWarpOptions& options = {});
// The same with every row wanted options.marginMm deep.
InsideSkinWarp warpIntoSkin(const MatrixX3d& V, const SkinDistanceFunction& skin,
                            const InsideSkinWarpOptions& options = {});

}  // namespace vesalius::transfer
