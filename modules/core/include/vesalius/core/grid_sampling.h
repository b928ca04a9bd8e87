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
double sampleTrilinear(const Grid<double>& grid, const Eigen::Vector3d& index);

// The voxels whose centres may lie within `radius` (mm) of the world point p: the index box (clamped to the
// grid, inclusive; empty when lo > hi on an axis) bounding the ball. `indexPerWorld` is the inverse of
// direction · diag(spacing); a world offset r maps to the index offset indexPerWorld · r, whose a-th
// component is at most radius · |row a of indexPerWorld|.
struct IndexBox {
  Eigen::Vector3i lo, hi;
};
IndexBox indexBoxAroundBall(const GridGeometry& geometry, const Eigen::Matrix3d& indexPerWorld,
                            const Eigen::Vector3d& p, double radius);

}  // namespace vesalius
