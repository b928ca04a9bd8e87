// The labelled image of Sujar et al. 2018, §3.2 from meshes ("skin and bones voxelized into a labelled image"): a
// body's skin and its bone meshes voxelized on one grid, for `rig --reference` (and the skin's inside for
// `rig --skin`).
// - The body is the voxels inside the skin (meshInsideMask, mesh_volume.h: the skin must be closed, as
//   MakeHuman's and a label surface are), opened by one voxel and cut to its largest face-connected part:
//   parts a voxel or two thin (finger tips, toes at coarse voxels) would otherwise give flat surface
//   pieces TetGen cannot seed, and parts joined to the body only at a voxel's edge or corner (a thin
//   body's finger tips) separate shells whose vertices reach no bone.
// - Each bone is the body's voxels where the generalized winding number of one of its meshes is at least
//   1/2 (winding_mask.h), which holds on OpenSim's open, non-manifold and self-crossing meshes, where
//   meshInsideMask would refuse or flood them. Bone voxels outside the body are dropped (the placed
//   OpenSim hands and toes reach through MakeHuman's skin); where two bones overlap the later one wins.
#pragma once

#include "vesalius/core/label_map.h"
#include "vesalius/core/mesh.h"
#include "vesalius/segmentation/label_ops.h"

#include <string>
#include <vector>

namespace vesalius::rigging {

// The body mask above on `grid`. Throws BadInput naming `source` if the skin is open or empty.
segmentation::Mask skinInsideMask(const TriMesh& skin, const GridGeometry& grid, const std::string& source);

struct BoneMeshes {
  std::string name;                   // the label's name in the map's table
  std::vector<const TriMesh*> meshes;  // mm LPS, each voxelized by its own winding number
};

// Label b + 1 for bones[b], label bones.size() + 1 ("body") for the rest of the body, 0 outside; the
// table names them. Throws BadInput naming `source` as skinInsideMask does or if a bone mesh is broken
// beyond indexing (no triangles, a bad index, a non-finite vertex).
LabelMap boneMeshLabelMap(const TriMesh& skin, const std::vector<BoneMeshes>& bones, const GridGeometry& grid,
                          const std::string& source);

}  // namespace vesalius::rigging
