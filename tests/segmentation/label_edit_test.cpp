// Label-map editing with known answers on small grids, and on TotalSegmentator's map of the test CT:
// extract by name, merge, relabel, crop with exact world geometry.
#include "vesalius/segmentation/label_edit.h"

#include "vesalius/core/error.h"
#include "vesalius/io/image_io.h"

#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace vesalius::segmentation {
namespace {

// A 6 x 5 x 4 map, labels 1 (voxel (1,1,1)), 2 (the block (2..3, 1..2, 1..2)) and 3 (voxel (5,4,3)),
// on an oblique, anisotropic grid so that crops must honour direction and spacing.
LabelMap smallMap() {
  GridGeometry g;
  g.size = Eigen::Vector3i(6, 5, 4);
  g.origin = Eigen::Vector3d(10, -20, 5);
  g.spacing = Eigen::Vector3d(0.5, 1.0, 2.0);
  g.direction = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  LabelMap map;
  map.labels = Grid<Label>(g, 0);
  map.labels.at(1, 1, 1) = 1;
  for (int k = 1; k <= 2; ++k)
    for (int j = 1; j <= 2; ++j)
      for (int i = 2; i <= 3; ++i) map.labels.at(i, j, k) = 2;
  map.labels.at(5, 4, 3) = 3;
  map.table.add({1, "liver", {{200, 0, 0}}});
  map.table.add({2, "spleen", {{0, 200, 0}}});
  map.table.add({3, "kidney_left", {{0, 0, 200}}});
  return map;
}

std::int64_t count(const LabelMap& map, Label id) { return countVoxels(maskOf(map.labels, id)); }

TEST(LabelEdit, ExtractsByIdAndByName) {
  const LabelMap map = smallMap();
  const LabelMap byName = extractLabels(map, std::vector<std::string>{"Spleen", "3"});
  EXPECT_EQ(count(byName, 1), 0);
  EXPECT_EQ(count(byName, 2), 8);
  EXPECT_EQ(count(byName, 3), 1);
  ASSERT_EQ(byName.table.entries.size(), 2u);
  EXPECT_EQ(byName.table.entries[0].name, "spleen");
  EXPECT_EQ(byName.table.entries[1].name, "kidney_left");
  EXPECT_EQ(byName.labels.values, extractLabels(map, std::vector<Label>{2, 3}).labels.values);
  EXPECT_THROW(extractLabels(map, std::vector<std::string>{"heart"}), UsageError);
}

TEST(LabelEdit, MergesSeveralIdsIntoOne) {
  const LabelMap merged = mergeLabels(smallMap(), {1, 3}, {7, "organs", {{9, 9, 9}}});
  EXPECT_EQ(count(merged, 1), 0);
  EXPECT_EQ(count(merged, 3), 0);
  EXPECT_EQ(count(merged, 7), 2);
  EXPECT_EQ(count(merged, 2), 8);
  ASSERT_EQ(merged.table.entries.size(), 2u);
  EXPECT_EQ(merged.table.resolve("organs"), 7);
  EXPECT_EQ(merged.table.find(Label(1)), nullptr);
  // Merging into one of the merged ids renames it.
  const LabelMap intoTwo = mergeLabels(smallMap(), {1, 2}, {2, "liver_and_spleen"});
  EXPECT_EQ(count(intoTwo, 2), 9);
  EXPECT_EQ(intoTwo.table.find(Label(2))->name, "liver_and_spleen");
  EXPECT_THROW(mergeLabels(smallMap(), {1}, {0, "background"}), UsageError);
}

TEST(LabelEdit, RelabelsAndRefusesCollisions) {
  const LabelMap swapped = relabel(smallMap(), {{1, 2}, {2, 1}, {3, 0}});
  EXPECT_EQ(count(swapped, 1), 8);
  EXPECT_EQ(count(swapped, 2), 1);
  EXPECT_EQ(count(swapped, 3), 0);
  EXPECT_EQ(swapped.table.find(Label(1))->name, "spleen");
  EXPECT_EQ(swapped.table.find(Label(2))->name, "liver");
  EXPECT_EQ(swapped.table.find(Label(3)), nullptr);
  EXPECT_THROW(relabel(smallMap(), {{1, 2}}), UsageError);  // 1 would join the untouched 2
}

TEST(LabelEdit, BoundsWithAMarginInMm) {
  const LabelMap map = smallMap();
  const VoxelBox tight = maskBounds(maskOf(map.labels, 2));
  EXPECT_EQ(tight.lo, Eigen::Vector3i(2, 1, 1));
  EXPECT_EQ(tight.hi, Eigen::Vector3i(4, 3, 3));
  // 1 mm is 2 voxels along i (0.5 mm), 1 along j, 1 along k (2 mm, rounded up); clipped to the grid.
  const VoxelBox grown = maskBounds(maskOf(map.labels, 2), 1.0);
  EXPECT_EQ(grown.lo, Eigen::Vector3i(0, 0, 0));
  EXPECT_EQ(grown.hi, Eigen::Vector3i(6, 4, 4));
  EXPECT_THROW(maskBounds(Mask(map.labels.geometry, 0)), BadInput);
  EXPECT_THROW(maskBounds(maskOf(map.labels, 2), -1.0), UsageError);
}

TEST(LabelEdit, CropKeepsEveryVoxelWhereItWas) {
  const LabelMap map = smallMap();
  const VoxelBox box = maskBounds(maskOf(map.labels, 2), 0.5);
  const LabelMap crop = cropLabelMap(map, box);
  EXPECT_EQ(crop.labels.geometry.size, box.size());
  EXPECT_EQ(count(crop, 2), 8);
  EXPECT_EQ(crop.table.find(Label(3)), nullptr);  // cropped away with its voxel
  const GridGeometry& g = map.labels.geometry;
  for (int k = 0; k < crop.labels.geometry.size.z(); ++k)
    for (int j = 0; j < crop.labels.geometry.size.y(); ++j)
      for (int i = 0; i < crop.labels.geometry.size.x(); ++i) {
        const Eigen::Vector3i source = box.lo + Eigen::Vector3i(i, j, k);
        EXPECT_EQ(crop.labels.at(i, j, k), map.labels.at(source.x(), source.y(), source.z()));
        EXPECT_LT((crop.labels.geometry.indexToWorld(Eigen::Vector3d(i, j, k)) -
                   g.indexToWorld(source.cast<double>())).norm(), 1e-12);
      }
  EXPECT_THROW(cropGeometry(g, VoxelBox{Eigen::Vector3i(0, 0, 0), Eigen::Vector3i(7, 1, 1)}), UsageError);
}

TEST(LabelEdit, LiverOfTotalSegmentatorByNameCroppedExactly) {
  const std::string dir = std::string(VESALIUS_TESTDATA) + "/ct-abdomen-pelvis/";
  const LabelMap map = io::readLabelMap(dir + "example_seg.nii.gz", dir + "labels_total_v2.tsv");
  const LabelMap liver = extractLabels(map, std::vector<std::string>{"liver"});
  ASSERT_EQ(liver.table.entries.size(), 1u);
  EXPECT_EQ(liver.table.entries[0].id, 5);
  const std::int64_t voxels = count(liver, 5);
  EXPECT_EQ(voxels, count(map, 5));
  EXPECT_EQ(countVoxels(nonZeroMask(liver.labels)), voxels);
  ASSERT_GT(voxels, 10000);

  const VoxelBox box = maskBounds(maskOf(liver.labels, 5), 6.0);  // two 3 mm voxels each side
  const LabelMap crop = cropLabelMap(liver, box);
  EXPECT_EQ(count(crop, 5), voxels);
  EXPECT_LT(crop.labels.values.size(), liver.labels.values.size());
  const GridGeometry& g = map.labels.geometry;
  EXPECT_LT((crop.labels.geometry.indexToWorld(Eigen::Vector3d::Zero()) - g.indexToWorld(box.lo.cast<double>()))
                .norm(),
            1e-9);
  // The liver's centroid in world mm is the same before and after.
  Eigen::Vector3d before = Eigen::Vector3d::Zero(), after = Eigen::Vector3d::Zero();
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i)
        if (liver.labels.at(i, j, k) == 5) before += g.indexToWorld(Eigen::Vector3d(i, j, k));
  const GridGeometry& c = crop.labels.geometry;
  for (int k = 0; k < c.size.z(); ++k)
    for (int j = 0; j < c.size.y(); ++j)
      for (int i = 0; i < c.size.x(); ++i)
        if (crop.labels.at(i, j, k) == 5) after += c.indexToWorld(Eigen::Vector3d(i, j, k));
  EXPECT_LT((before - after).norm() / double(voxels), 1e-9);
}

}  // namespace
}  // namespace vesalius::segmentation
