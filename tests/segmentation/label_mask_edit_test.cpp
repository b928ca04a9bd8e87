// Mask edits put back into a label map (segmentation/label_mask_edit.h), on painted maps of isotropic and
// anisotropic voxels: a dilated label takes background voxels only, or with overwrite those of its
// neighbour too; an eroded label's lost voxels become background; a hole holding another label is filled
// only with overwrite; components below a volume go and the largest one stays; labels not edited and the
// table never change; bad volumes and radii are refused.
#include "vesalius/segmentation/label_mask_edit.h"

#include "vesalius/core/error.h"

#include "test_label_maps.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <iostream>

namespace vesalius::segmentation {
namespace {

std::int64_t count(const LabelMap& m, Label id) {
  std::int64_t n = 0;
  for (Label v : m.labels.values) n += v == id;
  return n;
}

// Voxels that hold `id` in `after` but something else in `before`, by what they held.
std::int64_t taken(const LabelMap& before, const LabelMap& after, Label id, Label from) {
  std::int64_t n = 0;
  for (std::size_t i = 0; i < before.labels.values.size(); ++i)
    n += after.labels.values[i] == id && before.labels.values[i] == from;
  return n;
}

std::vector<GridGeometry> grids() {
  GridGeometry iso;
  iso.size = {40, 40, 40};
  iso.spacing = {1, 1, 1};
  GridGeometry aniso;
  aniso.size = {50, 50, 16};
  aniso.spacing = {0.8, 0.8, 2.5};
  return {iso, aniso};
}

// Two boxes side by side: label 1 on x < 20 mm, label 2 on x >= 20 mm, both within 8..32 mm in y and z.
LabelMap twoBoxes(const GridGeometry& g) {
  LabelMap m = test::paintedLabelMap(g, [](const Eigen::Vector3d& p) {
    if (p.y() < 8 || p.y() > 32 || p.z() < 8 || p.z() > 32 || p.x() < 4 || p.x() > 30) return 0;
    return p.x() < 20 ? 1 : 2;
  });
  m.table.entries = {{1, "left", {255, 0, 0}}, {2, "right", {0, 255, 0}}};
  return m;
}

TEST(LabelMaskEdit, DilationTakesBackgroundOnlyUnlessOverwrite) {
  for (const GridGeometry& g : grids()) {
    const LabelMap map = twoBoxes(g);
    const LabelMap kept = editLabelMasks(map, {1}, {MaskEdit::Dilate, 0, 3.0});
    const LabelMap over = editLabelMasks(map, {1}, {MaskEdit::Dilate, 0, 3.0, true});
    std::cout << g.spacing.transpose() << " mm voxels: dilated by 3 mm, label 1 took " << taken(map, kept, 1, 0)
              << " background voxels and " << taken(map, kept, 1, 2) << " of label 2; with overwrite "
              << taken(map, over, 1, 2) << " of label 2\n";
    EXPECT_GT(taken(map, kept, 1, 0), 0);
    EXPECT_EQ(taken(map, kept, 1, 2), 0);
    EXPECT_EQ(count(kept, 2), count(map, 2));
    EXPECT_GT(taken(map, over, 1, 2), 0);
    EXPECT_EQ(count(over, 2), count(map, 2) - taken(map, over, 1, 2));
    EXPECT_EQ(kept.table.entries.size(), 2u);
  }
}

TEST(LabelMaskEdit, ErodedVoxelsBecomeBackground) {
  for (const GridGeometry& g : grids()) {
    const LabelMap map = twoBoxes(g);
    const LabelMap eroded = editLabelMasks(map, {2}, {MaskEdit::Erode, 0, 2.0});
    const std::int64_t lost = count(map, 2) - count(eroded, 2);
    EXPECT_GT(lost, 0);
    EXPECT_EQ(count(eroded, 0), count(map, 0) + lost);
    EXPECT_EQ(count(eroded, 1), count(map, 1));
  }
}

TEST(LabelMaskEdit, HolesAndComponents) {
  for (const GridGeometry& g : grids()) {
    // A shell of label 1 (radius 6 to 12 mm around the centre) holding label 3 in its middle (to 3 mm) and
    // background between, and a small blob of label 1 away from it.
    const Eigen::Vector3d c = g.indexToWorld(((g.size.cast<double>().array() - 1) / 2).matrix());
    LabelMap map = test::paintedLabelMap(g, [&](const Eigen::Vector3d& p) {
      const double r = (p - c).norm();
      if (r <= 3) return 3;
      if (r >= 6 && r <= 12) return 1;
      return (p - c - Eigen::Vector3d(16, 10, 0)).norm() <= 3 ? 1 : 0;
    });
    const std::int64_t hole = count(map, 0) - count(editLabelMasks(map, {1}, {MaskEdit::FillHoles}), 0);
    const LabelMap over = editLabelMasks(map, {1}, {MaskEdit::FillHoles, 0, 0, true});
    EXPECT_GT(hole, 0);
    EXPECT_EQ(count(editLabelMasks(map, {1}, {MaskEdit::FillHoles}), 3), count(map, 3));
    EXPECT_EQ(count(over, 3), 0);
    const LabelMap largest = editLabelMasks(map, {1}, {MaskEdit::LargestComponent});
    const double voxelMl = g.spacing.prod() / 1000.0;
    const std::int64_t blob = count(map, 1) - count(largest, 1);
    std::cout << g.spacing.transpose() << " mm voxels: hole " << hole << " voxels, blob " << blob << " voxels\n";
    EXPECT_GT(blob, 0);
    // Components of at least the blob's volume plus a voxel: the blob goes, the shell stays.
    const LabelMap dropped = editLabelMasks(map, {1}, {MaskEdit::DropSmallComponents, (blob + 1) * voxelMl});
    EXPECT_EQ(count(dropped, 1), count(largest, 1));
    EXPECT_EQ(count(dropped, 0), count(map, 0) + blob);
  }
}

TEST(LabelMaskEdit, BadVolumeOrRadiusIsUsageError) {
  const LabelMap map = twoBoxes(grids().front());
  EXPECT_THROW(editLabelMasks(map, {1}, {MaskEdit::DropSmallComponents, -1}), UsageError);
  EXPECT_THROW(editLabelMasks(map, {1}, {MaskEdit::Close, 0, 0}), UsageError);
  EXPECT_THROW(editLabelMasks(map, {1}, {MaskEdit::Open, 0, std::nan("")}), UsageError);
}

}  // namespace
}  // namespace vesalius::segmentation
