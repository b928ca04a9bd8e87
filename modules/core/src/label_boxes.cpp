#include "vesalius/core/label_boxes.h"

#include <algorithm>

namespace vesalius {

std::vector<LabelBox> labelBoxes(const Grid<Label>& labels) {
  const Eigen::Vector3i& s = labels.geometry.size;
  const auto highest = std::max_element(labels.values.begin(), labels.values.end());
  std::vector<LabelBox> boxes(highest == labels.values.end() ? 0 : std::size_t(*highest) + 1,
                              LabelBox{s, Eigen::Vector3i::Constant(-1), 0});
  std::size_t n = 0;  // linear index: i fastest, as Grid stores values
  for (int k = 0; k < s.z(); ++k)
    for (int j = 0; j < s.y(); ++j)
      for (int i = 0; i < s.x(); ++i) {
        const Label v = labels.values[n++];
        if (v == 0) continue;  // background, most of a map: no box
        LabelBox& box = boxes[v];
        box.lo = box.lo.cwiseMin(Eigen::Vector3i(i, j, k));
        box.hi = box.hi.cwiseMax(Eigen::Vector3i(i, j, k));
        ++box.voxels;
      }
  return boxes;
}

}  // namespace vesalius
