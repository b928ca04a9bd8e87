// Fat forest (Dicko et al. 2013, §5) against the exact Euclidean distance map of the skin (ITK's Maurer filter,
// linear time, no trees) on the same grid, in the same run: the forest keeps a path and a root per fat
// voxel, the distance map only a number. Two workloads: the test CT's tissue classes (122 x 101 x 112,
// 3 mm) and a synthetic elliptic body on a 512 x 512 x 60 grid (0.977 x 0.977 x 2 mm, the DICOM
// series' spacing) with 2 mm of skin over 25 mm of fat. Each is timed three times; the table gives the
// range. Peak memory: each workload runs in a child process.
//
//   ninja -C build bench_fat && build/tests/bench/bench_fat
#include "bench_support.h"

#include "vesalius/fat/fat_forest.h"
#include "vesalius/io/image_io.h"
#include "vesalius/segmentation/ct_tissues.h"
#include "vesalius/segmentation/label_ops.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace {

using namespace vesalius;

void compare(const char* name, const fat::Mask& skin, const fat::Mask& fatMask) {
  double f[3], d[3];
  std::int64_t reached = 0;
  for (int r = 0; r < 3; ++r) {
    f[r] = bench::seconds([&] { reached = fat::FatForest(skin, fatMask).statistics().reachedFatVoxels; });
    d[r] = bench::seconds([&] { segmentation::distanceToMaskMm(skin); });
  }
  std::sort(f, f + 3);
  std::sort(d, d + 3);
  std::printf("| %s | %lld | %.3f–%.3f s | %.3f–%.3f s | %.1f M/s | %.1f× |", name, (long long)reached, d[0], d[2],
              f[0], f[2], double(reached) / f[1] / 1e6, f[1] / d[1]);
}

void testCt() {
  const Image ct = io::readScan(std::string(VESALIUS_TESTDATA) + "/ct-abdomen-pelvis/example_ct.nii.gz");
  const LabelMap labels = segmentation::segmentCtTissues(ct);
  compare("test CT, 122 × 101 × 112, 3 mm", segmentation::maskOf(labels.labels, segmentation::kCtSkin),
          segmentation::maskOf(labels.labels, segmentation::kCtSubcutaneousFat));
}

void ellipticBody() {
  GridGeometry g;
  g.size = Eigen::Vector3i(512, 512, 60);
  g.spacing = Eigen::Vector3d(0.977, 0.977, 2.0);
  fat::Mask skin(g, 0), fatMask(g, 0);
  for (int k = 0; k < 60; ++k)
    for (int j = 0; j < 512; ++j)
      for (int i = 0; i < 512; ++i) {
        const double x = (i - 256) * 0.977, y = (j - 256) * 0.977;
        const double depth = (1 - std::sqrt(x * x / (220.0 * 220.0) + y * y / (150.0 * 150.0))) * 150.0;
        skin.at(i, j, k) = depth >= 0 && depth < 2;
        fatMask.at(i, j, k) = depth >= 2 && depth < 27;
      }
  compare("elliptic body, 512 × 512 × 60, 0.977 × 0.977 × 2 mm", skin, fatMask);
}

}  // namespace

int main() {
  std::printf("| workload | fat voxels reached | skin distance map (baseline) | fat forest | forest voxels/s | "
              "forest / map | peak memory |\n|---|---|---|---|---|---|---|\n");
  bench::inChild(testCt);
  bench::inChild(ellipticBody);
  return 0;
}
