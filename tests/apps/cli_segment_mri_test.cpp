// `vesalius segment --modality mri` end to end on the head MRI: the label map, its table and picture, the
// same labels as the library gives, Slicer progress stages, a skull surface by name, help and usage errors.
#include "run_command.h"

#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/segmentation/mri_tissues.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace vesalius::test {
namespace {

namespace fs = std::filesystem;

const std::string kHead = std::string(VESALIUS_TESTDATA) + "/head-mri/ch2.nii.gz";

TEST(CliSegmentMri, HeadGivesTheLibraryLabelsWithTableAndPicture) {
  const std::string labels = outputDir() + "/head.nii.gz";
  const CommandResult r = runVesalius(
      {"segment", "--scan", kHead, "--modality", "mri", "--out", labels, "--force", "--progress", "slicer"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const char* stage : {"body", "skin", "fat and bone"})
    expectContains(r.out, std::string("<filter-name>") + stage + "</filter-name>");
  EXPECT_TRUE(fs::exists(outputDir() + "/head.tsv"));
  EXPECT_GT(fs::file_size(outputDir() + "/head.png"), 10000u);

  const LabelMap written = io::readLabelMap(labels);
  const Image scan = io::readScan(kHead);
  EXPECT_EQ(written.labels.geometry.size, scan.geometry.size);
  EXPECT_LT((written.labels.geometry.origin - scan.geometry.origin).norm(), 1e-6);
  EXPECT_EQ(written.labels.values, segmentation::segmentMriTissues(scan).labels.values);
  for (const char* name : {"skin", "subcutaneous_fat", "bone", "soft_tissue"})
    EXPECT_NO_THROW(written.table.resolve(name)) << name;

  const std::string skull = outputDir() + "/skull.stl";
  const CommandResult s =
      runVesalius({"surface", "--labels", labels, "--label", "bone", "--out", skull, "--force", "--progress", "none"});
  ASSERT_EQ(s.exitCode, 0) << s.err;
  const io::TriMeshSummary summary = io::summarize(io::readTriMesh(skull));
  EXPECT_TRUE(summary.closed);
  ASSERT_TRUE(summary.volume.has_value());
  // The skull class holds 717 ml of voxels; the surface must enclose about that.
  EXPECT_NEAR(*summary.volume / 1000.0, 717.0, 30.0);
}

TEST(CliSegmentMri, HelpShowsTheMriExampleAndUnknownModalitiesAreUsageErrors) {
  const CommandResult help = runVesalius({"segment", "--help"});
  EXPECT_EQ(help.exitCode, 0);
  expectContains(help.out, "--modality mri");
  expectContains(help.out, "head-mri/ch2.nii.gz");
  const CommandResult pet =
      runVesalius({"segment", "--scan", kHead, "--modality", "pet", "--out", outputDir() + "/pet.nii.gz"});
  EXPECT_EQ(pet.exitCode, 2);
  EXPECT_FALSE(fs::exists(outputDir() + "/pet.nii.gz"));
}

}  // namespace
}  // namespace vesalius::test
