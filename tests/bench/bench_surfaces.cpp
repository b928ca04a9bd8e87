// Surfacing every label of TotalSegmentator's 104-class map of the test CT, and segmenting that CT into
// tissue classes: wall time and peak memory. labelSurfaces (one scan for all label boxes, labels in
// parallel) is timed against the baseline it replaced in the same run: labelSurface per label, serially,
// each call scanning the whole map. Each workload runs in its own child process so its peak resident
// memory (getrusage via wait4) is its own. The shared surfaces of all labels at once (SurfaceNets) are
// timed against labelSurfaces in the same child. Prints markdown table rows.
//
//   build/tests/bench/bench_surfaces
#include "vesalius/io/image_io.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/meshing/shared_label_surfaces.h"
#include "vesalius/segmentation/ct_tissues.h"

#include "bench_support.h"

#include <tbb/global_control.h>

#include <cstdio>
#include <cstdlib>
#include <string>

using namespace vesalius;
using bench::seconds;

namespace {

const std::string kDir = std::string(VESALIUS_TESTDATA) + "/ct-abdomen-pelvis/";

long faces(const std::vector<meshing::LabelSurface>& surfaces) {
  long total = 0;
  for (const meshing::LabelSurface& s : surfaces) total += long(s.mesh.F.rows());
  return total;
}

void benchSurfaces() {
  const LabelMap map =
      io::readLabelMap(kDir + "example_seg_total_v1_for_example_ct.nii.gz", kDir + "labels_total_v1.tsv");
  std::vector<meshing::LabelSurface> serial, oneThread, parallel;
  const double baseline = seconds([&] {  // what labelSurfaces did before: one scan for the ids present,
    std::vector<bool> present(1 << 16, false);  // then labelSurface (a scan, then the surface) per id
    for (Label v : map.labels.values) present[v] = true;
    for (const LabelEntry& entry : map.table.entries)
      if (present[entry.id]) serial.push_back({entry.id, entry.name, meshing::labelSurface(map, entry.id)});
  });
  const double single = seconds([&] {
    const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    oneThread = meshing::labelSurfaces(map, {});
  });
  const double method = seconds([&] { parallel = meshing::labelSurfaces(map, {}); });
  if (serial.size() != parallel.size() || faces(serial) != faces(parallel) || faces(oneThread) != faces(parallel)) {
    std::fprintf(stderr, "surfaces differ: %zu/%zu labels, %ld/%ld/%ld faces\n", serial.size(), parallel.size(),
                 faces(serial), faces(oneThread), faces(parallel));
    std::exit(1);
  }
  const Eigen::Vector3i s = map.labels.geometry.size;
  std::printf("| surfaces of %zu labels present of 104, %dx%dx%d map, %ld faces | labelSurface per label, serial: "
              "%.2f s | labelSurfaces, 1 thread: %.2f s (%.1fx); all threads: %.2f s (%.1fx) |",
              parallel.size(), s.x(), s.y(), s.z(), faces(parallel), baseline, single, baseline / single, method,
              baseline / method);
}

void benchSharedSurfaces() {
  const LabelMap map =
      io::readLabelMap(kDir + "example_seg_total_v1_for_example_ct.nii.gz", kDir + "labels_total_v1.tsv");
  std::vector<meshing::LabelSurface> separate;
  meshing::SharedLabelSurfaces shared;
  const double baseline = seconds([&] { separate = meshing::labelSurfaces(map, {}); });
  const double method = seconds([&] { shared = meshing::sharedLabelSurfaces(map, {}); });
  std::printf("| shared surfaces of the same %zu labels, %ld triangles | labelSurfaces (each on its own): %.2f s | "
              "sharedLabelSurfaces: %.2f s (%.2fx) |",
              shared.ids.size(), long(shared.F.rows()), baseline, method, baseline / method);
}

void benchSegmentation() {
  const Image ct = io::readScan(kDir + "example_ct.nii.gz");
  LabelMap tissues;
  const double read = seconds([&] { io::readScan(kDir + "example_ct.nii.gz"); });
  const double segment = seconds([&] { tissues = segmentation::segmentCtTissues(ct); });
  const Eigen::Vector3i s = ct.geometry.size;
  std::printf("| segmentCtTissues, %dx%dx%d CT | reading the scan: %.2f s | %.2f s (%.1fx the read) |", s.x(), s.y(),
              s.z(), read, segment, segment / read);
}

}  // namespace

int main() {
  std::puts("| workload | baseline | method | peak memory |\n|---|---|---|---|");
  // The parent never starts TBB's threads, so forking is safe.
  bench::inChild(benchSurfaces);
  bench::inChild(benchSharedSurfaces);
  bench::inChild(benchSegmentation);
  return 0;
}
