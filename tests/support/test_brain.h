// The dense-template case: the brain of the head MRI in testdata/head-mri (Colin 27 brain-extracted, 1 mm;
// its non-zero voxels, largest part, holes filled, closed by a 5 mm ball: the cortex's envelope, which a
// smooth template can follow, not its sulci) as a label map, and ellipsoids of an adult brain's size
// (140 x 170 x 120 mm) as templates of any density, made from no scan. Shared by the fit test and the
// dense-fit benchmark.
#pragma once

#include "test_shapes.h"

#include "vesalius/io/image_io.h"
#include "vesalius/segmentation/label_ops.h"

#include <string>

namespace vesalius::test {

inline const std::string kBrainScan = std::string(VESALIUS_TESTDATA) + "/head-mri/ch2bet.nii.gz";

// Writes the brain label map (label 1 "brain", its table beside it) to `path`.
inline void writeBrainLabels(const std::string& path) {
  const Image scan = io::readScan(kBrainScan);
  const segmentation::Mask brain = segmentation::fillHoles3d(
      segmentation::closeMm(segmentation::largestComponent(segmentation::thresholdMask(scan, 0.5f, 1e9f)), 5.0));
  io::writeLabelMap(path, segmentation::labelMapOf(brain, {1, "brain"}), WriteOptions{true});
}

// 8 * 4^levels triangles, centred at the origin.
inline TriMesh brainSizedEllipsoid(int levels) {
  TriMesh m = sphere(levels);
  m.V = m.V * Eigen::Vector3d(70, 85, 60).asDiagonal();
  return m;
}

}  // namespace vesalius::test
