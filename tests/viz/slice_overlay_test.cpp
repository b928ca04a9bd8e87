// Slice overlays: the radiological display convention on synthetic scans whose bright half is known, the
// same picture whatever the grid's direction, labels blended in their colours, and the PNG on disk.
#include "vesalius/viz/slice_overlay.h"

#include "vesalius/core/error.h"
#include "vesalius/viz/text.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>

namespace vesalius::viz {
namespace {

constexpr int kMargin = 12, kPanel = 100, kGap = 12;  // layout of slice_overlay.cpp with panelPixels 100
const Rgb kWhite{{255, 255, 255}}, kBlack{{0, 0, 0}};

// A 20 mm cube of 1 mm voxels centred on the world origin, stored along `direction`.
Image cube(const Eigen::Matrix3d& direction, const std::function<float(const Eigen::Vector3d&)>& value) {
  GridGeometry g;
  g.size = Eigen::Vector3i(20, 20, 20);
  g.direction = direction;
  g.origin = -direction * Eigen::Vector3d::Constant(9.5);
  Image image(g);
  for (int k = 0; k < 20; ++k)
    for (int j = 0; j < 20; ++j)
      for (int i = 0; i < 20; ++i) image.at(i, j, k) = value(g.indexToWorld(Eigen::Vector3d(i, j, k)));
  return image;
}

LabelMap noLabels(const Image& scan) { return {Grid<Label>(scan.geometry, 0), {}}; }

// Top row of the panels: the first row where the first panel, right of its title, is not background.
int panelTop(const RgbImage& picture) {
  const Rgb background = picture.get(0, 0);
  for (int y = 0; y < picture.height; ++y)
    if (picture.get(kMargin + kPanel * 3 / 4, y) != background) return y;
  return -1;
}

// The colour at (u, v) in [0, 1]^2 of panel `n` (0 axial, 1 coronal, 2 sagittal).
Rgb at(const RgbImage& picture, int n, double u, double v) {
  const int x = kMargin + n * (kPanel + kGap) + int(u * kPanel), y = panelTop(picture) + int(v * kPanel);
  return picture.get(x, y);
}

RgbImage render(const Image& scan) {
  OverlayOptions options;
  options.panelPixels = kPanel;
  return renderSliceOverlay(scan, noLabels(scan), options);
}

TEST(SliceOverlay, PatientLeftIsOnTheImageRight) {
  for (const Eigen::Matrix3d& d : {Eigen::Matrix3d(Eigen::Matrix3d::Identity()),
                                   Eigen::Matrix3d(Eigen::Vector3d(-1, -1, 1).asDiagonal())}) {
    const RgbImage picture =
        render(cube(d, [](const Eigen::Vector3d& p) { return p.x() > 0 ? 1000.f : -1000.f; }));
    ASSERT_GE(panelTop(picture), 0);
    for (int n : {0, 1}) {
      EXPECT_EQ(at(picture, n, 0.25, 0.5), kBlack) << "panel " << n;
      EXPECT_EQ(at(picture, n, 0.75, 0.5), kWhite) << "panel " << n;
    }
  }
}

TEST(SliceOverlay, AnteriorIsUpInAxialAndLeftInSagittal) {
  const RgbImage picture = render(cube(
      Eigen::Matrix3d::Identity(), [](const Eigen::Vector3d& p) { return p.y() < 0 ? 1000.f : -1000.f; }));
  EXPECT_EQ(at(picture, 0, 0.5, 0.25), kWhite);
  EXPECT_EQ(at(picture, 0, 0.5, 0.75), kBlack);
  EXPECT_EQ(at(picture, 2, 0.25, 0.5), kWhite);
  EXPECT_EQ(at(picture, 2, 0.75, 0.5), kBlack);
}

TEST(SliceOverlay, SuperiorIsUpInCoronalAndSagittal) {
  const RgbImage picture = render(cube(
      Eigen::Matrix3d::Identity(), [](const Eigen::Vector3d& p) { return p.z() > 0 ? 1000.f : -1000.f; }));
  for (int n : {1, 2}) {
    EXPECT_EQ(at(picture, n, 0.5, 0.25), kWhite) << "panel " << n;
    EXPECT_EQ(at(picture, n, 0.5, 0.75), kBlack) << "panel " << n;
  }
}

TEST(SliceOverlay, LabelsAreBlendedInTheirColourAndWrittenAsPng) {
  const Image scan = cube(Eigen::Matrix3d::Identity(), [](const Eigen::Vector3d&) { return -1000.f; });
  LabelMap labels = noLabels(scan);
  labels.table.add({4, "muscle", {{200, 0, 0}}});
  for (int k = 0; k < 20; ++k)
    for (int j = 0; j < 20; ++j)
      for (int i = 0; i < 20; ++i) labels.labels.at(i, j, k) = 4;
  OverlayOptions options;
  options.panelPixels = kPanel;
  options.opacity = 0.5;
  const RgbImage picture = renderSliceOverlay(scan, labels, options);
  EXPECT_EQ(at(picture, 0, 0.5, 0.5), (Rgb{{100, 0, 0}}));  // half red over black
  const std::string path = std::string(VESALIUS_TEST_OUTPUT) + "/overlay.png";
  std::filesystem::create_directories(VESALIUS_TEST_OUTPUT);
  options.write.force = true;
  writeSliceOverlayPng(scan, labels, path, options);
  EXPECT_GT(std::filesystem::file_size(path), 1000u);
  options.write.force = false;
  EXPECT_THROW(writeSliceOverlayPng(scan, labels, path, options), UsageError);
}

TEST(SliceOverlay, RejectsMismatchedLabelsAndBadOptions) {
  const Image scan = cube(Eigen::Matrix3d::Identity(), [](const Eigen::Vector3d&) { return 0.f; });
  LabelMap other{Grid<Label>(GridGeometry{Eigen::Vector3i(5, 5, 5)}, 0), {}};
  EXPECT_THROW(renderSliceOverlay(scan, other), BadInput);
  OverlayOptions options;
  options.window = 0;
  EXPECT_THROW(renderSliceOverlay(scan, noLabels(scan), options), UsageError);
  options = {};
  options.voxel = Eigen::Vector3i(30, 0, 0);
  EXPECT_THROW(renderSliceOverlay(scan, noLabels(scan), options), UsageError);
}

TEST(Text, IsMeasuredAndDrawnWithoutAWindow) {
  const TextExtent e = measureText("bone", 15);
  EXPECT_GT(e.width, 15);
  EXPECT_GT(e.height, 5);
  RgbImage image(60, 30, kBlack);
  drawText(image, 2, 2, "bone", kWhite, 15);
  EXPECT_NE(std::count(image.pixels.begin(), image.pixels.end(), 0), long(image.pixels.size()));
}

}  // namespace
}  // namespace vesalius::viz
