// MRI tissue classes on real scans. On the Colin27 T1 head the brain-extracted version of the same scan
// (ch2bet, made by BET) is an independent reference: the body must be one component without holes, the
// brain must lie in soft tissue, and above the skull base the bone class must separate the brain from
// the scalp. On the abdominal MR, TotalSegmentator's organs must lie in the body and not in the outer
// layers.
#include "vesalius/segmentation/mri_tissues.h"

#include "vesalius/core/error.h"
#include "vesalius/io/image_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace vesalius::segmentation {
namespace {

const std::string kHead = std::string(VESALIUS_TESTDATA) + "/head-mri/";
const std::string kAbdomen = std::string(VESALIUS_TESTDATA) + "/mr-abdomen/";

// World height (LPS z, mm) below which the skull base has its natural openings (foramen magnum, optic
// canals, orbits) on Colin27: MNI z = -21 mm, under the temporal lobes' lowest third.
constexpr double kSkullBaseZ = -21.0;

Mask positive(const Image& image) {
  Mask out(image.geometry);
  for (std::size_t n = 0; n < out.values.size(); ++n) out.values[n] = image.values[n] > 0;
  return out;
}

// Voxels whose centre lies below world height z.
Mask below(const GridGeometry& g, double z) {
  Mask out(g);
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i) out.at(i, j, k) = g.indexToWorld(Eigen::Vector3d(i, j, k)).z() < z;
  return out;
}

double fraction(const Mask& part, const Mask& whole) {
  return double(countVoxels(maskAnd(part, whole))) / double(countVoxels(whole));
}

class HeadMri : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const Image scan = io::readScan(kHead + "ch2.nii.gz");
    ours_ = new LabelMap(segmentMriTissues(scan));
    brain_ = new Mask(positive(io::readScan(kHead + "ch2bet.nii.gz")));
  }
  static void TearDownTestSuite() {
    delete ours_;
    delete brain_;
  }
  Mask scalp() const { return maskOr(maskOf(ours_->labels, kMriSkin), maskOf(ours_->labels, kMriSubcutaneousFat)); }
  static LabelMap* ours_;
  static Mask* brain_;
};
LabelMap* HeadMri::ours_ = nullptr;
Mask* HeadMri::brain_ = nullptr;

TEST_F(HeadMri, LabelsKeepTheScanGeometryAndTable) {
  EXPECT_EQ(ours_->labels.geometry.size, Eigen::Vector3i(181, 217, 181));
  EXPECT_EQ(ours_->table.resolve("skin"), kMriSkin);
  EXPECT_EQ(ours_->table.resolve("subcutaneous_fat"), kMriSubcutaneousFat);
  EXPECT_EQ(ours_->table.resolve("bone"), kMriBone);
  EXPECT_EQ(ours_->table.resolve("soft_tissue"), kMriSoftTissue);
}

TEST_F(HeadMri, BodyIsOneComponentWithoutHoles) {
  const Mask body = nonZeroMask(ours_->labels);
  EXPECT_EQ(countVoxels(body), countVoxels(largestComponent(body)));
  EXPECT_EQ(countVoxels(body), countVoxels(fillHoles3d(body)));
  EXPECT_EQ(fraction(body, *brain_), 1.0);
  // The head down to the upper neck: 4.09 L measured.
  const double litres = countVoxels(body) * 1e-6;  // 1 mm voxels
  RecordProperty("body_litres", std::to_string(litres));
  EXPECT_GT(litres, 3.9);
  EXPECT_LT(litres, 4.3);
}

TEST_F(HeadMri, BrainIsSoftTissueNotBoneOrScalp) {
  // Measured: 99.54 % soft tissue; 0.46 % bone (CSF-dark sulci at the brain's edge); none scalp.
  const double bone = fraction(maskOf(ours_->labels, kMriBone), *brain_);
  RecordProperty("brain_in_bone", std::to_string(bone));
  EXPECT_GT(fraction(maskOf(ours_->labels, kMriSoftTissue), *brain_), 0.99);
  EXPECT_LT(bone, 0.01);
  EXPECT_EQ(countVoxels(maskAnd(scalp(), *brain_)), 0);
}

