// The voxels of a grid inside a broken surface (holes, non-manifold edges, crossing or duplicated
// triangles, as OpenSim's bone meshes have): where the generalized winding number is at least 1/2
// (Jacobson, Kavan, Sorkine-Hornung, "Robust inside-outside segmentation using generalized winding
// numbers", SIGGRAPH 2013, §3-4), evaluated at the voxel centres by the fast dipole tree of
// winding_number.h (Barill et al. 2018). The sign is taken so that the mesh's enclosed volume is positive:
// a mesh given inside out voxelizes as the right way round.
//
// Only voxels whose centres lie in the mesh's bounding box (in index space) are evaluated; the others
// are 0. Beyond a face of the box the whole surface lies on one side of a plane, so a surface closed up to
// holes is seen under less than half the sphere there (winding number < 1/2): the box costs nothing in
// accuracy and saves evaluating a large grid around a small bone (rig --reference voxelizes each bone of
// a body this way). For a closed, consistently oriented mesh meshInsideMask (mesh_volume.h) is faster.
#pragma once

#include "vesalius/core/grid.h"
#include "vesalius/core/mesh.h"
#include "vesalius/meshing/winding_number.h"

#include <cstdint>

namespace vesalius::meshing {

// mesh: #V by 3 (mm), #F by 3 in any orientation; grid: any geometry that validates (oblique too).
// Returns 1 where the voxel centre's winding number is >= 1/2, 0 elsewhere (values as segmentation::Mask).
// Throws BadInput if the mesh has no triangles, a non-finite vertex or a bad index; UsageError on bad options.
Grid<std::uint8_t> windingNumberMask(const TriMesh& mesh, const GridGeometry& grid,
                                     const WindingNumberOptions& options = {});

}  // namespace vesalius::meshing
