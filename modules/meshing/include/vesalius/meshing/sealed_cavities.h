// The cavities of a body: space outside its closed surface that is shut off from the outside once the
// surface's openings narrower than a given width are sealed. MakeHuman's skin, like a real face, is a
// surface whose mouth and nostrils are pockets reaching into the head; the teeth and the palate lie in
// them, outside the surface, though inside the head by any anatomical account. Rules R5 and R6 of
// Dicko et al. 2013 (tissue inside the skin) are measured against the body with its cavities.
//
// Method: the morphological closing of the inside by a ball of diameter `openingMm` (dilation, then
// erosion), then the background the closing encloses (not reachable from the grid's border through voxels
// outside the closing, 6-connected). Only the enclosed background counts: concave places of the outer
// surface that the closing fills (a crease, the gap between two toes) are not cavities. The closing is
// read off the signed distance, which is exact near the surface: a voxel outside the surface is in the
// dilation where its distance is below the ball's radius r, and in the closing where every voxel centre
// within r of it is in the dilation. On a grid the opening width holds to within about a voxel.
// Not segmentation::closeMm and fillHoles3d: those are ITK's (meshing stays free of it), and on the
// full body's 46M-voxel grid they took 6-13 s a call against 0.6 s here, where only the voxels within r
// of the surface need the ball test.
#pragma once

#include "vesalius/core/grid.h"

#include <cstdint>

namespace vesalius::meshing {

// 1 at the voxels of the cavities, 0 elsewhere, on the geometry of `signedDistance` (mm, negative
// inside, as meshSignedDistance writes it, with a band of at least openingMm / 2; any spacing). Voxels
// beyond the grid are open space. Throws UsageError if openingMm is not positive or finite.
Grid<std::uint8_t> sealedCavities(const Grid<float>& signedDistance, double openingMm);

}  // namespace vesalius::meshing
