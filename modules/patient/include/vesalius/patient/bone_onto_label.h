// A reference bone brought onto the patient's bone label, keeping its mesh (Dicko et al. 2013, §8's per-bone
// registration, with the patient's segmented bone as the target instead of the interpolated skin
// displacement). The virtual patient's model (whole_model.h) holds, inside the scan's field of view, the
// patient's own bones in the reference's meshes: the pelvis and femurs the rig poses are then the
// patient's, and beyond the field of view each bone goes on as the reference's.
//  1. The bone's mesh refined by midpoint subdivision (meshing/midpoint_subdivision.h) until its mean
//     edge is at most `maxEdgeMm`, so that it can take the label's shape (OpenSim's pelvis has 122
//     vertices); the subdivided triangles lie on the reference's, so its shape is unchanged.
//  2. An affine ICP (fit/affine_icp.h) onto points spread over the label's boundary inside the scan
//     (meshing::withinScan: where the field of view cuts the bone the cap is the scan's edge, not bone).
//  3. Non-rigid rounds: each vertex inside the field of view is pulled to its closest point on the label's
//     boundary, and each boundary point pulls its closest vertex (both ways, so the mesh neither skips a
//     process of the label nor piles up on one side of it); the pulls are averaged per vertex, continued
//     harmonically to the vertices beyond the field of view (transfer/surface_harmonic_extension.h: the
//     bone beyond the scan follows without a step) down to none at `fadeMm` from it, and smoothed over
//     the mesh by `smoothing` Laplacian passes that halve each round (coarse to fine, as non-rigid ICP
//     anneals its stiffness: Amberg et al., "Optimal step nonrigid ICP algorithms for surface
//     registration", CVPR 2007).
// Deviation: Dicko et al. 2013 registers each bone by one affine map (rule R1 keeps bones straight); a patient's
// bone differs from the reference's by more than an affine map, and its own label is the truth inside the
// field of view, so the rounds follow the label there. Beyond it the moves fade to none, so a femur's
// shaft and knee stay where the bone's placement put them.
#pragma once

#include "vesalius/core/label_map.h"
#include "vesalius/core/mesh.h"

#include <string>
#include <vector>

namespace vesalius::patient {

struct BoneOntoLabelOptions {
  double maxEdgeMm = 2.0;  // step 1: refine to this mean edge (two thirds of the shipped CT's 3 mm voxel)
  int affineTargets = 1500;  // step 2: points on the label's boundary; 0: no affine step (the bone is placed)
  int rounds = 12;           // step 3
  int smoothing = 32;        // Laplacian passes of the moves in the first round; halved each round
  // Beyond the field of view the moves fade out: vertices farther than this from the scan's box keep
  // their place (the bone placed as a whole, e.g. by the transfer, stays placed there), mm.
  double fadeMm = 40.0;
};

struct BoneOntoLabel {
  TriMesh mesh;                  // the bone's mesh, refined, on the label; faces keep the bone's orientation
  long verticesInFieldOfView = 0;
  double boundaryToMeshMeanMm = 0, boundaryToMeshMaxMm = 0;  // the label's boundary inside the scan to `mesh`
};

// bone: a closed bone surface (#V by 3, #F by 3), mm LPS, already near the label (the completed reference's
// bone, reference_completion.h). ids: the label(s) that are this bone in `labels` (their union is the
// target). Throws BadInput naming `labelsSource` when the labels have no boundary inside the scan, and
// naming `boneSource` for a bone mesh without triangles.
BoneOntoLabel registerBoneOntoLabel(const TriMesh& bone, const LabelMap& labels, const std::vector<Label>& ids,
                                    const BoneOntoLabelOptions& options, const std::string& boneSource,
                                    const std::string& labelsSource);

}  // namespace vesalius::patient
