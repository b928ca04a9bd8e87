// `vesalius labels` end to end on the TotalSegmentator map of the test CT (3 mm voxels): each action's
// voxels against the input's, world positions kept by crop, and one-line refusals that write nothing.
#include "run_command.h"
#include "test_data.h"

#include "vesalius/io/image_io.h"
#include "vesalius/segmentation/label_ops.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

namespace vesalius::test {
namespace {

namespace fs = std::filesystem;
namespace seg = segmentation;

constexpr Label kLiver = 5, kPancreas = 10, kL4 = 19, kHipLeft = 90, kHipRight = 91, kSacrum = 92;

const LabelMap& input() {
  static const LabelMap map = io::readLabelMap(kCtLabels, kCtLabelTable);
  return map;
}

// A fresh output path (and no label tables beside it) in this test's folder.
std::string outputPath(const std::string& name) {
  const fs::path path = fs::path(outputDir()) / name;
  fs::remove(path);
  for (const std::string& table : io::labelTableSidecarPaths(path.string())) fs::remove(table);
  return path.string();
}

// `vesalius labels ACTION --labels <the test map> --table <its table> ARGS --out OUT`, which must succeed.
LabelMap runLabels(const std::string& action, std::vector<std::string> args, const std::string& out,
                   std::string* printed = nullptr) {
  args.insert(args.begin(), {"labels", action, "--labels", kCtLabels, "--table", kCtLabelTable});
  args.insert(args.end(), {"--out", out, "--progress", "none"});
  const CommandResult r = runVesalius(args);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  if (printed) *printed = r.out;
  return io::readLabelMap(out);  // with the table written beside it
}

std::int64_t count(const LabelMap& map, Label id) {
  return std::count(map.labels.values.begin(), map.labels.values.end(), id);
}

std::int64_t count(const seg::Mask& mask) { return seg::countVoxels(mask); }

bool contains(const seg::Mask& outer, const seg::Mask& inner) { return count(seg::maskAndNot(inner, outer)) == 0; }

TEST(CliLabels, ExtractKeepsTheLiverAndNothingElse) {
  const std::int64_t liver = count(input(), kLiver);
  ASSERT_GT(liver, 10000);
  std::string printed;
  const LabelMap out = runLabels("extract", {"--label", "liver"}, outputPath("liver.nii.gz"), &printed);
  EXPECT_EQ(count(out, kLiver), liver);
  EXPECT_EQ(count(out, 0), std::int64_t(out.labels.values.size()) - liver);
  ASSERT_EQ(out.table.entries.size(), 1u);
  EXPECT_EQ(out.table.entries[0].name, "liver");
  EXPECT_TRUE(out.labels.geometry.size == input().labels.geometry.size);
  // 27 mm^3 voxels: the printed millilitres are the voxel count times 0.027.
  char ml[32];
  std::snprintf(ml, sizeof ml, "%.1f", double(liver) * 0.027);
  expectContains(printed, "liver (5): " + std::to_string(liver) + " -> " + std::to_string(liver) + " voxels, " + ml);
}

TEST(CliLabels, MergeJoinsTheHipsUnderOneId) {
  const std::int64_t left = count(input(), kHipLeft), right = count(input(), kHipRight);
  ASSERT_GT(left, 1000);
  ASSERT_GT(right, 1000);
  const LabelMap out = runLabels("merge", {"--label", "hip_left", "--label", "hip_right", "--into", "200:hips"},
                                 outputPath("hips.nii.gz"));
  EXPECT_EQ(count(out, 200), left + right);
  EXPECT_EQ(count(out, kHipLeft), 0);
  EXPECT_EQ(count(out, kHipRight), 0);
  ASSERT_NE(out.table.find(200), nullptr);
  EXPECT_EQ(out.table.find(200)->name, "hips");
  EXPECT_EQ(out.table.find(kHipLeft), nullptr);
  std::int64_t changedElsewhere = 0;
  for (std::size_t n = 0; n < out.labels.values.size(); ++n) {
    const Label was = input().labels.values[n];
    changedElsewhere += was != kHipLeft && was != kHipRight && out.labels.values[n] != was;
  }
  EXPECT_EQ(changedElsewhere, 0);
}

TEST(CliLabels, RelabelDeletesAndRenumbers) {
  const std::int64_t liver = count(input(), kLiver), hipLeft = count(input(), kHipLeft);
  const LabelMap out =
      runLabels("relabel", {"--map", "hip_left=0", "--map", "liver=150"}, outputPath("relabelled.nii.gz"));
  EXPECT_EQ(count(out, kHipLeft), 0);
  EXPECT_EQ(count(out, kLiver), 0);
  EXPECT_EQ(count(out, 150), liver);
  EXPECT_EQ(count(out, 0), count(input(), 0) + hipLeft);
  ASSERT_NE(out.table.find(150), nullptr);
  EXPECT_EQ(out.table.find(150)->name, "liver");
  EXPECT_EQ(out.table.find("hip_left"), nullptr);
  EXPECT_EQ(count(out, kHipRight), count(input(), kHipRight));
}

// Closing with a 3 mm ball contains the liver and adds little to it; with --overwrite it is exactly a
// dilation followed by an erosion, done as two commands.
TEST(CliLabels, MorphCloseContainsTheLiverAndKeepsItsVolume) {
  const seg::Mask liver = seg::maskOf(input().labels, kLiver);
  const LabelMap closed =
      runLabels("morph", {"--label", "liver", "--op", "close", "--radius-mm", "3"}, outputPath("closed.nii.gz"));
  const seg::Mask closedLiver = seg::maskOf(closed.labels, kLiver);
  EXPECT_TRUE(contains(closedLiver, liver));
  const double ratio = double(count(closedLiver)) / double(count(liver));
  RecordProperty("close_volume_ratio", std::to_string(ratio));
  EXPECT_GE(ratio, 1.0);
  EXPECT_LE(ratio, 1.03);
  // Without --overwrite the liver took background voxels only.
  EXPECT_EQ(count(seg::maskAnd(seg::maskAndNot(closedLiver, liver), seg::nonZeroMask(input().labels))), 0);

  const std::string dilatedPath = outputPath("dilated.nii.gz");
  const LabelMap dilated =
      runLabels("morph", {"--label", "liver", "--op", "dilate", "--radius-mm", "3", "--overwrite"}, dilatedPath);
  EXPECT_TRUE(contains(seg::maskOf(dilated.labels, kLiver), liver));
  EXPECT_GT(count(dilated, kLiver), count(closedLiver));
  const std::string eroded = outputPath("dilated-eroded.nii.gz");
  const CommandResult r = runVesalius({"labels", "morph", "--labels", dilatedPath, "--label", "liver", "--op", "erode",
                                       "--radius-mm", "3", "--out", eroded});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const LabelMap closedOverwrite =
      runLabels("morph", {"--label", "liver", "--op", "close", "--radius-mm", "3", "--overwrite"},
                outputPath("closed-ow.nii.gz"));
  const seg::Mask a = seg::maskOf(io::readLabelMap(eroded).labels, kLiver),
                  b = seg::maskOf(closedOverwrite.labels, kLiver);
  EXPECT_EQ(count(seg::maskAndNot(a, b)) + count(seg::maskAndNot(b, a)), 0);
  EXPECT_TRUE(contains(b, liver));
}

// The pancreas of this map lies in three 26-connected pieces: 425, 390 and 3 voxels.
TEST(CliLabels, ComponentsKeepTheLargestOrThoseAboveAVolume) {
  const seg::Mask pancreas = seg::maskOf(input().labels, kPancreas);
  ASSERT_EQ(count(pancreas), 818);
  const LabelMap largest =
      runLabels("components", {"--label", "pancreas", "--largest"}, outputPath("pancreas-largest.nii.gz"));
  const seg::Mask one = seg::maskOf(largest.labels, kPancreas);
  EXPECT_EQ(count(one), 425);
  EXPECT_EQ(count(seg::largestComponent(one)), count(one));  // a single component
  EXPECT_TRUE(contains(pancreas, one));
  EXPECT_EQ(count(largest, 0), count(input(), 0) + 818 - 425);

  const LabelMap big =
      runLabels("components", {"--label", "pancreas", "--min-ml", "1"}, outputPath("pancreas-1ml.nii.gz"));
  const seg::Mask kept = seg::maskOf(big.labels, kPancreas);
  EXPECT_EQ(count(kept), 815);
  EXPECT_TRUE(contains(pancreas, kept));
  EXPECT_TRUE(contains(kept, one));
  // 1 mL is 37.04 voxels of 27 mm^3: every piece left has at least 38.
  EXPECT_EQ(count(seg::removeSmallComponents(kept, 38)), 815);
}

// Filling takes background only: what is left of a label's holes holds other labels. The sacrum has a
// 5-voxel hole in 3-D; L4's spinal canal, open at its top and bottom, is a hole in axial slices only.
TEST(CliLabels, FillClosesBackgroundHoles) {
  const seg::Mask sacrum = seg::maskOf(input().labels, kSacrum);
  const LabelMap filled = runLabels("fill", {"--label", "sacrum"}, outputPath("sacrum-filled.nii.gz"));
  const seg::Mask after = seg::maskOf(filled.labels, kSacrum);
  EXPECT_EQ(count(after), count(sacrum) + 5);
  EXPECT_TRUE(contains(after, sacrum));
  EXPECT_EQ(count(seg::maskAnd(seg::maskAndNot(after, sacrum), seg::nonZeroMask(input().labels))), 0);
  EXPECT_EQ(count(seg::maskAnd(seg::fillHoles3d(after), seg::maskOf(filled.labels, 0))), 0);

  const seg::Mask l4 = seg::maskOf(input().labels, kL4);
  const LabelMap axial = runLabels("fill", {"--label", "vertebrae_L4", "--axial"}, outputPath("l4-filled.nii.gz"));
  const seg::Mask canal = seg::maskAndNot(seg::maskOf(axial.labels, kL4), l4);
  RecordProperty("l4_canal_ml", std::to_string(double(count(canal)) * 0.027));
  EXPECT_EQ(count(seg::fillHoles3d(l4)), count(l4));  // no hole in 3-D
  EXPECT_EQ(count(canal), 102);
  EXPECT_EQ(count(seg::maskAnd(canal, seg::nonZeroMask(input().labels))), 0);
  const int axis = seg::axialAxis(axial.labels.geometry);
  EXPECT_EQ(
      count(seg::maskAnd(seg::fillHolesSliceWise(seg::maskOf(axial.labels, kL4), axis), seg::maskOf(axial.labels, 0))),
      0);
}

TEST(CliLabels, CropKeepsEveryLiverVoxelWhereItWas) {
  const LabelMap out = runLabels("crop", {"--to-label", "liver", "--margin-mm", "6"}, outputPath("liver-box.nii.gz"));
  const GridGeometry &gi = input().labels.geometry, &go = out.labels.geometry;
  EXPECT_EQ(count(out, kLiver), count(input(), kLiver));
  // 6 mm is two 3 mm voxels each side of the liver's bounds, clipped to the grid.
  Eigen::Vector3i lo = gi.size, hi = Eigen::Vector3i::Zero();
  for (int k = 0; k < gi.size.z(); ++k)
    for (int j = 0; j < gi.size.y(); ++j)
      for (int i = 0; i < gi.size.x(); ++i)
        if (input().labels.at(i, j, k) == kLiver) {
          lo = lo.cwiseMin(Eigen::Vector3i(i, j, k));
          hi = hi.cwiseMax(Eigen::Vector3i(i, j, k));
        }
  const Eigen::Vector3i expected = (hi.array() + 3).min(gi.size.array()) - (lo.array() - 2).max(0);
  EXPECT_EQ(go.size, expected) << go.size.transpose() << " vs " << expected.transpose();
  EXPECT_LT(go.voxelCount(), gi.voxelCount() / 2);
  // Every liver voxel of the crop is a liver voxel of the input at the same LPS position (mm).
  std::int64_t moved = 0, checked = 0;
  for (int k = 0; k < go.size.z(); ++k)
    for (int j = 0; j < go.size.y(); ++j)
      for (int i = 0; i < go.size.x(); ++i) {
        if (out.labels.at(i, j, k) != kLiver) continue;
        const Eigen::Vector3d at = gi.worldToIndex(go.indexToWorld(Eigen::Vector3d(i, j, k)));
        const Eigen::Vector3i ijk = at.array().round().cast<int>();
        moved += (at - ijk.cast<double>()).norm() > 1e-6 || input().labels.at(ijk.x(), ijk.y(), ijk.z()) != kLiver;
        ++checked;
      }
  EXPECT_EQ(moved, 0);
  EXPECT_EQ(checked, count(input(), kLiver));
  // The first liver voxel of the input, by its LPS position before and after.
  const auto first = std::find(input().labels.values.begin(), input().labels.values.end(), kLiver);
  const std::int64_t n = first - input().labels.values.begin();
  const Eigen::Vector3d ijk(double(n % gi.size.x()), double(n / gi.size.x() % gi.size.y()),
                            double(n / (std::int64_t(gi.size.x()) * gi.size.y())));
  const Eigen::Vector3d lps = gi.indexToWorld(ijk);
  const Eigen::Vector3d inCrop = go.worldToIndex(lps);
  const Eigen::Vector3i c = inCrop.array().round().cast<int>();
  EXPECT_LT((inCrop - c.cast<double>()).norm(), 1e-6);
  EXPECT_EQ(out.labels.at(c.x(), c.y(), c.z()), kLiver);
  EXPECT_LT((go.indexToWorld(c.cast<double>()) - lps).norm(), 1e-6);
}

TEST(CliLabels, UnknownLabelIsRefusedByName) {
  const std::string out = outputPath("unknown.nii.gz");
  const CommandResult r = runVesalius(
      {"labels", "extract", "--labels", kCtLabels, "--table", kCtLabelTable, "--label", "appendix_vermiformis", "--out", out});
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_EQ(r.err, "vesalius: " + kCtLabels +
                       ": no label 'appendix_vermiformis' (neither an id nor a name in its "
                       "label table)\n");
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliLabels, LabelWithoutVoxelsIsRefused) {
  const std::string out = outputPath("empty.nii.gz");
  const CommandResult r =
      runVesalius({"labels", "fill", "--labels", kCtLabels, "--table", kCtLabelTable, "--label", "777", "--out", out});
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_EQ(r.err, "vesalius: " + kCtLabels + ": no voxel has label 777\n");
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliLabels, OutputOverTheInputIsRefused) {
  // A copy of the map with its table beside it, so the input could be replaced if it were not refused.
  const std::string copy = outputPath("copy.nii.gz");
  fs::copy_file(kCtLabels, copy);
  fs::copy_file(kCtLabelTable, io::labelTableSidecarPath(copy));
  const auto size = fs::file_size(copy);
  for (const std::string& out : {copy, (fs::path(outputDir()) / "copy.nrrd").string()}) {
    const CommandResult r =
        runVesalius({"labels", "extract", "--labels", copy, "--label", "liver", "--out", out, "--force"});
    EXPECT_EQ(r.exitCode, 2) << out;
    // The map itself is refused with every command's check of its options; its table beside it, which
    // no option names, by labels' own.
    if (out == copy)
      EXPECT_EQ(r.err, "vesalius: " + copy + ": --out names the input --labels " + copy +
                           "; an output never replaces an input, --force or not\n");
    else
      EXPECT_EQ(r.err, "vesalius: " + io::labelTableSidecarPath(copy) + ": is an input of this command; choose another --out\n");
  }
  EXPECT_EQ(fs::file_size(copy), size);
  EXPECT_EQ(io::readLabelMap(copy).table.entries.size(), 104u);
}

struct BadArgs {
  std::string name;
  std::vector<std::string> args;
  std::string error;
};

class LabelsRefuses : public ::testing::TestWithParam<BadArgs> {};

TEST_P(LabelsRefuses, WithOneLine) {
  const std::string out = outputPath("refused.nii.gz");
  std::vector<std::string> args{"labels"};
  args.insert(args.end(), GetParam().args.begin(), GetParam().args.end());
  args.insert(args.end(), {"--labels", kCtLabels, "--table", kCtLabelTable, "--out", out});
  const CommandResult r = runVesalius(args);
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_EQ(r.err, "vesalius: " + GetParam().error + "\n");
  EXPECT_FALSE(fs::exists(out));
}

INSTANTIATE_TEST_SUITE_P(
    BadOptions, LabelsRefuses,
    ::testing::Values(
        BadArgs{"map_without_equals",
                {"relabel", "--map", "liver:3"},
                "--map 'liver:3': expected OLD=NEW, OLD a label id or name, NEW an id 0..65535 (0 deletes)"},
        BadArgs{"map_to_a_name",
                {"relabel", "--map", "liver=spleen"},
                "--map 'liver=spleen': expected OLD=NEW, OLD a label id or name, NEW an id 0..65535 (0 deletes)"},
        BadArgs{"map_onto_a_label",
                {"relabel", "--map", "liver=1"},
                "relabelling would give labels 1 and 5 the same id 1; merge them instead"},
        BadArgs{"negative_radius",
                {"morph", "--label", "liver", "--op", "dilate", "--radius-mm", "-2"},
                "--radius-mm must be a number of mm > 0"},
        BadArgs{"new_id_without_name",
                {"merge", "--label", "hip_left", "--label", "hip_right", "--into", "200"},
                "--into '200': id 200 is new; name it with --into 200:NAME"},
        BadArgs{"name_of_another_label",
                {"merge", "--label", "hip_left", "--label", "hip_right", "--into", "200:sacrum"},
                "--into '200:sacrum': the name sacrum belongs to label sacrum (92)"},
        BadArgs{"negative_margin", {"crop", "--margin-mm", "-1"}, "crop margin must be a finite number of mm >= 0"},
        BadArgs{"components_needs_a_rule",
                {"components", "--label", "liver"},
                "labels components: give one of --largest and --min-ml"}),
    [](const auto& info) { return info.param.name; });

TEST(CliLabels, EveryActionHasHelpWithAnExample) {
  for (const std::string action : {"extract", "merge", "relabel", "components", "fill", "morph", "crop"}) {
    const CommandResult r = runVesalius({"labels", action, "--help"});
    EXPECT_EQ(r.exitCode, 0) << action;
    expectContains(r.out, "vesalius labels " + action + " --labels");
  }
}

}  // namespace
}  // namespace vesalius::test
