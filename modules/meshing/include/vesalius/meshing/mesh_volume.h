// Volumes from closed triangle surfaces: the inside mask and the narrow-band signed distance field of a
// mesh on a given grid, and a grid that covers meshes under a size cap.
//
// Method (docs/methods/voxelization.md): the mesh is mapped into the grid's continuous index space
// (any non-singular direction, oblique, mirrored or sheared; any spacing), where our voxel centres, the
// points origin + direction · diag(spacing) · (i, j, k) as in ITK, are OpenVDB's integer voxels.
// OpenVDB's mesh-to-volume conversion (openvdb::tools::meshToVolume; Museth, "VDB: high-resolution sparse
// volumes with dynamic topology", ACM TOG 32(3), 2013) finds the voxels at the surface and a sign
// everywhere by flood-filling the exterior. Its signs next to the surface come from a heuristic and its
// distances away from it are grown from neighbours, and both err a little; so the voxels near the
// surface (within a voxel, or within the band for distances) are measured exactly: distance to the
// closest point on the triangles (core TriangleTree) and its sign by the angle-weighted pseudonormal
// (Bærentzen and Aanæs, IEEE TVCG 11(3), 2005). The other voxels take the sign of the measured voxels
// they connect to, as no surface passes between two adjacent voxels that are not both near it.
// Meshes that are not consistently oriented 2-manifolds, or whose pieces face different ways (cavities,
// a piece inside out), keep OpenVDB's signs, which count everything unreachable from outside as inside.
// The grid cap follows Sujar et al. 2018, §3.2, which keeps the voxelized body "always smaller than 250x700x120"
// voxels by choosing the voxel size (see CoveringGridOptions).
// Accuracy measured in tests/meshing/mesh_volume_test.cpp and docs/methods/voxelization.md.
#pragma once

#include "vesalius/core/grid.h"
#include "vesalius/core/mesh.h"

#include <cstdint>
#include <vector>

namespace vesalius::meshing {

// 1 where the voxel centre lies inside the closed surface (V #V by 3 mm, F #F by 3), 0 elsewhere, on
// `grid` (its geometry; values as segmentation::Mask). Throws BadInput if the mesh is empty, has
// non-finite vertices or out-of-range indices, or is open (boundary edges); the grid must validate().
Grid<std::uint8_t> meshInsideMask(const TriMesh& mesh, const GridGeometry& grid);

struct SignedDistanceOptions {
  double bandMm = 3.0;  // half width of the narrow band; farther values are clamped to ±bandMm
};

// Signed distance in mm from each voxel centre of `grid` to the closed surface, negative inside.
// Exact within bandMm of the surface; beyond it the value is clamped: -bandMm inside, +bandMm outside.
// Cost: one closest-point query per voxel in the band (about 2 bandMm x area / voxel volume of them).
// Throws BadInput as meshInsideMask, UsageError if bandMm is not positive.
Grid<float> meshSignedDistance(const TriMesh& mesh, const GridGeometry& grid,
                               const SignedDistanceOptions& options = {});

struct CoveringGridOptions {
  double voxelSizeMm = 1.0;  // wanted isotropic voxel size; grown only as far as the cap demands
  double marginMm = 5.0;     // free space around the meshes' bounding box on every side
  // At most this many voxels along i, j, k. Sujar et al. 2018 keeps its body image under 250x700x120 voxels,
  // its x, y, z being width, height and depth of a standing body; in LPS that is i (left) 250,
  // j (posterior, depth) 120, k (superior, height) 700.
  Eigen::Vector3i maxSize = Eigen::Vector3i(250, 120, 700);
};

// An axis-aligned (LPS, identity direction) grid of isotropic voxels whose voxel centres span the
// bounding box of all `meshes` (#V by 3 vertices each) grown by marginMm, centred on it. The voxel size
// is voxelSizeMm, or the smallest size that keeps every axis within maxSize if that is larger.
// Throws BadInput if there are no vertices or a vertex is not finite, UsageError on bad options.
GridGeometry coveringGrid(const std::vector<const TriMesh*>& meshes, const CoveringGridOptions& options = {});

}  // namespace vesalius::meshing
