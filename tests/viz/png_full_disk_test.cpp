// Issue 32: a full disk. The slice picture's writer, and a label map written together with its picture as
// `vesalius segment` writes them (core/atomic_file.h, writeFilesAtomically), must throw a BadInput naming
// an output and leave nothing behind: with room for the labels but not the picture, no labels either.
// The file system is a 2 MB tmpfs the test mounts (full_disk.h); without the right to mount one the test
// is skipped.
#include "vesalius/core/atomic_file.h"
#include "vesalius/core/error.h"
#include "vesalius/core/grid.h"
#include "vesalius/core/label_map.h"
#include "vesalius/io/image_io.h"
#include "vesalius/viz/slice_overlay.h"

#include "full_disk.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace vesalius::viz {
namespace {

namespace fs = std::filesystem;

// A scan of grey noise inside the CT soft-tissue window, so that the picture cannot compress to nothing,
// and a label map on its grid holding one box: a few hundred bytes compressed.
struct ScanAndLabels {
  Image scan;
  LabelMap labels;
};

ScanAndLabels noiseScanWithABox(int n) {
  GridGeometry geometry;
  geometry.size = Eigen::Vector3i(n, n, n);
  ScanAndLabels s{Image(geometry), {}};
  std::mt19937 random(11);
  std::uniform_real_distribution<float> value(-160, 240);
  for (float& v : s.scan.values) v = value(random);
  s.labels.labels = Grid<Label>(geometry);
  for (int z = n / 4; z < 3 * n / 4; ++z)
    for (int y = n / 4; y < 3 * n / 4; ++y)
      for (int x = n / 4; x < 3 * n / 4; ++x) s.labels.labels.at(x, y, z) = 1;
  s.labels.table.add({1, "liver", {{200, 80, 60}}});
  return s;
}

class PngFullDisk : public test::FullDiskTest {
 protected:
  const ScanAndLabels data = noiseScanWithABox(48);

  std::vector<std::string> segmentOutputs() const {
    std::vector<std::string> outputs = io::labelMapFiles((dir / "labels.nii.gz").string());
    outputs.push_back((dir / "labels.png").string());
    return outputs;
  }
  // The labels, their tables and their picture, as `vesalius segment` writes them.
  void writeSegmentOutputs() const {
    writeFilesAtomically(segmentOutputs(), {}, [&](const std::vector<std::string>& files) {
      io::writeLabelMap(files.front(), data.labels);
      writeSliceOverlayPng(data.scan, data.labels, files.back());
    });
  }

  // `write` must throw a BadInput whose message starts with one of `outputs` and leave only the filler.
  void expectFails(const std::function<void()>& write, const std::vector<std::string>& outputs, const char* what) {
    testing::internal::CaptureStderr();
    std::optional<std::string> message;
    try {
      write();
    } catch (const BadInput& error) {
      message = error.what();
    }
    const std::string printed = testing::internal::GetCapturedStderr();
    if (!message) {
      ADD_FAILURE() << what << " reported success";
    } else {
      std::cout << what << ": " << *message << "\n";
      bool namesAnOutput = false;
      for (const std::string& output : outputs) namesAnOutput |= message->rfind(output + ": ", 0) == 0;
      EXPECT_TRUE(namesAnOutput) << what << ": the message does not start with an output's name";
      EXPECT_EQ(message->find('\n'), std::string::npos) << what << ": more than one line";
      EXPECT_EQ(printed, "") << what << ": VTK printed a line of its own";
    }
    EXPECT_EQ(listing(), std::vector<std::string>{"filler"}) << what << " left a file behind";
  }
};

TEST_F(PngFullDisk, ThePictureFailsCleanlyOnAFullDisk) {
  fill(0);
  const std::string png = (dir / "labels.png").string();
  expectFails([&] { writeSliceOverlayPng(data.scan, data.labels, png); }, {png}, "full disk, slice picture");
  expectFails([&] { writeSegmentOutputs(); }, segmentOutputs(), "full disk, labels with their picture");
}

// Room for the labels and their tables but not for the picture: the labels go too.
TEST_F(PngFullDisk, LabelsWithTheirPictureAreAllOrNoneOnANearlyFullDisk) {
  fill(64 * 1024);
  const std::string png = (dir / "labels.png").string();
  expectFails([&] { writeSliceOverlayPng(data.scan, data.labels, png); }, {png}, "nearly full disk, slice picture");
  expectFails([&] { writeSegmentOutputs(); }, segmentOutputs(), "nearly full disk, labels with their picture");
  // The labels alone fit, so it was the picture that failed the pair.
  io::writeLabelMap((dir / "labels.nii.gz").string(), data.labels);
  std::uintmax_t bytes = 0;
  for (const std::string& file : io::labelMapFiles((dir / "labels.nii.gz").string())) bytes += fs::file_size(file);
  std::cout << "the labels alone fit: " << bytes << " bytes with their tables\n";
}

TEST_F(PngFullDisk, LabelsWithTheirPictureAreWrittenWithRoom) {
  writeSegmentOutputs();
  for (const std::string& file : segmentOutputs()) EXPECT_TRUE(fs::is_regular_file(file)) << file;
  const std::uintmax_t png = fs::file_size(dir / "labels.png");
  std::cout << "the picture: " << png << " bytes\n";
  EXPECT_GT(png, 64u * 1024) << "the picture would fit the nearly full disk, which then tests nothing";
  EXPECT_EQ(listing().size(), segmentOutputs().size());
}

}  // namespace
}  // namespace vesalius::viz
