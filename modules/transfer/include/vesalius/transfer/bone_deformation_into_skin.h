// A bone mesh bent inside its skin by a smooth displacement of its vertices, for a bone that no similarity
// change brings inside (bones_inside_skin.h): the full-body reference's OpenSim skull and jaw, a coarse
// closed model with its mouth region filled, against MakeHuman's skin, which models the mouth as a bag of
// its surface reaching 95 mm into the head, and the eyes as sockets (docs/methods/skeleton-alignment.md).
// Seed 000 §3 asks that a reference's tissues lie inside its skin (rules R5, R6); its Zygote reference had
// bones modelled to fit the skin, so this step is not in the seed.
//
// Method: the hinge of correctionIntoSkin, met per vertex by fixed-point steps. Each step measures
// the signed distances d_i of the bent mesh anew; a vertex less than the margin m deep (d_i > −m) wants to
// move by −(d_i + m) n_i (n_i its outward direction: onto its closest skin point and m beyond it), a vertex
// deeper wants to stay where it is; the step is the smooth displacement (fit/smooth_displacement.h: least
// squares under the membrane energy of the mesh's graph Laplacian) that best meets those wishes, a shallow
// vertex weighing 1 and a deep one `keepWeight`. Steps add up until no vertex is shallow or `iterations` are
// spent. So the bend reaches from the vertices that poke out over the membrane's reach (set by
// `smoothness`) and fades where the mesh is deep enough; vertices far from any shallow one hardly move,
// but a deep vertex is held where the last step left it, so a long bend drags it a little each step.
// A cavity of the skin (MakeHuman's mouth bag, 76 mm tall) has its closest wall above a vertex here and
// below its neighbour there, and the closest ways out tear the bone across it (measured on the skull: two
// neighbours 5 mm apart sent 30 mm up and 27 mm down); so a shallow vertex may go out along a
// `preferredDirection` instead (the skull's up, the jaw's down): to the first point along it, mm by mm up
// to `reachMm`, that is the margin inside, where that way is at most `detourFactor` times the closest one
// (a vertex out of the back of the head keeps its closest way).
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/transfer/bones_inside_skin.h"

#include <Eigen/Core>

namespace vesalius::transfer {

struct IntoSkinDeformationOptions {
  double marginMm = 1.5;    // how far inside every vertex should end
  int iterations = 30;      // steps at most (each measures the distances once)
  double smoothness = 12.0; // the membrane's weight (fit::SmoothDisplacementOptions::smoothness)
  Eigen::Vector3d preferredDirection = Eigen::Vector3d::Zero();  // the way out to take where it leads in
  double reachMm = 60.0;    // how far along it a way out may lead
  double detourFactor = 3.0;  // how many times longer than the way to the closest skin point it may be
  double keepWeight = 0.2;  // a deep vertex's wish to stay, against a shallow vertex's wish to move (1)
};

struct IntoSkinDeformation {
  MatrixX3d displacement;  // #V by 3, mm: the bent mesh is V + displacement
  long outsideBefore = 0;  // vertices outside the skin (d > 0) before and after
  long outsideAfter = 0;
  int steps = 0;           // steps taken
};

// mesh: the bone (V #V by 3 world mm, F its triangles). Throws UsageError for an empty mesh or options out
// of range.
IntoSkinDeformation deformationIntoSkin(const TriMesh& mesh, const SkinDistanceFunction& skin,
                                        const IntoSkinDeformationOptions& options = {});

}  // namespace vesalius::transfer
