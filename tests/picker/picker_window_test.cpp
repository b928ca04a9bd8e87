// The picker's window rendered in-process under Xvfb (label gui): a slice step with the 3D view deferred
// redraws the slice view and leaves the 3D view's pixels as they were until the deferred render, which
// then shows what rendering at every step shows; marker labels in a slice view are drawn beside their
// marker (slice_labels.h: cached bitmaps in one texture); with the event loop running, the deferred render
// comes from the interactor's timer.
#include <gtest/gtest.h>

#include "picker_window.h"
#include "scan_volume.h"

#include "vesalius/io/image_io.h"
#include "vesalius/viz/display_connection.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkImageData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkWindowToImageFilter.h>

#include <array>

namespace vesalius::picker {
namespace {

const std::string kScan = std::string(VESALIUS_TESTDATA) + "/ct-abdomen-pelvis/example_ct.nii.gz";
constexpr int kSize = 800;  // the window; each view a 400 x 400 quadrant

// One connection for every test: Xvfb (without -noreset) resets when its last client leaves, and a
// connection opened during the reset fails.
void* display() {
  static const viz::DisplayConnection connection("picker_window_test");
  return connection.display;
}

// What the window shows, without rendering again.
vtkSmartPointer<vtkImageData> pixels(vtkRenderWindow* window) {
  auto capture = vtkSmartPointer<vtkWindowToImageFilter>::New();
  capture->SetInput(window);
  capture->ReadFrontBufferOff();
  capture->ShouldRerenderOff();
  capture->Update();
  return capture->GetOutput();
}

// Pixels of the quadrant (x0, y0, 400 x 400; y up) whose colour differs between two captures.
int changedPixels(vtkImageData* a, vtkImageData* b, int x0, int y0) {
  int changed = 0;
  for (int y = y0; y < y0 + kSize / 2; ++y)
    for (int x = x0; x < x0 + kSize / 2; ++x)
      for (int c = 0; c < 3; ++c)
        if (a->GetScalarComponentAsDouble(x, y, 0, c) != b->GetScalarComponentAsDouble(x, y, 0, c)) {
          ++changed;
          break;
        }
  return changed;
}

MarkerSet oneLandmark(const Eigen::Vector3d& position, const std::string& label) {
  Marker m;
  m.label = label;
  m.position = position;
  MarkerSet set;
  set.markers.push_back(m);
  return set;
}

// The app's path: with the interactor's event loop running, the 3D view is rendered by the one-shot timer
// once the slices stop moving. First in this file: VTK 9.1's X event loop visits every interactor ever
// initialised in the process, and those of windows already destroyed crash it (ctest runs each test in a
// process of its own anyway).
TEST(PickerWindow, TimerRendersTheDeferredView3dOnceScrollingStops) {
  // A connection of its own (opened while the shared one keeps Xvfb from resetting): the event loop
  // reads every event of its connection, those of the other tests' windows too.
  display();
  const viz::DisplayConnection own("picker_window_test");
  const ScanVolume scan(io::readScan(kScan));
  PickerWindow window(scan, kSize, kSize);
  window.renderWindow()->SetDisplayId(own.display);
  window.interactor()->Initialize();
  window.renderWindow()->Render();
  window.fitViews();
  window.deferView3d(50);
  const MarkerSet none;
  window.render(none, 1);
  const auto before = pixels(window.renderWindow());
  for (int step = 0; step < 5; ++step) {
    window.sliceViews()[0]->stepSlices(2);
    window.render(none, 1);
  }
  ASSERT_TRUE(window.view3dPending());
  // The first timer event ends the loop: the window's (50 ms), or a 5 s guard if that one never comes.
  auto stop = vtkSmartPointer<vtkCallbackCommand>::New();
  stop->SetCallback([](vtkObject* interactor, unsigned long, void*, void*) {
    static_cast<vtkRenderWindowInteractor*>(interactor)->SetDone(true);
  });
  window.interactor()->AddObserver(vtkCommand::TimerEvent, stop);
  window.interactor()->CreateOneShotTimer(5000);
  window.interactor()->Start();
  EXPECT_FALSE(window.view3dPending()) << "the timer did not render the 3D view";
  EXPECT_GT(changedPixels(before, pixels(window.renderWindow()), kSize / 2, kSize / 2), 100)
      << "the 3D view's axial plane did not move";
}

TEST(PickerWindow, DeferredView3dKeepsItsPixelsUntilRenderedThenMatchesRenderingEveryStep) {
  const ScanVolume scan(io::readScan(kScan));
  const GridGeometry& grid = scan.geometry();
  const MarkerSet markers =
      oneLandmark(grid.indexToWorld((grid.size.cast<double>() - Eigen::Vector3d::Ones()) / 2), "L-1");
  std::array<vtkSmartPointer<vtkImageData>, 2> final3d;
  for (const bool deferred : {true, false}) {
    PickerWindow window(scan, kSize, kSize);
    window.renderWindow()->SetDisplayId(display());
    window.renderWindow()->Render();
    window.fitViews();
    window.deferView3d(deferred ? 150 : 0);
    window.render(markers, 1);
    const auto before = pixels(window.renderWindow());
    window.sliceViews()[0]->stepSlices(10);
    window.render(markers, 1);
    const auto stepped = pixels(window.renderWindow());
    EXPECT_GT(changedPixels(before, stepped, 0, kSize / 2), 1000) << "the axial view shows the new slice";
    EXPECT_EQ(window.view3dPending(), deferred);
    if (deferred) {
      EXPECT_EQ(changedPixels(before, stepped, kSize / 2, kSize / 2), 0) << "the 3D view was rendered at once";
      window.renderView3d();
      EXPECT_FALSE(window.view3dPending());
    }
    final3d[deferred ? 0 : 1] = pixels(window.renderWindow());
    EXPECT_GT(changedPixels(before, final3d[deferred ? 0 : 1], kSize / 2, kSize / 2), 100)
        << "the 3D view's axial plane moved";
  }
  EXPECT_EQ(changedPixels(final3d[0], final3d[1], kSize / 2, kSize / 2), 0)
      << "the deferred 3D render differs from rendering at every step";
}

TEST(PickerWindow, SliceLabelIsDrawnBesideItsMarker) {
  const ScanVolume scan(io::readScan(kScan));
  const GridGeometry& grid = scan.geometry();
  // 50 mm to the patient's left of the centre voxel (on the spine): soft tissue, dark in the default window.
  const Eigen::Vector3d centre =
      grid.indexToWorld((grid.size.cast<double>() - Eigen::Vector3d::Ones()) / 2) + Eigen::Vector3d(50, 0, 0);
  std::array<vtkSmartPointer<vtkImageData>, 2> shown;
  std::array<double, 2> markerPixel{};
  for (const bool labelled : {true, false}) {
    PickerWindow window(scan, kSize, kSize);
    window.renderWindow()->SetDisplayId(display());
    window.renderWindow()->Render();
    window.fitViews();
    window.render(oneLandmark(centre, labelled ? "LABEL" : ""), 1);
    shown[labelled ? 0 : 1] = pixels(window.renderWindow());
    vtkRenderer* axial = window.sliceViews()[0]->renderer();
    const Eigen::Vector3d plane = window.sliceViews()[0]->frame().toPlane(centre);
    axial->SetWorldPoint(plane.x(), plane.y(), 0, 1);
    axial->WorldToDisplay();
    markerPixel = {axial->GetDisplayPoint()[0], axial->GetDisplayPoint()[1]};
  }
  // The text starts 1.5 marker radii (9 pixels) right of the marker's centre, centred on it vertically:
  // white letters there with the label, none without.
  const auto whitePixels = [&](vtkImageData* image) {
    int white = 0;
    for (int y = int(markerPixel[1]) - 6; y <= int(markerPixel[1]) + 6; ++y)
      for (int x = int(markerPixel[0]) + 9; x < int(markerPixel[0]) + 50; ++x)
        white += image->GetScalarComponentAsDouble(x, y, 0, 0) > 200 &&
                 image->GetScalarComponentAsDouble(x, y, 0, 1) > 200 &&
                 image->GetScalarComponentAsDouble(x, y, 0, 2) > 200;
    return white;
  };
  EXPECT_GT(whitePixels(shown[0]), 20) << "no label text right of the marker";
  EXPECT_EQ(whitePixels(shown[1]), 0) << "white pixels right of an unlabelled marker";
}

}  // namespace
}  // namespace vesalius::picker
