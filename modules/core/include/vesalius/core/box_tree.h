// A bounding-volume hierarchy over axis-aligned boxes, shared by the spatial queries of core
// (TriangleTree, TetLocator).
//
// Built by splitting at the median box centre along the widest axis of the centres, so the depth is at
// most ceil(log2(#boxes)) and a depth-first walk never stacks more than depth + 1 nodes. Leaves hold up to
// four elements; elements are the indices of the boxes given to the constructor.
#pragma once

#include "vesalius/core/error.h"

#include <Eigen/Geometry>

#include <array>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace vesalius {

// One box per row of E (#E by k vertex indices into V, #V by 3): triangles or tets. Throws BadInput
// "<what> index is outside the #V vertices" if E indexes outside V.
template <class Elements>
std::vector<Eigen::AlignedBox3d> elementBoxes(const Eigen::MatrixX3d& V, const Elements& E, const std::string& what) {
  if (E.rows() > 0 && (E.minCoeff() < 0 || E.maxCoeff() >= V.rows()))
    throw BadInput("", what + " index is outside the " + std::to_string(V.rows()) + " vertices");
  std::vector<Eigen::AlignedBox3d> boxes(std::size_t(E.rows()));
  for (Eigen::Index e = 0; e < E.rows(); ++e) {
    boxes[std::size_t(e)].setEmpty();
    for (Eigen::Index k = 0; k < E.cols(); ++k) boxes[std::size_t(e)].extend(V.row(E(e, k)).transpose());
  }
  return boxes;
}

class BoxTree {
 public:
  // `boxes` must be non-empty.
  explicit BoxTree(const std::vector<Eigen::AlignedBox3d>& boxes);

  const Eigen::AlignedBox3d& bounds() const { return nodes_[0].box; }

  // Nearest-first search: visits leaves in order of box distance to p and skips every box whose
  // squared distance is not below `bound`. `visit(element)` examines one element and may lower `bound`
  // (the squared distance of the best element found so far).
  template <class Visit>
  void nearestFirst(const Eigen::Vector3d& p, double& bound, Visit visit) const;

  // Visits every element whose box lies within squared distance `margin2` of p; stops early when
  // `visit(element)` returns true.
  template <class Visit>
  void near(const Eigen::Vector3d& p, double margin2, Visit visit) const;

 private:
  struct Node {
    Eigen::AlignedBox3d box;
    int left = -1, right = -1;  // children, or -1 for a leaf
    int begin = 0, end = 0;     // range in order_ for a leaf
  };
  static constexpr int kLeafSize = 4;
  static constexpr int kStackSize = 64;

  std::vector<int> order_;
  std::vector<Node> nodes_;

  int build(int begin, int end, const std::vector<Eigen::AlignedBox3d>& boxes,
            const std::vector<Eigen::Vector3d>& centres);
};

template <class Visit>
void BoxTree::nearestFirst(const Eigen::Vector3d& p, double& bound, Visit visit) const {
  std::array<std::pair<int, double>, kStackSize> stack;
  int top = 0;
  stack[top++] = {0, nodes_[0].box.squaredExteriorDistance(p)};
  while (top > 0) {
    const auto [index, boxDistance] = stack[--top];
    if (boxDistance >= bound) continue;
    const Node& node = nodes_[index];
    if (node.left < 0) {
      for (int i = node.begin; i < node.end; ++i) visit(order_[i]);
      continue;
    }
    std::pair<int, double> nearer{node.left, nodes_[node.left].box.squaredExteriorDistance(p)};
    std::pair<int, double> farther{node.right, nodes_[node.right].box.squaredExteriorDistance(p)};
    if (farther.second < nearer.second) std::swap(nearer, farther);
    // Pushed last, so popped first: the nearer child tightens the bound before the farther is tried.
    stack[top++] = farther;
    stack[top++] = nearer;
  }
}

template <class Visit>
void BoxTree::near(const Eigen::Vector3d& p, double margin2, Visit visit) const {
  std::array<int, kStackSize> stack;
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (node.box.squaredExteriorDistance(p) > margin2) continue;
    if (node.left >= 0) {
      stack[top++] = node.right;
      stack[top++] = node.left;
      continue;
    }
    for (int i = node.begin; i < node.end; ++i)
      if (visit(order_[i])) return;
  }
}

}  // namespace vesalius
