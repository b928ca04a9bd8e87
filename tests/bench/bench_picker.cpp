// Benchmark of the marker picker's slice scrolling (issue 5: 5,000 markers and 60 fps): milliseconds per
// axial slice step (reslice, the status readout, and render of what changed) with 5,000 markers against
// the same with none, in one run; wall time and the process's CPU time (every thread, Mesa's llvmpipe
// included), which varies less on a shared machine. Three ways of rendering a step, the earlier two as
// same-run baselines: all four views; the axial and the 3D view; the axial view alone with the 3D view
// deferred until scrolling stops (what the picker does), whose one 3D render is timed apart. Last, a
// render that draws nothing, VTK's window against the picker's: the floor of any step on llvmpipe.
// Needs an X server: xvfb-run -a -s "-screen 0 1280x1024x24" bench_picker.
// Usage: bench_picker [markers, default 5000] [slice steps, default 200].
#include "bench_support.h"

#include "picker_render_window.h"
#include "picker_window.h"
#include "scan_volume.h"

#include "vesalius/io/image_io.h"

#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <random>

using namespace vesalius;
using namespace vesalius::picker;

namespace {

// `count` markers of the three kinds at uniformly random points of the scan's grid.
MarkerSet randomMarkers(const GridGeometry& grid, int count) {
  std::mt19937 random(5);
  MarkerSet set;
  for (int i = 0; i < count; ++i) {
    Eigen::Vector3d index;
    for (int a = 0; a < 3; ++a)
      index[a] = std::uniform_real_distribution<double>(0, grid.size[a] - 1)(random);
    Marker m;
    m.kind = MarkerKind(i % 3);
    m.label = "M-" + std::to_string(i + 1);
    m.position = grid.indexToWorld(index);
    set.markers.push_back(m);
  }
  return set;
}

// How a slice step is rendered: every view (the picker before it skipped unchanged views); the changed
// slice view and the 3D view (the picker before it deferred the 3D view); the changed slice view alone,
// the 3D view once scrolling stops (the picker now).
enum class Mode { AllViews, SliceAnd3d, Deferred3d };
const char* modeName(Mode mode) {
  return mode == Mode::AllViews ? "all 4" : mode == Mode::SliceAnd3d ? "axial + 3D" : "axial; 3D deferred";
}

struct StepTime {
  double wallMs = 0, cpuMs = 0;
  double view3dMs = 0;  // Deferred3d: the one 3D render after scrolling stops
};

// Per axial slice step, scrolling forward then back through `steps` steps, the status readout changing
// at every step as the mouse's LPS position does in the picker.
StepTime timePerSliceStep(const ScanVolume& scan, const MarkerSet& markers, int steps, Mode mode) {
  PickerWindow window(scan, 1200, 900);
  window.renderWindow()->Render();
  window.fitViews();
  window.deferView3d(mode == Mode::Deferred3d ? 150 : 0);  // no event loop here: the bench renders it
  window.render(markers, 1);
  SliceView& axial = *window.sliceViews()[0];
  axial.stepSlices(-steps / 4);
  window.render(markers, 1);
  window.renderView3d();
  const std::clock_t cpuStart = std::clock();
  const double wall = bench::seconds([&] {
    for (int step = 0; step < steps; ++step) {
      axial.stepSlices(step < steps / 2 ? 1 : -1);
      if (mode == Mode::AllViews) window.fitViews();  // the same cameras again, but every view counts as changed
      window.setStatus("LPS 12.00 -40.00 " + std::to_string(step) + ".00 mm", "placing landmark");
      window.render(markers, 1);  // the markers did not change: only the axial view redraws them
    }
  });
  const double cpu = double(std::clock() - cpuStart) / CLOCKS_PER_SEC;
  StepTime t{1000 * wall / steps, 1000 * cpu / steps};
  if (mode == Mode::Deferred3d) {
    if (!window.view3dPending()) std::fprintf(stderr, "bench_picker: the 3D view was not deferred\n");
    constexpr int kRepeats = 10;
    t.view3dMs = 1000 * bench::seconds([&] {
      for (int i = 0; i < kRepeats; ++i) window.renderView3d();
    }) / kRepeats;
  }
  return t;
}

// A render of a 1200 x 900 window that draws nothing: what every render costs whatever changed (VTK copies
// its frame buffers to the window and swaps), for VTK's own X window and for the picker's, which skips
// the depth copy (picker_render_window.h).
StepTime timeEmptyRender(vtkRenderWindow* window, int renders) {
  window->SetSize(1200, 900);
  window->SetMultiSamples(0);
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  window->AddRenderer(renderer);
  window->Render();
  renderer->SetDraw(false);
  const std::clock_t cpuStart = std::clock();
  const double wall = bench::seconds([&] {
    for (int i = 0; i < renders; ++i) window->Render();
  });
  const double cpu = double(std::clock() - cpuStart) / CLOCKS_PER_SEC;
  return {1000 * wall / renders, 1000 * cpu / renders};
}

}  // namespace

int main(int argc, char** argv) {
  const int markerCount = argc > 1 ? std::atoi(argv[1]) : 5000;
  const int steps = argc > 2 ? std::atoi(argv[2]) : 200;
  const ScanVolume scan(io::readScan(std::string(VESALIUS_TESTDATA) + "/ct-abdomen-pelvis/example_ct.nii.gz"));
  const MarkerSet none;
  const MarkerSet markers = randomMarkers(scan.geometry(), markerCount);
  std::printf("| markers | views rendered per step | ms per slice step | slices per second | CPU ms per slice step "
              "| deferred 3D render, ms |\n|---|---|---|---|---|---|\n");
  for (const Mode mode : {Mode::AllViews, Mode::SliceAnd3d, Mode::Deferred3d}) {
    for (const MarkerSet* set : {&none, &markers}) {
      const StepTime t = timePerSliceStep(scan, *set, steps, mode);
      char view3d[32] = "-";
      if (mode == Mode::Deferred3d) std::snprintf(view3d, sizeof view3d, "%.2f", t.view3dMs);
      std::printf("| %zu | %s | %.2f | %.0f | %.2f | %s |\n", set->markers.size(), modeName(mode), t.wallMs,
                  1000 / t.wallMs, t.cpuMs, view3d);
    }
  }
  for (const bool picker : {false, true}) {
    const StepTime floor = timeEmptyRender(
        picker ? newPickerRenderWindow() : vtkSmartPointer<vtkRenderWindow>::New(),
        steps);
    std::printf("| - | none: %s window alone | %.2f | %.0f | %.2f | - |\n", picker ? "the picker's" : "VTK's",
                floor.wallMs, 1000 / floor.wallMs, floor.cpuMs);
  }
  return 0;
}
