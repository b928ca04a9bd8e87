// CT tissue classes on a synthetic phantom whose answer is known by construction: an extruded disk of
// soft tissue with a subcutaneous fat ring inside a one-voxel dermis, a muscle wall, visceral fat, a bone
// rod with low-density marrow, a gas pocket, and a table joined to the body by a one-voxel-wide bridge.
#include "vesalius/core/progress.h"
#include "vesalius/segmentation/ct_tissues.h"

#include <gtest/gtest.h>

namespace vesalius::segmentation {
namespace {

constexpr int kCentre = 45;  // voxel index of the disk axis; 3 mm voxels, so offset n lies at 3n mm

float phantomHu(double x, double y) {  // mm from the axis, y towards posterior
  const double r = std::hypot(x, y);
  auto within = [](double dx, double dy, double radius) { return std::hypot(dx, dy) <= radius; };
  if (y >= 129 && y <= 135 && std::abs(x) <= 120) return 0.0f;  // table
  if (y > 120 && y < 129 && x == 0) return 40.0f;               // bridge to the table, 2 voxels long
  if (r > 120) return -1000.0f;
  if (r > 117) return 40.0f;                  // dermis
  if (r > 95) return -100.0f;                 // subcutaneous fat
  if (r > 85) return 50.0f;                   // muscle wall
  if (within(x - 40, y, 20)) return -100.0f;  // visceral fat
  if (within(x + 40, y, 15)) return -900.0f;  // gas
  if (within(x, y - 40, 9)) return 100.0f;    // marrow
  if (within(x, y - 40, 15)) return 700.0f;   // cortex
  return 40.0f;
}

Image phantom() {
  GridGeometry g;
  g.size = Eigen::Vector3i(91, 91, 8);
  g.spacing = Eigen::Vector3d::Constant(3.0);
  Image ct(g);
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i)
        ct.at(i, j, k) = phantomHu(3.0 * (i - kCentre), 3.0 * (j - kCentre));
  return ct;
}

Label labelAt(const LabelMap& m, int dx, int dy) { return m.labels.at(kCentre + dx, kCentre + dy, 4); }

TEST(CtPhantom, EachStructureGetsItsClass) {
  Progress progress;
  const LabelMap m = segmentCtTissues(phantom(), {}, &progress);
  EXPECT_EQ(labelAt(m, 40, 0), kCtSkin);
  EXPECT_EQ(labelAt(m, -40, 0), kCtSkin);
  EXPECT_EQ(labelAt(m, 36, 0), kCtSubcutaneousFat);
  EXPECT_EQ(labelAt(m, 0, -36), kCtSubcutaneousFat);
  EXPECT_EQ(labelAt(m, 30, 0), kCtSoftTissue);  // muscle wall
  EXPECT_EQ(labelAt(m, 13, 0), kCtFat);         // visceral fat stays inside the wall
  EXPECT_EQ(labelAt(m, 0, 13), kCtBone);        // marrow at 100 HU filled into the bone
  EXPECT_EQ(labelAt(m, 0, 17), kCtBone);        // cortex
  EXPECT_EQ(labelAt(m, -13, 0), kCtAir);        // gas inside the body
  EXPECT_EQ(labelAt(m, 0, 0), kCtSoftTissue);
  EXPECT_EQ(labelAt(m, 0, 44), kCtAir);  // table
  EXPECT_EQ(labelAt(m, 20, 44), kCtAir);
  EXPECT_EQ(labelAt(m, 0, 41), kCtAir);  // bridge
}

TEST(CtPhantom, SkinIsOneVoxelAndTheBodyIncludesTheGas) {
  const Image ct = phantom();
  const LabelMap m = segmentCtTissues(ct);
  EXPECT_EQ(labelAt(m, 39, 0), kCtSubcutaneousFat);
  const Mask body = segmentCtBody(ct, {});
  EXPECT_EQ(body.at(kCentre - 13, kCentre, 4), 1);
  EXPECT_EQ(body.at(kCentre, kCentre + 44, 4), 0);
  // A 5 mm skin reaches the second voxel layer (centre 4.5 mm deep) but not the third (7.5 mm).
  CtTissueOptions thick;
  thick.skinThicknessMm = 5.0;
  const LabelMap t = segmentCtTissues(ct, thick);
  EXPECT_EQ(labelAt(t, 39, 0), kCtSkin);
  EXPECT_EQ(labelAt(t, 38, 0), kCtSubcutaneousFat);
}

TEST(CtPhantom, SplitBoneSeparatesCortexFromMarrow) {
  CtTissueOptions options;
  options.splitBone = true;
  const LabelMap m = segmentCtTissues(phantom(), options);
  EXPECT_EQ(labelAt(m, 0, 13), kCtTrabecularBone);
  EXPECT_EQ(labelAt(m, 0, 17), kCtBone);
  EXPECT_EQ(m.table.find(kCtBone)->name, "cortical_bone");
  EXPECT_EQ(m.table.find(kCtTrabecularBone)->name, "trabecular_bone");
}

}  // namespace
}  // namespace vesalius::segmentation
