// Generalized winding numbers, exact or by a tree of dipoles (winding_number.h).
#include "vesalius/meshing/winding_number.h"

#include "vesalius/core/error.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

namespace vesalius::meshing {
namespace {

constexpr double kFourPi = 4.0 * M_PI;
constexpr int kLeafSize = 8;

// Solid angle of triangle (a, b, c) seen from q (van Oosterom and Strackee 1983); positive when q is on
// the side its counter-clockwise normal points away from.
double solidAngle(const Eigen::Vector3d& q, const Eigen::Vector3d& a0, const Eigen::Vector3d& b0,
                  const Eigen::Vector3d& c0) {
  const Eigen::Vector3d a = a0 - q, b = b0 - q, c = c0 - q;
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  const double numerator = a.dot(b.cross(c));
  const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
  return 2.0 * std::atan2(numerator, denominator);
}

// A bounding-volume hierarchy whose nodes carry their dipole (Barill et al. 2018 §3.2): the area-weighted
// centre of their triangles, the sum of area-weighted normals, and the radius around the centre that
// holds every vertex of them. Split at the median centroid along the widest axis, as core's BoxTree.
class DipoleTree {
 public:
  DipoleTree(const MatrixX3d& V, const MatrixX3i& F) : V_(V), F_(F), order_(std::size_t(F.rows())) {
    std::iota(order_.begin(), order_.end(), 0);
    centroids_.resize(order_.size());
    areaNormals_.resize(order_.size());
    for (std::size_t f = 0; f < order_.size(); ++f) {
      const Eigen::Vector3d a = corner(int(f), 0), b = corner(int(f), 1), c = corner(int(f), 2);
      centroids_[f] = (a + b + c) / 3.0;
      areaNormals_[f] = 0.5 * (b - a).cross(c - a);
    }
    nodes_.reserve(2 * (order_.size() / kLeafSize + 1));
    build(0, int(order_.size()));
  }

  double at(const Eigen::Vector3d& q, double beta) const {
    double sum = 0;
    std::array<int, 128> stack;
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[std::size_t(stack[--top])];
      const Eigen::Vector3d d = node.centre - q;
      const double distance = d.norm();
      if (beta > 0 && distance > beta * node.radius) {
        sum += node.areaNormal.dot(d) / (distance * distance * distance);
      } else if (node.left >= 0) {
        stack[top++] = node.left;
        stack[top++] = node.right;
      } else {
        for (int i = node.begin; i < node.end; ++i)
          sum += solidAngle(q, corner(order_[i], 0), corner(order_[i], 1), corner(order_[i], 2));
      }
    }
    return sum / kFourPi;
  }

 private:
  struct Node {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero(), areaNormal = Eigen::Vector3d::Zero();
    double radius = 0;
    int left = -1, right = -1, begin = 0, end = 0;
  };

  Eigen::Vector3d corner(int f, int k) const { return V_.row(F_(f, k)).transpose(); }

  int build(int begin, int end) {
    const int index = int(nodes_.size());
    nodes_.emplace_back();
    Node node;
    node.begin = begin;
    node.end = end;
    double area = 0;
    Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
    Eigen::AlignedBox3d centreBox;
    centreBox.setEmpty();
    for (int i = begin; i < end; ++i) {
      const double a = areaNormals_[std::size_t(order_[i])].norm();
      area += a;
      weighted += a * centroids_[std::size_t(order_[i])];
      node.areaNormal += areaNormals_[std::size_t(order_[i])];
      centreBox.extend(centroids_[std::size_t(order_[i])]);
    }
    node.centre = area > 0 ? Eigen::Vector3d(weighted / area) : centreBox.center();
    for (int i = begin; i < end; ++i)
      for (int k = 0; k < 3; ++k) node.radius = std::max(node.radius, (corner(order_[i], k) - node.centre).norm());
    if (end - begin > kLeafSize) {
      int axis;
      centreBox.sizes().maxCoeff(&axis);
      const int mid = begin + (end - begin) / 2;
      std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                       [&](int x, int y) { return centroids_[std::size_t(x)][axis] < centroids_[std::size_t(y)][axis]; });
      node.left = build(begin, mid);
      node.right = build(mid, end);
    }
    nodes_[std::size_t(index)] = node;
    return index;
  }

  const MatrixX3d& V_;
  const MatrixX3i& F_;
  std::vector<int> order_;
  std::vector<Eigen::Vector3d> centroids_, areaNormals_;
  std::vector<Node> nodes_;
};

}  // namespace

Eigen::VectorXd windingNumbers(const MatrixX3d& V, const MatrixX3i& F, const MatrixX3d& P,
                               const WindingNumberOptions& options) {
  if (!(options.beta >= 0.0)) throw UsageError("the winding-number accuracy beta must be >= 0");
  if (F.rows() > 0 && (F.minCoeff() < 0 || F.maxCoeff() >= V.rows()))
    throw BadInput("", "a triangle index is outside the " + std::to_string(V.rows()) + " vertices");
  Eigen::VectorXd w = Eigen::VectorXd::Zero(P.rows());
  if (F.rows() == 0) return w;
  const DipoleTree tree(V, F);
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, P.rows(), 256), [&](const tbb::blocked_range<Eigen::Index>& r) {
    for (Eigen::Index i = r.begin(); i < r.end(); ++i) w[i] = tree.at(P.row(i).transpose(), options.beta);
  });
  return w;
}

std::vector<PointInside> pointsInside(const MatrixX3d& V, const MatrixX3i& F, const MatrixX3d& P) {
  std::vector<PointInside> inside;
  if (P.rows() == 0) return inside;
  const Eigen::VectorXd w = windingNumbers(V, F, P);
  std::vector<Eigen::Index> rows;
  for (Eigen::Index r = 0; r < P.rows(); ++r)
    if (w[r] >= 0.5) rows.push_back(r);
  if (rows.empty()) return inside;
  const std::vector<ClosestPoint> closest = TriangleTree(V, F).closest(MatrixX3d(P(rows, Eigen::all)));
  for (std::size_t k = 0; k < rows.size(); ++k) inside.push_back({rows[k], closest[k]});
  return inside;
}

}  // namespace vesalius::meshing
