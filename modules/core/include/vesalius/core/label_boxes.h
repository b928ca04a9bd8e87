// The bounding box of every label of a label grid, found in one pass over the voxels.
#pragma once

#include "vesalius/core/label_map.h"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace vesalius {

struct LabelBox {
  Eigen::Vector3i lo, hi;  // inclusive voxel index bounds; lo > hi when the label has no voxels
  std::int64_t voxels = 0;
};

// One box per label value 0..the largest label present (index = label value); background (0) gets none
// (voxels 0).
std::vector<LabelBox> labelBoxes(const Grid<Label>& labels);

}  // namespace vesalius
