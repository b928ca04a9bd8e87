// GridGeometry: index <-> world with an oblique direction, orientation codes, validation.
#include "vesalius/core/error.h"
#include "vesalius/core/grid.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <set>
#include <string>

namespace vesalius {
namespace {

GridGeometry obliqueGeometry() {
  GridGeometry g;
  g.size = Eigen::Vector3i(10, 20, 30);
  g.origin = Eigen::Vector3d(-120.5, 33.25, 7.0);
  g.spacing = Eigen::Vector3d(0.5, 0.75, 2.0);
  g.direction = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  return g;
}

TEST(GridGeometry, IndexToWorldFollowsItkPhysicalSpace) {
  const GridGeometry g = obliqueGeometry();
  const Eigen::Vector3d index(3, 4.5, -2);
  const Eigen::Vector3d expected = g.origin + g.direction * g.spacing.asDiagonal() * index;
  EXPECT_NEAR((g.indexToWorld(index) - expected).norm(), 0.0, 1e-12);
  EXPECT_NEAR((g.indexToWorld(Eigen::Vector3d::Zero()) - g.origin).norm(), 0.0, 1e-12);
  // Moving one voxel along i moves spacing[0] along the first direction column.
  const Eigen::Vector3d step =
      g.indexToWorld(Eigen::Vector3d(1, 0, 0)) - g.indexToWorld(Eigen::Vector3d::Zero());
  EXPECT_NEAR((step - 0.5 * g.direction.col(0)).norm(), 0.0, 1e-12);
}

TEST(GridGeometry, WorldToIndexInvertsIndexToWorld) {
  const GridGeometry g = obliqueGeometry();
  for (const Eigen::Vector3d& index :
       {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(9, 19, 29), Eigen::Vector3d(2.25, -1.5, 14.75),
        Eigen::Vector3d(-40, 100, 3.5)}) {
    EXPECT_NEAR((g.worldToIndex(g.indexToWorld(index)) - index).norm(), 0.0, 1e-12);
  }
  const Eigen::Vector3d world(10, -20, 30);
  EXPECT_NEAR((g.indexToWorld(g.worldToIndex(world)) - world).norm(), 0.0, 1e-12);
}

TEST(GridGeometry, MatrixAgreesWithIndexToWorld) {
  const GridGeometry g = obliqueGeometry();
  const Eigen::Matrix4d M = g.indexToWorldMatrix();
  const Eigen::Vector3d index(1.5, 2, 3);
  const Eigen::Vector4d h = M * index.homogeneous();
  EXPECT_NEAR((h.head<3>() - g.indexToWorld(index)).norm(), 0.0, 1e-12);
  EXPECT_EQ(M.row(3), Eigen::RowVector4d(0, 0, 0, 1));
}

TEST(GridGeometry, OrientationCodes) {
  GridGeometry g;
  EXPECT_EQ(g.orientationCode(), "LPS");
  g.direction = Eigen::Vector3d(-1, -1, 1).asDiagonal();
  EXPECT_EQ(g.orientationCode(), "RAS");
  // i along +z (superior), j along +x (left), k along -y (anterior).
  g.direction << 0, 1, 0,   //
      0, 0, -1,             //
      1, 0, 0;
  EXPECT_EQ(g.orientationCode(), "SLA");
  // A small tilt keeps the dominant components.
  g.direction = Eigen::AngleAxisd(0.2, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  EXPECT_EQ(g.orientationCode(), "LPS");
  g.direction = Eigen::Vector3d(1, -1, -1).asDiagonal();
  EXPECT_EQ(g.orientationCode(), "LAI");
}

TEST(GridGeometry, ValidateRejectsBadGeometry) {
  const GridGeometry good = obliqueGeometry();
  EXPECT_NO_THROW(good.validate("scan.nii.gz"));
  auto expectRejected = [](const GridGeometry& g) {
    try {
      g.validate("scan.nii.gz");
      ADD_FAILURE() << "validate accepted a bad geometry";
    } catch (const BadInput& e) {
      EXPECT_EQ(e.file(), "scan.nii.gz");
      EXPECT_NE(std::string(e.what()).find("scan.nii.gz"), std::string::npos);
    }
  };
  GridGeometry g = good;
  g.spacing[1] = 0.0;
  expectRejected(g);
  g.spacing[1] = -1.0;
  expectRejected(g);
  g.spacing[1] = std::numeric_limits<double>::quiet_NaN();
  expectRejected(g);
  g.spacing[1] = std::numeric_limits<double>::infinity();
  expectRejected(g);
  g = good;
  g.direction.col(2) = g.direction.col(0);
  expectRejected(g);
  g = good;
  g.size[2] = 0;
  expectRejected(g);
}

TEST(GridGeometry, LinearIndexRunsIFastest) {
  GridGeometry g;
  g.size = Eigen::Vector3i(4, 5, 6);
  EXPECT_EQ(g.voxelCount(), 120);
  EXPECT_EQ(g.linearIndex(1, 0, 0), 1);
  EXPECT_EQ(g.linearIndex(0, 1, 0), 4);
  EXPECT_EQ(g.linearIndex(0, 0, 1), 20);
  EXPECT_EQ(g.linearIndex(3, 4, 5), 119);
  EXPECT_TRUE(g.contains(3, 4, 5));
  EXPECT_FALSE(g.contains(4, 0, 0));
  EXPECT_FALSE(g.contains(0, -1, 0));
  Grid<int> grid(g, 7);
  EXPECT_EQ(grid.values.size(), 120u);
  grid.at(1, 2, 3) = 42;
  EXPECT_EQ(grid.values[g.linearIndex(1, 2, 3)], 42);
  EXPECT_EQ(grid.at(0, 0, 0), 7);
}

TEST(GridGeometry, PixelTypeNamesAreDistinct) {
  std::set<std::string> names;
  for (PixelType t : {PixelType::UInt8, PixelType::Int8, PixelType::UInt16, PixelType::Int16,
                      PixelType::UInt32, PixelType::Int32, PixelType::Float32, PixelType::Float64}) {
    ASSERT_NE(pixelTypeName(t), nullptr);
    EXPECT_FALSE(std::string(pixelTypeName(t)).empty());
    names.insert(pixelTypeName(t));
  }
  EXPECT_EQ(names.size(), 8u);
}

}  // namespace
}  // namespace vesalius
