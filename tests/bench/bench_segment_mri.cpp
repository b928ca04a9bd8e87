// Segmenting the head MRI (181x217x181, 1 mm) into tissue classes: wall time against reading the scan in
// the same run, and peak memory of a child process that does only this. Prints a markdown table row.
//
//   build/tests/bench/bench_segment_mri
#include "vesalius/io/image_io.h"
#include "vesalius/segmentation/mri_tissues.h"

#include "bench_support.h"

#include <cstdio>
#include <string>

using namespace vesalius;
using bench::seconds;

namespace {

const std::string kHead = std::string(VESALIUS_TESTDATA) + "/head-mri/ch2.nii.gz";

void benchSegmentation() {
  Image scan;
  const double read = seconds([&] { scan = io::readScan(kHead); });
  LabelMap tissues;
  const double segment = seconds([&] { tissues = segmentation::segmentMriTissues(scan); });
  const Eigen::Vector3i s = scan.geometry.size;
  std::printf("| segmentMriTissues, %dx%dx%d head MRI | reading the scan: %.2f s | %.2f s (%.0fx the read) |", s.x(),
              s.y(), s.z(), read, segment, segment / read);
}

}  // namespace

int main() {
  std::puts("| workload | baseline | method | peak memory |\n|---|---|---|---|");
  bench::inChild(benchSegmentation);
  return 0;
}
