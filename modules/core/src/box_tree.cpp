#include "vesalius/core/box_tree.h"

#include <algorithm>
#include <numeric>

namespace vesalius {

BoxTree::BoxTree(const std::vector<Eigen::AlignedBox3d>& boxes) {
  const int n = int(boxes.size());
  std::vector<Eigen::Vector3d> centres(n);
  for (int i = 0; i < n; ++i) centres[i] = boxes[i].center();
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0);
  nodes_.reserve(2 * (n / kLeafSize + 1));
  build(0, n, boxes, centres);
}

int BoxTree::build(int begin, int end, const std::vector<Eigen::AlignedBox3d>& boxes,
                   const std::vector<Eigen::Vector3d>& centres) {
  const int index = int(nodes_.size());
  nodes_.emplace_back();
  Eigen::AlignedBox3d box, centreBox;
  box.setEmpty();
  centreBox.setEmpty();
  for (int i = begin; i < end; ++i) {
    box.extend(boxes[order_[i]]);
    centreBox.extend(centres[order_[i]]);
  }
  nodes_[index].box = box;
  if (end - begin <= kLeafSize) {
    nodes_[index].begin = begin;
    nodes_[index].end = end;
    return index;
  }
  int axis;
  centreBox.sizes().maxCoeff(&axis);
  const int mid = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                   [&](int x, int y) { return centres[x][axis] < centres[y][axis]; });
  const int left = build(begin, mid, boxes, centres);
  const int right = build(mid, end, boxes, centres);
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

}  // namespace vesalius
