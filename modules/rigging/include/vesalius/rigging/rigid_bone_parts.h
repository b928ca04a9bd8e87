// The rigid parts of a posed scan or label map (posing/posed_volume.h): the voxels inside the rig's bone
// meshes that move rigidly with their joints (AnatomyRig::meshJoint), so that a re-posed bone label moves
// exactly as its mesh does rather than as the tets around it.
#pragma once

#include "vesalius/core/anatomy_rig.h"
#include "vesalius/core/grid.h"
#include "vesalius/core/mesh.h"
#include "vesalius/posing/posed_volume.h"

#include <Eigen/Geometry>

#include <vector>

namespace vesalius::rigging {

// rig: its meshes' rest shapes in `restMeshes` (one per rig.meshes, #V by 3 mm LPS with their faces) and
// their posed vertices in `posedMeshes` (posing::RigPoser::carry); world: the joints' posed world
// transforms; scan: the grid of the volume to re-pose; out: the posed volume's grid. Part j + 1 is joint
// j; a voxel inside posed bone meshes of two joints belongs to none (the tets carry it). Each posed bone
// mesh is voxelized by its generalized winding number (meshing/winding_mask.h), since OpenSim's bone meshes
// have holes. A bone whose rest mesh misses the scan's grid has nothing of the scan to carry and is
// skipped. A rig that moves no mesh rigidly gives no parts (RigidParts::restFromPosed empty). Throws
// BadInput if the mesh counts disagree.
posing::RigidParts rigidBoneParts(const AnatomyRig& rig, const std::vector<TriMesh>& restMeshes,
                                  const std::vector<MatrixX3d>& posedMeshes,
                                  const std::vector<Eigen::Isometry3d>& world, const GridGeometry& scan,
                                  const GridGeometry& out);

}  // namespace vesalius::rigging
