// The picker's slice frames and extents, on an axis-aligned and on an oblique grid.
#include "slice_geometry.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>

namespace vesalius::picker {
namespace {

TEST(SliceGeometry, FramesAreRightHandedAndShowRadiologically) {
  for (SliceAxis axis : kSliceAxes) {
    const SliceFrame frame = SliceFrame::of(axis);
    EXPECT_NEAR((frame.planeToWorld().transpose() * frame.planeToWorld() - Eigen::Matrix3d::Identity()).norm(),
                0, 1e-12);
    EXPECT_NEAR(frame.planeToWorld().determinant(), 1, 1e-12) << sliceAxisName(axis);
    EXPECT_NEAR(std::abs(frame.forward.dot(frame.normal)), 1, 1e-12);
    const Eigen::Vector3d world(3, -4, 5);
    EXPECT_NEAR((frame.toWorld(frame.toPlane(world)) - world).norm(), 0, 1e-12);
  }
  // Patient left (+x in LPS) on the screen's right in axial and coronal; anterior (-y) up in axial.
  EXPECT_EQ(SliceFrame::of(SliceAxis::Axial).right, Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(SliceFrame::of(SliceAxis::Axial).up, Eigen::Vector3d(0, -1, 0));
  EXPECT_EQ(SliceFrame::of(SliceAxis::Sagittal).right, Eigen::Vector3d(0, 1, 0));  // anterior on the left
  EXPECT_EQ(SliceFrame::of(SliceAxis::Coronal).forward, Eigen::Vector3d(0, -1, 0));  // next slice: anterior
}

TEST(SliceGeometry, ExtentOfAnAxisAlignedGrid) {
  GridGeometry grid;
  grid.size = {11, 21, 5};
  grid.spacing = {0.5, 1, 3};
  grid.origin = {10, 20, 30};
  const SliceExtent axial = sliceExtent(grid, SliceFrame::of(SliceAxis::Axial));
  EXPECT_NEAR((axial.centre - Eigen::Vector3d(12.5, -30, -36)).norm(), 0, 1e-12);
  EXPECT_NEAR((axial.halfSize - Eigen::Vector3d(2.5, 10, 6)).norm(), 0, 1e-12);
  EXPECT_NEAR(axial.depthStep, 3, 1e-12);
  EXPECT_NEAR(sliceExtent(grid, SliceFrame::of(SliceAxis::Sagittal)).depthStep, 0.5, 1e-12);
}

TEST(SliceGeometry, StepOfAnObliqueGridMovesAtMostOneVoxel) {
  GridGeometry grid;
  grid.size = {10, 10, 10};
  grid.spacing = {1, 1, 2};
  grid.direction = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()).toRotationMatrix();  // pitched
  const SliceFrame axial = SliceFrame::of(SliceAxis::Axial);
  const SliceExtent extent = sliceExtent(grid, axial);
  const Eigen::Vector3d indexChange = grid.worldToIndex(axial.normal * extent.depthStep) - grid.worldToIndex({0, 0, 0});
  EXPECT_NEAR(indexChange.cwiseAbs().maxCoeff(), 1, 1e-12);
  // k runs along (0, -sin, cos): one step of 2 mm along k is 2 / cos(0.3) mm of depth, j's share is smaller.
  EXPECT_NEAR(extent.depthStep, std::min(2 / std::cos(0.3), 1 / std::sin(0.3)), 1e-12);
}

}  // namespace
}  // namespace vesalius::picker
