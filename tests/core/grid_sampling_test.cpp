// Sampling a grid between voxel centres: exact on a linear ramp (anisotropic spacing), clamped beyond the
// edge voxels, constant along a one-voxel axis; which indices lie in the voxels.
#include "vesalius/core/grid_sampling.h"

#include <gtest/gtest.h>

namespace vesalius {
namespace {

Grid<float> ramp(const Eigen::Vector3i& size) {
  GridGeometry g;
  g.size = size;
  g.spacing = {2, 1, 1};
  Grid<float> grid(g);
  for (int k = 0; k < size.z(); ++k)
    for (int j = 0; j < size.y(); ++j)
      for (int i = 0; i < size.x(); ++i) grid.at(i, j, k) = float(3 * i + j - k);
  return grid;
}

TEST(GridSampling, TrilinearIsExactOnALinearRampAndClampedBeyondTheEdge) {
  const Grid<float> grid = ramp({4, 4, 4});
  EXPECT_NEAR(sampleTrilinear(grid, {1.5, 1.5, 0.25}), 3 * 1.5 + 1.5 - 0.25, 1e-12);
  EXPECT_NEAR(sampleTrilinear(grid, {3.0, 3.0, 3.0}), 9 + 3 - 3, 1e-12);  // the last voxel centre
  EXPECT_NEAR(sampleTrilinear(grid, {-5, 0, 0}), 0, 1e-12);
  EXPECT_NEAR(sampleTrilinear(grid, {3.4, 0, 0}), 9, 1e-12);
}

TEST(GridSampling, AOneVoxelAxisIsConstant) {
  const Grid<float> grid = ramp({4, 4, 1});
  EXPECT_NEAR(sampleTrilinear(grid, {1.25, 2.0, 0.4}), 3 * 1.25 + 2, 1e-12);
  EXPECT_NEAR(sampleTrilinear(grid, {1.25, 2.0, -0.4}), 3 * 1.25 + 2, 1e-12);
}

TEST(GridSampling, InsideVoxelsReachesHalfAVoxelBeyondTheCentres) {
  const Eigen::Vector3i size(4, 3, 1);
  EXPECT_TRUE(insideVoxels({-0.5, -0.5, -0.5}, size));
  EXPECT_TRUE(insideVoxels({3.5, 2.5, 0.5}, size));
  EXPECT_FALSE(insideVoxels({3.51, 1, 0}, size));
  EXPECT_FALSE(insideVoxels({1, 1, -0.6}, size));
}

}  // namespace
}  // namespace vesalius
