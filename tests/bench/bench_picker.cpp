// Benchmark of the marker picker's slice scrolling (issue 5: 5,000 markers and 60 fps): milliseconds per
// axial slice step (reslice, and render of the views that changed: axial and 3D) with 5,000 markers
// against the same with none, in one run; wall time and the process's CPU time (every thread, Mesa's
// llvmpipe included), which varies less on a shared machine. Each is also timed with all four views
// rendered at every step, as the picker did before it skipped the views that did not change.
// Needs an X server: xvfb-run -a -s "-screen 0 1280x1024x24" bench_picker.
// Usage: bench_picker [markers, default 5000] [slice steps, default 200].
#include "bench_support.h"

#include "picker_window.h"
#include "scan_volume.h"

#include "vesalius/io/image_io.h"

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

struct StepTime {
  double wallMs = 0, cpuMs = 0;
};

// Per axial slice step, scrolling forward then back through `steps` steps.
StepTime timePerSliceStep(const ScanVolume& scan, const MarkerSet& markers, int steps, bool allViews) {
  PickerWindow window(scan, 1200, 900);
  window.renderWindow()->Render();
  window.fitViews();
  window.render(markers, 1);
  SliceView& axial = *window.sliceViews()[0];
  axial.stepSlices(-steps / 4);
  window.render(markers, 1);
  const std::clock_t cpuStart = std::clock();
  const double wall = bench::seconds([&] {
    for (int step = 0; step < steps; ++step) {
      axial.stepSlices(step < steps / 2 ? 1 : -1);
      if (allViews) window.fitViews();  // the same cameras again, but every view counts as changed
      window.render(markers, 1);        // the markers did not change: only the axial view redraws them
    }
  });
  const double cpu = double(std::clock() - cpuStart) / CLOCKS_PER_SEC;
  return {1000 * wall / steps, 1000 * cpu / steps};
}

}  // namespace

int main(int argc, char** argv) {
  const int markerCount = argc > 1 ? std::atoi(argv[1]) : 5000;
  const int steps = argc > 2 ? std::atoi(argv[2]) : 200;
  const ScanVolume scan(io::readScan(std::string(VESALIUS_TESTDATA) + "/ct-abdomen-pelvis/example_ct.nii.gz"));
  const MarkerSet none;
  const MarkerSet markers = randomMarkers(scan.geometry(), markerCount);
  std::printf("| markers | views rendered | ms per slice step | slices per second | CPU ms per slice step |\n"
              "|---|---|---|---|---|\n");
  for (const bool allViews : {true, false}) {
    for (const MarkerSet* set : {&none, &markers}) {
      const StepTime t = timePerSliceStep(scan, *set, steps, allViews);
      std::printf("| %zu | %s | %.2f | %.0f | %.2f |\n", set->markers.size(), allViews ? "all 4" : "changed (2)",
                  t.wallMs, 1000 / t.wallMs, t.cpuMs);
    }
  }
  return 0;
}
