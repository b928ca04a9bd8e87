// A closed 2-manifold surface from a broken one (holes, non-manifold edges, duplicated or crossing
// triangles), such as OpenSim's bone meshes, so that TetGen can mesh it.
//
// Method (docs/methods/closed-surfaces.md): the solid is where the generalized winding number is at least
// 1/2 (Jacobson, Kavan, Sorkine-Hornung, "Robust inside-outside segmentation using generalized winding
// numbers", SIGGRAPH 2013, §3-4), sampled at the voxel centres of a grid covering the mesh
// (coveringGrid, mesh_volume.h) by the fast hierarchical evaluation of winding_number.h (Barill et al.
// 2018). The voxel solid is made well-composed and turned into a surface as a label is (labelSurface,
// label_surface.h: flying edges, windowed-sinc smoothing, decimation to a face count, the voxel volume
// restored, no crossing triangles). A hole closes along the surface a soap film would span; a flap or a
// fin (two triangles back to back) has no inside and disappears, and so do pieces of the solid smaller than
// 2x2x2 voxels (where the approximate winding number beside a fin strays above 1/2). Details below one voxel
// are lost: the grid's resolution is the accuracy (measured in tests/meshing/closed_surface_test.cpp).
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/meshing/winding_number.h"

namespace vesalius::meshing {

struct ClosedSurfaceOptions {
  // Voxels along the longest side of the mesh's bounding box (any units). Finer keeps finer detail, and
  // holes and handles of the solid that a decimated surface keeps.
  int resolution = 64;
  int targetFaces = 0;           // decimate to about this many triangles; 0 keeps the iso-surface's
  int smoothingIterations = 20;  // windowed-sinc iterations of labelSurface (0 or >= 2)
  WindingNumberOptions winding;
};

// mesh: #V by 3, #F by 3, in any units (mm inside Vesalius). Returns a closed, outward, 2-manifold surface
// without crossing triangles, in the same units; attributes and uv are not carried. A mesh given inside
// out (negative enclosed volume) is read the other way round. Throws BadInput if the mesh has no
// triangles, a non-finite vertex, a bad index or no extent, or encloses no voxel; UsageError on bad options.
TriMesh closedSurface(const TriMesh& mesh, const ClosedSurfaceOptions& options = {});

}  // namespace vesalius::meshing
