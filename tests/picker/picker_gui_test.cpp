// Drives vesalius-picker for real (under Xvfb, as the README's test command runs ctest) by playing
// vtkInteractorEventRecorder files kept beside this test, then checks what it saved and showed.
//
// Expected positions are computed here from the scan's geometry and the picker's documented view
// geometry (docs/picker.md, "Views"), not from the app's code: in an 800x800 window each slice view is
// 400x400 pixels, its parallel camera is centred on the scan's centre voxel with a half height of
// 1.05 x the larger half extent of the voxel centres, so a display pixel p maps to the plane point
// centre + (p - viewport centre) * 2 * halfHeight / 400.
#include "run_command.h"

#include "vesalius/core/grid_sampling.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/marker_io.h"
#include "vesalius/io/mesh_io.h"

#include <gtest/gtest.h>
#include <vtkImageData.h>
#include <vtkPNGReader.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

namespace vesalius {
namespace {

namespace fs = std::filesystem;
using test::runVesalius;

const std::string kScan = std::string(VESALIUS_TESTDATA) + "/ct-abdomen-pelvis/example_ct.nii.gz";
const std::string kEvents = VESALIUS_PICKER_EVENTS;
constexpr int kViewPixels = 400;

// One slice orientation, LPS: screen right, screen up, and where the next slice lies (as in 3D Slicer:
// superior for axial, anterior for coronal).
struct Orientation {
  Eigen::Vector3d right, up, forward;
  Eigen::Vector2d viewportCentre;  // display pixels
};
const Orientation kAxial{{1, 0, 0}, {0, -1, 0}, {0, 0, 1}, {200, 600}};
const Orientation kCoronal{{1, 0, 0}, {0, 0, 1}, {0, -1, 0}, {200, 200}};

// Where a click at display pixel `pixel` lands, `slicesForward` slice steps from the centre slice.
Eigen::Vector3d clickedWorldPoint(const GridGeometry& grid, const Orientation& view, Eigen::Vector2d pixel,
                                  int slicesForward) {
  const Eigen::Vector3d centre = grid.indexToWorld((grid.size.cast<double>() - Eigen::Vector3d::Ones()) / 2);
  double halfRight = 0, halfUp = 0, indexPerMm = 0;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d axisSpan = grid.direction.col(i) * grid.spacing[i] * (grid.size[i] - 1);
    halfRight += std::abs(axisSpan.dot(view.right)) / 2;
    halfUp += std::abs(axisSpan.dot(view.up)) / 2;
    indexPerMm = std::max(indexPerMm, std::abs(grid.direction.col(i).dot(view.forward)) / grid.spacing[i]);
  }
  const double millimetresPerPixel = 2 * 1.05 * std::max(halfRight, halfUp) / kViewPixels;
  const Eigen::Vector2d offset = (pixel - view.viewportCentre) * millimetresPerPixel;
  return centre + view.right * offset.x() + view.up * offset.y() + view.forward * (slicesForward / indexPerMm);
}

std::vector<std::string> playArgs(const std::string& events, const std::string& out) {
  return {kScan, "--out", out, "--play", events, "--exit-after-play", "--window-width", "800",
          "--window-height", "800"};
}

std::string freshDir(const std::string& name) {
  const fs::path dir = fs::path(test::outputDir()) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

Eigen::Vector3d pixelColour(vtkImageData* image, int x, int y) {
  Eigen::Vector3d rgb;
  for (int c = 0; c < 3; ++c) rgb[c] = image->GetScalarComponentAsDouble(x, y, 0, c);
  return rgb;
}

TEST(PickerGui, PlacesMovesDeletesUndoesAndSavesExactPositions) {
  const std::string dir = freshDir("place_move_delete_undo_save");
  const std::string out = dir + "/picked.mrk.json", screenshot = dir + "/window.png";
  auto args = playArgs(kEvents + "/place_move_delete_undo_save.events", out);
  args.insert(args.end(), {"--restore", "no", "--screenshot", screenshot});
  const auto run = runVesalius(args);
  ASSERT_EQ(run.exitCode, 0) << run.err;

  const GridGeometry grid = io::readScan(kScan).geometry;
  const MarkerSet saved = io::readMarkers(out);
  struct Expected {
    std::string label;
    MarkerKind kind;
    Eigen::Vector3d position;
  };
  const std::vector<Expected> expected{
      {"L-1", MarkerKind::Landmark, clickedWorldPoint(grid, kAxial, {150, 650}, 3)},
      {"L-2", MarkerKind::Landmark, clickedWorldPoint(grid, kAxial, {270, 580}, 3)},  // dragged here
      {"ICP-2", MarkerKind::IcpMarker, clickedWorldPoint(grid, kAxial, {230, 700}, 3)},  // deleted, undone
      {"ICP-3", MarkerKind::IcpMarker, clickedWorldPoint(grid, kCoronal, {200, 150}, 0)},
  };
  ASSERT_EQ(saved.markers.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const Marker& m = saved.markers[i];
    EXPECT_EQ(m.label, expected[i].label);
    EXPECT_EQ(m.kind, expected[i].kind) << m.label;
    EXPECT_EQ(m.status, MarkerStatus::Defined) << m.label;
    EXPECT_LE((m.position - expected[i].position).norm(), 0.01)
        << m.label << " at " << m.position.transpose() << ", expected " << expected[i].position.transpose();
  }
  EXPECT_FALSE(fs::exists(dir + "/picked.autosave.mrk.json"));  // saved, so nothing left to restore

  auto png = vtkSmartPointer<vtkPNGReader>::New();
  png->SetFileName(screenshot.c_str());
  png->Update();
  vtkImageData* image = png->GetOutput();
  ASSERT_EQ(image->GetDimensions()[0], 800);
  const Eigen::Vector3d landmarkYellow(255, 0.85 * 255, 0), icpCyan(0, 0.8 * 255, 255);
  const auto expectColour = [&](int x, int y, const Eigen::Vector3d& colour, bool present) {
    const double difference = (pixelColour(image, x, y) - colour).cwiseAbs().maxCoeff();
    if (present)
      EXPECT_LE(difference, 3) << "pixel " << x << "," << y << " is " << pixelColour(image, x, y).transpose();
    else
      EXPECT_GT(difference, 40) << "pixel " << x << "," << y << " still shows a marker";
  };
  expectColour(150, 650, landmarkYellow, true);
  expectColour(270, 580, landmarkYellow, true);
  expectColour(250, 560, landmarkYellow, false);  // where L-2 was before the drag
  expectColour(230, 700, icpCyan, true);
  expectColour(180, 520, icpCyan, false);  // ICP-1, deleted
  expectColour(200, 150, icpCyan, true);   // ICP-3 in the coronal view
}

TEST(PickerGui, AutosaveOnExitIsRestoredAndSaved) {
  const std::string dir = freshDir("autosave_restore");
  const std::string out = dir + "/picked.mrk.json", sidecar = dir + "/picked.autosave.mrk.json";
  const auto first = runVesalius(playArgs(kEvents + "/place_one_landmark.events", out));
  ASSERT_EQ(first.exitCode, 0) << first.err;
  EXPECT_FALSE(fs::exists(out));
  ASSERT_TRUE(fs::exists(sidecar));

  auto args = playArgs(kEvents + "/save_only.events", out);
  args.insert(args.end(), {"--restore", "yes"});
  const auto second = runVesalius(args);
  ASSERT_EQ(second.exitCode, 0) << second.err;
  const MarkerSet saved = io::readMarkers(out);
  ASSERT_EQ(saved.markers.size(), 1u);
  const GridGeometry grid = io::readScan(kScan).geometry;
  EXPECT_LE((saved.markers[0].position - clickedWorldPoint(grid, kAxial, {210, 610}, 0)).norm(), 0.01);
}

TEST(PickerGui, NamedLandmarksArePlacedInOrderAndSkippedOnesStayMissing) {
  const std::string dir = freshDir("named_landmarks");
  const std::string names = dir + "/names.txt", out = dir + "/named.mrk.json";
  std::ofstream(names) << "# liver landmarks\napex\nhilum\n\ntip\n";
  auto args = playArgs(kEvents + "/named_landmarks.events", out);
  args.insert(args.end(), {"--restore", "no", "--landmark-names", names});
  const auto run = runVesalius(args);
  ASSERT_EQ(run.exitCode, 0) << run.err;

  const GridGeometry grid = io::readScan(kScan).geometry;
  const MarkerSet saved = io::readMarkers(out);
  ASSERT_EQ(saved.markers.size(), 3u);
  EXPECT_EQ(saved.markers[0].label, "apex");
  EXPECT_EQ(saved.markers[0].status, MarkerStatus::Defined);
  EXPECT_LE((saved.markers[0].position - clickedWorldPoint(grid, kAxial, {160, 640}, 0)).norm(), 0.01);
  EXPECT_EQ(saved.markers[1].label, "hilum");
  EXPECT_EQ(saved.markers[1].status, MarkerStatus::Missing);  // skipped, as 3D Slicer's "missing"
  EXPECT_EQ(saved.markers[2].label, "tip");
  EXPECT_EQ(saved.markers[2].status, MarkerStatus::Defined);
  EXPECT_LE((saved.markers[2].position - clickedWorldPoint(grid, kAxial, {240, 560}, 0)).norm(), 0.01);
}

// An axis-aligned cube of half side `half` mm centred on `centre`, as a closed surface.
TriMesh cube(const Eigen::Vector3d& centre, double half) {
  TriMesh mesh;
  mesh.V.resize(8, 3);
  for (int corner = 0; corner < 8; ++corner)
    mesh.V.row(corner) = centre.transpose() +
                         half * Eigen::RowVector3d(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1, corner & 4 ? 1 : -1);
  mesh.F.resize(12, 3);
  mesh.F << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5;
  return mesh;
}

TEST(PickerGui, OverlayContourAndLabelLayerAreDrawn) {
  const std::string dir = freshDir("overlays");
  const GridGeometry grid = io::readScan(kScan).geometry;
  const Eigen::Vector3d centre = grid.indexToWorld((grid.size.cast<double>() - Eigen::Vector3d::Ones()) / 2);
  const double half = 30;
  io::writeTriMesh(dir + "/cube.obj", cube(centre, half));
  const std::string labelsPath = std::string(VESALIUS_TESTDATA) + "/ct-abdomen-pelvis/example_seg.nii.gz";

  const auto screenshotOf = [&](const std::string& name, std::vector<std::string> extra) {
    auto args = playArgs(kEvents + "/place_one_landmark.events", dir + "/" + name + ".mrk.json");
    args.insert(args.end(), {"--restore", "no", "--screenshot", dir + "/" + name + ".png"});
    args.insert(args.end(), extra.begin(), extra.end());
    const auto run = runVesalius(args);
    EXPECT_EQ(run.exitCode, 0) << run.err;
    auto png = vtkSmartPointer<vtkPNGReader>::New();
    png->SetFileName((dir + "/" + name + ".png").c_str());
    png->Update();
    return vtkSmartPointer<vtkImageData>(png->GetOutput());
  };
  const auto plain = screenshotOf("plain", {});
  const auto withContour = screenshotOf("contour", {"--overlay", dir + "/cube.obj"});
  const auto withLabels = screenshotOf("labels", {"--labels", labelsPath});

  // The cube cuts the axial centre slice in a square of half side 30 mm: its right edge (patient left,
  // world x = centre + 30) at 15 mm above the centre on screen (anterior).
  const Eigen::Vector3d edgePoint = centre + Eigen::Vector3d(half, -15, 0);
  const double millimetresPerPixel =
      (clickedWorldPoint(grid, kAxial, {201, 600}, 0) - clickedWorldPoint(grid, kAxial, {200, 600}, 0)).norm();
  const int edgeX = int(std::lround(200 + (edgePoint.x() - centre.x()) / millimetresPerPixel));
  const int edgeY = int(std::lround(600 + 15 / millimetresPerPixel));
  const Eigen::Vector3d orange(255, 0.45 * 255, 0.1 * 255);
  double closest = 1e9;
  for (int dx = -1; dx <= 1; ++dx)
    closest = std::min(closest, (pixelColour(withContour, edgeX + dx, edgeY) - orange).cwiseAbs().maxCoeff());
  EXPECT_LE(closest, 3) << "no contour near pixel " << edgeX << "," << edgeY;
  EXPECT_GT((pixelColour(plain, edgeX, edgeY) - orange).cwiseAbs().maxCoeff(), 40);

  // The label layer tints labelled voxels and leaves background ones alone: compare pixels of the
  // coronal view whose whole voxel neighbourhood has one label. The label map covers 30 of the scan's
  // 112 slices, so this also checks that it is placed by its own geometry.
  const LabelMap labels = io::readLabelMap(labelsPath);
  const GridGeometry& labelGrid = labels.labels.geometry;
  int tinted = 0, untouched = 0;
  for (int y = 10; y < 390; y += 20) {
    for (int x = 10; x < 390; x += 20) {
      if (std::abs(x - 200) < 3 || std::abs(y - 200) < 3) continue;  // the crosshair
      const Eigen::Vector3d index = labelGrid.worldToIndex(clickedWorldPoint(grid, kCoronal, {double(x), double(y)}, 0));
      std::set<Label> around;
      for (int corner = 0; corner < 8; ++corner) {
        Eigen::Vector3i voxel;
        for (int a = 0; a < 3; ++a) voxel[a] = int(corner & (1 << a) ? std::ceil(index[a]) : std::floor(index[a]));
        const bool inside = labelGrid.contains(voxel.x(), voxel.y(), voxel.z());
        around.insert(inside ? labels.labels.at(voxel.x(), voxel.y(), voxel.z()) : Label(0));
      }
      if (around.size() != 1) continue;
      const double change = (pixelColour(withLabels, x, y) - pixelColour(plain, x, y)).cwiseAbs().maxCoeff();
      if (*around.begin() == 0) {
        EXPECT_LE(change, 1) << "background pixel " << x << "," << y << " changed";
        ++untouched;
      } else {
        EXPECT_GE(change, 10) << "label " << *around.begin() << " at pixel " << x << "," << y << " not tinted";
        ++tinted;
      }
    }
  }
  EXPECT_GT(tinted, 3);
  EXPECT_GT(untouched, 3);
}

// The point of steepest intensity change within `radius` mm of `click` on the axial line through it
// along the in-plane image gradient: the gradient from differences over one voxel either side; along
// the line, every 0.01 mm, the change over one voxel centred there (the interpolated profile is linear
// between voxel centres, so a shorter difference would have no single peak).
Eigen::Vector3d steepestEdgeNear(const Image& scan, const Eigen::Vector3d& click, double radius) {
  const auto value = [&](const Eigen::Vector3d& world) {
    return sampleTrilinear(scan, scan.geometry.worldToIndex(world));
  };
  const double voxel = scan.geometry.spacing.maxCoeff();
  Eigen::Vector3d direction(value(click + Eigen::Vector3d(voxel, 0, 0)) - value(click - Eigen::Vector3d(voxel, 0, 0)),
                            value(click + Eigen::Vector3d(0, voxel, 0)) - value(click - Eigen::Vector3d(0, voxel, 0)),
                            0);
  direction.normalize();
  Eigen::Vector3d steepest = click;
  double steepestChange = -1;
  for (double t = -radius; t <= radius + 1e-9; t += 0.01) {
    const Eigen::Vector3d p = click + t * direction;
    const double change = std::abs(value(p + voxel / 2 * direction) - value(p - voxel / 2 * direction));
    if (change > steepestChange) {
      steepestChange = change;
      steepest = p;
    }
  }
  return steepest;
}

TEST(PickerGui, SnapMovesAClickToTheBodyEdge) {
  const std::string dir = freshDir("snap");
  const std::string out = dir + "/snapped.mrk.json";
  auto args = playArgs(kEvents + "/snap_to_edge.events", out);
  args.insert(args.end(), {"--restore", "no"});
  const auto run = runVesalius(args);
  ASSERT_EQ(run.exitCode, 0) << run.err;

  const Image scan = io::readScan(kScan);
  const MarkerSet saved = io::readMarkers(out);
  ASSERT_EQ(saved.markers.size(), 1u);
  const Eigen::Vector3d snapped = saved.markers[0].position;
  const Eigen::Vector3d click = clickedWorldPoint(scan.geometry, kAxial, {260, 729}, 0);
  const Eigen::Vector3d edge = steepestEdgeNear(scan, click, 3);  // the picker's documented snap radius
  const double voxel = scan.geometry.spacing.maxCoeff();
  EXPECT_NEAR(snapped.z(), click.z(), 0.01) << "left the slice";
  EXPECT_GE((snapped - click).norm(), 1.0) << "the click was not moved: snap off?";
  EXPECT_LE((snapped - edge).norm(), voxel / 2) << "snapped to " << snapped.transpose() << ", the edge is at "
                                                << edge.transpose() << ", clicked " << click.transpose();
  // It is the body/air boundary: air (below -800 HU) a voxel outside, tissue (above -300 HU) a voxel inside.
  const Eigen::Vector3d across = (edge - click).normalized();  // from the click toward the edge
  const auto value = [&](const Eigen::Vector3d& w) { return sampleTrilinear(scan, scan.geometry.worldToIndex(w)); };
  const double a = value(snapped + voxel * across), b = value(snapped - voxel * across);
  EXPECT_LT(std::min(a, b), -800);
  EXPECT_GT(std::max(a, b), -300);
}

// Suggestions as `vesalius markers suggest` writes them (preview ICP markers, the confidence first in
// the description) at display pixels of the axial centre slice, and one landmark the user picked.
MarkerSet suggestionsAt(const GridGeometry& grid, const std::vector<Eigen::Vector2d>& pixels,
                        const std::vector<double>& confidences) {
  MarkerSet set;
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    Marker m;
    m.label = "suggested-" + std::to_string(i + 1);
    m.kind = MarkerKind::IcpMarker;
    m.status = MarkerStatus::Preview;
    m.position = clickedWorldPoint(grid, kAxial, pixels[i], 0);
    m.description = "confidence " + std::to_string(confidences[i]) + "; edge 50.0 per mm, 1.0 mm from the template";
    set.markers.push_back(m);
  }
  Marker picked;
  picked.label = "L-1";
  picked.position = clickedWorldPoint(grid, kAxial, {200, 700}, 0);
  set.markers.push_back(picked);
  return set;
}

TEST(PickerGui, SuggestionsAreAcceptedAndRejected) {
  const std::string dir = freshDir("accept_reject_previews");
  const std::string suggested = dir + "/suggested.mrk.json", out = dir + "/picked.mrk.json";
  const std::string screenshot = dir + "/window.png";
  const GridGeometry grid = io::readScan(kScan).geometry;
  const std::vector<Eigen::Vector2d> pixels{{150, 650}, {250, 650}, {150, 550}, {250, 550}};
  const MarkerSet start = suggestionsAt(grid, pixels, {0.912, 0.48, 0.75, 0.3});
  io::writeMarkers(suggested, start);
  auto args = playArgs(kEvents + "/accept_reject_previews.events", out);
  args.insert(args.end(), {"--markers", suggested, "--accept-confidence", "0.6", "--restore", "no",
                           "--screenshot", screenshot});
  const auto run = runVesalius(args);
  ASSERT_EQ(run.exitCode, 0) << run.err;

  // suggested-2 rejected; suggested-3 rejected, undone, then accepted by Shift+A (0.75 >= 0.6);
  // suggested-4 (0.3) still a preview, in the saved file too. (Files list landmarks first.)
  const MarkerSet saved = io::readMarkers(out);
  const std::map<std::string, MarkerStatus> expected{{"suggested-1", MarkerStatus::Defined},
                                                     {"suggested-3", MarkerStatus::Defined},
                                                     {"suggested-4", MarkerStatus::Preview},
                                                     {"L-1", MarkerStatus::Defined}};
  ASSERT_EQ(saved.markers.size(), expected.size());
  for (const Marker& m : saved.markers) {
    ASSERT_EQ(expected.count(m.label), 1u) << m.label << " should not be in the saved file";
    EXPECT_EQ(m.status, expected.at(m.label)) << m.label;
    for (const Marker& original : start.markers) {
      if (original.label != m.label) continue;
      EXPECT_EQ(m.kind, original.kind) << m.label;
      EXPECT_LE((m.position - original.position).norm(), 0.01) << m.label;
    }
  }

  // The remaining suggestion is a ring of the ICP colour: cyan around it, not at its centre. The
  // accepted ones are filled discs; the rejected one is gone.
  auto png = vtkSmartPointer<vtkPNGReader>::New();
  png->SetFileName(screenshot.c_str());
  png->Update();
  vtkImageData* image = png->GetOutput();
  const Eigen::Vector3d icpCyan(0, 0.8 * 255, 255);
  const auto cyanness = [&](int x, int y) { return (pixelColour(image, x, y) - icpCyan).cwiseAbs().maxCoeff(); };
  for (const auto& [dx, dy] : std::vector<std::pair<int, int>>{{5, 0}, {-5, 0}, {0, 5}, {0, -5}})
    EXPECT_LE(cyanness(250 + dx, 550 + dy), 3) << "ring of suggested-4 at offset " << dx << "," << dy;
  EXPECT_GT(cyanness(250, 550), 40) << "suggested-4 should be hollow";
  EXPECT_LE(cyanness(150, 650), 3) << "accepted suggested-1 should be a filled disc";
  EXPECT_LE(cyanness(150, 550), 3) << "accepted suggested-3 should be a filled disc";
  EXPECT_GT(cyanness(250, 650), 40) << "rejected suggested-2 is still drawn";
}

TEST(PickerGui, BadInputIsOneLineNamingTheFile) {
  const std::string dir = freshDir("bad_input");
  const auto missingScan = runVesalius({dir + "/no-such-scan.nii.gz", "--out", dir + "/a.mrk.json"});
  EXPECT_EQ(missingScan.exitCode, 3);
  test::expectContains(missingScan.err, "no-such-scan.nii.gz");
  EXPECT_EQ(std::count(missingScan.err.begin(), missingScan.err.end(), '\n'), 1) << missingScan.err;

  const std::string broken = dir + "/broken.mrk.json";
  std::ofstream(broken) << "{\"@schema\": \"https://raw.githubusercontent.com/slicer/slicer/master/Modules/"
                           "Loadable/Markups/Resources/Schema/markups-schema-v1.0.3.json#\", \"markups\": [";
  const auto brokenMarkers = runVesalius({kScan, "--markers", broken, "--out", dir + "/b.mrk.json"});
  EXPECT_EQ(brokenMarkers.exitCode, 3);
  test::expectContains(brokenMarkers.err, "broken.mrk.json");

  const auto overwriteInput = runVesalius({kScan, "--markers", broken, "--out", broken});
  EXPECT_EQ(overwriteInput.exitCode, 2);
  test::expectContains(overwriteInput.err, "never overwritten");
}

}  // namespace
}  // namespace vesalius
