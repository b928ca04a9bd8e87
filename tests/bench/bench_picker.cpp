// Benchmark of the marker picker's slice scrolling (issue 5: 5,000 markers and 60 fps): milliseconds per
// axial slice step (reslice and render of the whole 4-view window) with 5,000 markers against the same
// with none, in one run. Needs an X server: xvfb-run -a -s "-screen 0 1280x1024x24" bench_picker.
// Usage: bench_picker [markers, default 5000] [slice steps, default 200].
#include "bench_support.h"

#include "picker_window.h"
#include "scan_volume.h"

#include "vesalius/io/image_io.h"

#include <cstdio>
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

// Milliseconds per axial slice step, scrolling forward then back through `steps` steps.
double millisecondsPerSliceStep(const ScanVolume& scan, const MarkerSet& markers, int steps) {
  PickerWindow window(scan, 1200, 900);
  window.renderWindow()->Render();
  window.fitViews();
  window.render(markers, 1);
  SliceView& axial = *window.sliceViews()[0];
  axial.stepSlices(-steps / 4);
  window.render(markers, 1);
  const double total = bench::seconds([&] {
    for (int step = 0; step < steps; ++step) {
      axial.stepSlices(step < steps / 2 ? 1 : -1);
      window.render(markers, 1);  // the markers did not change: only the slice views redraw theirs
    }
  });
  return 1000 * total / steps;
}

}  // namespace

int main(int argc, char** argv) {
  const int markerCount = argc > 1 ? std::atoi(argv[1]) : 5000;
  const int steps = argc > 2 ? std::atoi(argv[2]) : 200;
  const ScanVolume scan(io::readScan(std::string(VESALIUS_TESTDATA) + "/ct-abdomen-pelvis/example_ct.nii.gz"));
  const double none = millisecondsPerSliceStep(scan, {}, steps);
  const double many = millisecondsPerSliceStep(scan, randomMarkers(scan.geometry(), markerCount), steps);
  std::printf("| markers | ms per slice step | slices per second |\n|---|---|---|\n");
  std::printf("| 0 | %.2f | %.0f |\n", none, 1000 / none);
  std::printf("| %d | %.2f | %.0f |\n", markerCount, many, 1000 / many);
  std::printf("ratio %d markers / none: %.2f\n", markerCount, many / none);
  return 0;
}
