// `vesalius segment --modality mri` end to end on the head MRI: the label map, its table and picture, the
// same labels as the library gives, one Slicer progress bar over its stages, a skull surface by name, help and usage errors.
#include "run_command.h"

#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/segmentation/mri_tissues.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <sstream>
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
  // One bar over the command: the first stage starts it, the others name themselves in comments, and the
  // whole command's fraction only grows.
  expectContains(r.out, "<filter-start><filter-name>body</filter-name>");
  for (const char* stage : {"skin", "fat and bone"}) expectContains(r.out, std::string("<filter-comment>") + stage);
  std::istringstream lines(r.out);
  long starts = 0, ends = 0;
  double last = -1;
  for (std::string line; std::getline(lines, line);) {
    starts += line.rfind("<filter-start>", 0) == 0;
    ends += line.rfind("<filter-end>", 0) == 0;
    const std::string tag = "<filter-progress>";
    if (line.rfind(tag, 0) != 0) continue;
    const double value = std::stod(line.substr(tag.size()));
    EXPECT_GT(value, last) << line;
    last = value;
  }
  std::cout << starts << " start, " << ends << " end, the whole command's fraction last " << last << '\n';
  EXPECT_EQ(starts, 1);
  EXPECT_EQ(ends, 1);
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
