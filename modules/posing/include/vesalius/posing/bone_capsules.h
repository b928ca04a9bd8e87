// Bone regions of a tet mesh from a skeleton alone, for bodies without bone meshes (the rig of Sujar et al. 2018,
// §3.2, labels "bones' voxels" from the bone models; MakeHuman's body ships a skeleton but no bones).
//
// Deviation from the paper, stated: each bone is a capsule around its segment (joint to tail) instead of
// a bone mesh. The segment is trimmed by endTrim of its length at both ends, so that the tissue around a
// joint belongs to no bone and blends between its two neighbours (as cartilage does between real bones);
// the capsule's radius is radiusFraction of the smallest distance from the trimmed segment to the skin,
// so it stays inside the limb (a forearm capsule is thinner than a thigh's); a segment that leaves the
// body gets no capsule. A vertex inside several capsules belongs to the one whose axis is nearest
// relative to its radius.
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/core/skeleton.h"

#include <Eigen/Core>

namespace vesalius::posing {

struct BoneCapsuleOptions {
  double radiusFraction = 0.4;  // capsule radius / distance of the segment to the skin, in (0, 1)
  double endTrim = 0.15;        // fraction of the segment removed at each end, in [0, 0.5)
  int samples = 16;             // points along the segment where the distance to the skin is measured
};

// V: #V by 3 tet mesh vertices, skeleton: at rest, in the same space (mm), skin: the closed body surface.
// Returns #V: the joint whose bone holds the vertex, or -1. Joints without a tail have no bone. Throws
// UsageError on options out of range, BadInput if the skin has no triangles.
Eigen::VectorXi boneCapsuleVertices(const MatrixX3d& V, const Skeleton& skeleton, const TriMesh& skin,
                                    const BoneCapsuleOptions& options = {});

}  // namespace vesalius::posing
