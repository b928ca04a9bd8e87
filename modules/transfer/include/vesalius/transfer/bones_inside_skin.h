// A placed bone (or a group of bones that move as one) moved inside its skin by the smallest similarity
// change: a translation, a turn and a uniform scale about the bones' centroid that bring every vertex a
// margin inside. Dicko et al. 2013, §3, asks of a reference anatomy that its tissues lie inside its skin (rules R5,
// R6); the full-body reference's bones are placed by the skin's rig (skeleton_placement.h), which does not
// look at the skin, so some poke through where the rig's joints sit near it (feet, face, lower back).
//
// Method: Gauss-Newton on E = Σ_i max(0, d_i + m)² + λ |p|²_W + w Σ_a |T(a) − a|², d_i the signed
// distance of vertex i to the skin (negative inside), m the margin, p = (t, ω, s − 1) the change's
// translation, rotation vector and scale about the bones' centroid, W weighing the turn in mm at the bones'
// RMS radius and the scale `scaleCost` times dearer (a bone is moved before it is shrunk), and a the
// anchors: the joints the bones share with their neighbours, kept in place so that a bone turns about its
// joint rather than leave it. Each iteration measures the distances anew and linearises them along each
// vertex's outward direction n_i: d_i changes by n_i · (δt + ω × (x_i − c) + δs (x_i − c)); the steps are
// damped (Levenberg-Marquardt). The change starts from none, so a bone already a margin inside stays as it
// is. A symmetric group (the trunk, Dicko et al. 2013, §8, rule R2) keeps its mirror symmetry: translation in the
// sagittal plane, turn about its normal, scale about the centroid projected onto it. Caps
// (InsideSkinOptions) bound the change where no similarity fits the bone inside (a bone larger than the
// skin around it); its vertices then stay partly outside. Not in the papers: the GRAPP 2012 paper moves a rig's joints
// inside the skin (§3.2 onwards), not the bones; this is the same aim for bones placed by a given rig.
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/mesh.h"
#include "vesalius/linalg/similarity_transform.h"

#include <Eigen/Core>

#include <functional>

namespace vesalius::transfer {

// Signed distances (mm, negative inside) of points to a closed skin, and the unit direction in which each
// grows (outward), one row per point.
struct SkinDistances {
  Eigen::VectorXd distance;
  MatrixX3d outward;
};
using SkinDistanceFunction = std::function<SkinDistances(const MatrixX3d& points)>;

struct InsideSkinOptions {
  double marginMm = 1.5;        // how far inside every vertex should end
  int iterations = 40;          // Gauss-Newton iterations at most (each measures the distances once)
  double minScale = 0.8;        // the scale change is kept at or above this
  double maxShiftMm = 30.0;     // the translation's length at most
  double maxTurnDegrees = 20.0; // the turn at most
  double changeWeight = 0.1;    // weight of the change's size |p|²_W against one vertex's squared hinge (mm²)
  double scaleCost = 25.0;      // how much dearer a change of scale is than a turn of the same mm at the radius
  double anchorWeight = 30.0;   // weight of an anchor's squared displacement, against one vertex's hinge
};

struct InsideSkinCorrection {
  SimilarityTransform change;  // world to world, applied after the placement
  long outsideBefore = 0;           // vertices outside the skin (d > 0) before and after
  long outsideAfter = 0;
};

// V: the bones' vertices (#V by 3, world mm). anchors: points the change should keep in place (#A by 3,
// may be empty): the joints the bones share with their neighbours, so that a bone turns about its joint
// rather than leaving it. sagittal: the plane a symmetric group's change keeps it symmetric about; nullptr
// for a free bone. Throws UsageError for no vertices or options out of range.
InsideSkinCorrection correctionIntoSkin(const MatrixX3d& V, const MatrixX3d& anchors, const SkinDistanceFunction& skin,
                                        const Plane* sagittal, const InsideSkinOptions& options = {});

}  // namespace vesalius::transfer
