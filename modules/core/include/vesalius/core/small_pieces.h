// Pieces of a mask below a size: the specks a threshold or a winding number leaves.
#pragma once

#include "vesalius/core/grid.h"

#include <cstdint>

namespace vesalius {

// Clears (sets to 0) every 26-connected piece of nonzero voxels of `mask` with fewer than `minVoxels`
// voxels (face, edge and corner neighbours all join a piece), and sets the voxels kept to 1; returns the
// number of voxels cleared. Linear in the voxels; the working memory is a stack of up to one piece's voxels.
std::int64_t dropSmallPieces(Grid<std::uint8_t>& mask, std::int64_t minVoxels);

}  // namespace vesalius
