// Sampling a grid between its voxel centres, in continuous index space (voxel centres at integer indices,
// GridGeometry::worldToIndex gives the index of a world point).
#pragma once

#include "vesalius/core/grid.h"

#include <Eigen/Core>

namespace vesalius {

// Whether `index` lies within half a voxel of the voxel centres of a grid of `size`, i.e. in its voxels.
bool insideVoxels(const Eigen::Vector3d& index, const Eigen::Vector3i& size);

// Trilinear interpolation at `index`, clamped to the grid first: beyond the outermost voxel centres the
// edge values extend, and a one-voxel axis is constant.
double sampleTrilinear(const Grid<float>& grid, const Eigen::Vector3d& index);

}  // namespace vesalius
