// CT tissue classes checked against labels made by someone else: TotalSegmentator's subcutaneous-fat and
// skeletal-muscle masks and the union of its bone labels on the 30-slice crop of the test CT, and the body
// mask of the whole CT.
#include "vesalius/segmentation/ct_tissues.h"

#include "vesalius/core/error.h"
#include "vesalius/io/image_io.h"

#include <gtest/gtest.h>

#include <string>

namespace vesalius::segmentation {
namespace {

const std::string kCt = std::string(VESALIUS_TESTDATA) + "/ct-abdomen-pelvis/";

bool isBoneName(const std::string& name) {
  for (const char* part : {"vertebrae_", "rib_", "hip_", "sacrum", "femur_", "humerus_", "scapula_",
                           "clavicula_", "sternum", "skull"})
    if (name.find(part) != std::string::npos) return true;
  return false;
}

Mask theirBone(const LabelMap& theirs) {
  Mask bone(theirs.labels.geometry, 0);
  for (const LabelEntry& e : theirs.table.entries)
    if (isBoneName(e.name)) bone = maskOr(bone, maskOf(theirs.labels, e.id));
  return bone;
}

class CtCrop : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ct_ = new Image(io::readScan(kCt + "example_ct_sm.nii.gz"));
    ours_ = new LabelMap(segmentCtTissues(*ct_));
  }
  static void TearDownTestSuite() {
    delete ct_;
    delete ours_;
  }
  static Image* ct_;
  static LabelMap* ours_;
};
Image* CtCrop::ct_ = nullptr;
LabelMap* CtCrop::ours_ = nullptr;

TEST_F(CtCrop, LabelsKeepTheScanGeometryAndTable) {
  EXPECT_EQ(ours_->labels.geometry.size, ct_->geometry.size);
  EXPECT_TRUE(ours_->labels.geometry.direction.isApprox(ct_->geometry.direction));
  EXPECT_TRUE(ours_->labels.geometry.origin.isApprox(ct_->geometry.origin));
  EXPECT_EQ(ours_->table.resolve("subcutaneous_fat"), kCtSubcutaneousFat);
  EXPECT_EQ(ours_->table.resolve("bone"), kCtBone);
}

TEST_F(CtCrop, SubcutaneousFatMatchesTotalSegmentator) {
  const LabelMap theirs = io::readLabelMap(kCt + "example_seg_tissue_types/subcutaneous_fat.nii.gz");
  const double dice = diceCoefficient(maskOf(ours_->labels, kCtSubcutaneousFat), nonZeroMask(theirs.labels));
  RecordProperty("dice_subcutaneous_fat", std::to_string(dice));
  EXPECT_GE(dice, VESALIUS_DICE_SUBCUTANEOUS_FAT) << dice;
}

TEST_F(CtCrop, BoneMatchesTheUnionOfTotalSegmentatorBones) {
  const LabelMap theirs = io::readLabelMap(kCt + "example_seg.nii.gz", kCt + "labels_total_v2.tsv");
  const double dice = diceCoefficient(maskOf(ours_->labels, kCtBone), theirBone(theirs));
  RecordProperty("dice_bone", std::to_string(dice));
  EXPECT_GE(dice, VESALIUS_DICE_BONE) << dice;
}

// We have no muscle class: muscle is soft tissue, with the organs. Reported: the Dice of our soft tissue
// against their skeletal muscle (low by design: it holds the organs too), and the share of their muscle
// that we call soft tissue, which must be high.
TEST_F(CtCrop, SkeletalMuscleIsInOurSoftTissue) {
  const LabelMap theirs = io::readLabelMap(kCt + "example_seg_tissue_types/skeletal_muscle.nii.gz");
  const Mask muscle = nonZeroMask(theirs.labels), soft = maskOf(ours_->labels, kCtSoftTissue);
  const double dice = diceCoefficient(soft, muscle);
  const double share = double(countVoxels(maskAnd(soft, muscle))) / double(countVoxels(muscle));
  RecordProperty("dice_soft_tissue_vs_skeletal_muscle", std::to_string(dice));
  RecordProperty("skeletal_muscle_in_soft_tissue", std::to_string(share));
  EXPECT_GE(share, 0.93) << share;  // measured 0.947; the rest is mostly voxels in the fat range
}

TEST(CtBody, WholeCtBodyIsOneComponentWithoutHoles) {
  const Image ct = io::readScan(kCt + "example_ct.nii.gz");
  const Mask body = segmentCtBody(ct, CtTissueOptions{});
  EXPECT_EQ(countVoxels(body), countVoxels(largestComponent(body)));
  EXPECT_EQ(countVoxels(body), countVoxels(fillHoles3d(body)));
  // An adult abdomen and pelvis over 336 mm: between 20 and 40 litres.
  const double bodyMl = countVoxels(body) * ct.geometry.spacing.prod() / 1000.0;
  EXPECT_GT(bodyMl, 20000.0);
  EXPECT_LT(bodyMl, 40000.0);
}

TEST(CtBody, RejectsAScanWithNoBody) {
  Image air(GridGeometry{Eigen::Vector3i(8, 8, 8)}, -1000.0f);
  EXPECT_THROW(segmentCtTissues(air), BadInput);
}

}  // namespace
}  // namespace vesalius::segmentation