TEST_F(HeadMri, SkullSeparatesBrainFromScalpAboveTheSkullBase) {
  // With a lid closing the skull base, whatever the skull encloses is a hole of skull + lid (holes are
  // 6-connected background regions, so no 6-connected path leads from them to the scalp).
  const Mask lid = below(ours_->labels.geometry, kSkullBaseZ);
  const Mask wall = maskOr(maskOf(ours_->labels, kMriBone), lid);
  const Mask enclosed = maskAndNot(fillHoles3d(wall), wall);
  const double brainEnclosed = fraction(enclosed, maskAndNot(*brain_, lid));
  RecordProperty("brain_enclosed", std::to_string(brainEnclosed));
  EXPECT_GT(brainEnclosed, 0.99);  // 0.996 measured; the rest is brain labelled bone
  EXPECT_EQ(countVoxels(maskAnd(enclosed, scalp())), 0);
}

TEST_F(HeadMri, ScalpFatLiesOutsideTheSkull) {
  // Above the skull base the scalp fat is at least the skull's thickness away from the brain: 6.7 mm
  // nearest, 11.7 mm median measured.
  const Grid<float> toBrain = distanceToMaskMm(*brain_);
  const Mask fat =
      maskAndNot(maskOf(ours_->labels, kMriSubcutaneousFat), below(ours_->labels.geometry, kSkullBaseZ));
  std::vector<float> d;
  for (std::size_t n = 0; n < fat.values.size(); ++n)
    if (fat.values[n]) d.push_back(toBrain.values[n]);
  ASSERT_GT(d.size(), 100000u);
  std::sort(d.begin(), d.end());
  RecordProperty("fat_brain_min_mm", std::to_string(d.front()));
  EXPECT_GE(d.front(), 5.0);
  EXPECT_GT(d[d.size() / 2], 10.0);
  // Class volumes (ml, 1 mm voxels), measured 246 / 277 / 717: a 2 mm skin over a 4.1 L head, the scalp
  // fat, and the skull with the CSF layer under it.
  EXPECT_NEAR(countVoxels(maskOf(ours_->labels, kMriSkin)) / 1000.0, 246, 15);
  EXPECT_NEAR(countVoxels(maskOf(ours_->labels, kMriSubcutaneousFat)) / 1000.0, 277, 40);
  EXPECT_NEAR(countVoxels(maskOf(ours_->labels, kMriBone)) / 1000.0, 717, 80);
}

TEST(AbdomenMri, BodyHoldsTheOrgansAndTheOuterLayersDoNot) {
  const Image scan = io::readScan(kAbdomen + "example_mr_sm.nii.gz");
  const LabelMap ours = segmentMriTissues(scan);
  const LabelMap theirs = io::readLabelMap(kAbdomen + "example_seg_mr.nii.gz", kAbdomen + "labels_total_mr.tsv");
  const Mask body = nonZeroMask(ours.labels);
  const Mask organs = nonZeroMask(theirs.labels);
  EXPECT_EQ(countVoxels(body), countVoxels(largestComponent(body)));
  EXPECT_EQ(countVoxels(body), countVoxels(fillHoles3d(body)));
  // Every TotalSegmentator label lies in our body; none is skin or subcutaneous fat (both measured exactly).
  EXPECT_EQ(fraction(body, organs), 1.0);
  const Mask outer = maskOr(maskOf(ours.labels, kMriSkin), maskOf(ours.labels, kMriSubcutaneousFat));
  EXPECT_EQ(countVoxels(maskAnd(outer, organs)), 0);
  // The bright fat ring is found (5.1 % of the body measured; its inner part, darkened by the surface
  // coil's falloff, stays soft tissue).
  EXPECT_GT(fraction(maskOf(ours.labels, kMriSubcutaneousFat), body), 0.04);
}

TEST(MriTissues, RejectsAConstantScan) {
  Image flat(GridGeometry{Eigen::Vector3i(8, 8, 8)}, 7.0f);
  EXPECT_THROW(segmentMriTissues(flat), BadInput);
}

}  // namespace
}  // namespace vesalius::segmentation
