// smoothDisplacement on a subdivided icosahedron (radius 10 mm): a lone pull translates the whole surface
// (the membrane energy does not resist a translation); two opposite pulls stretch it symmetrically, less
// than asked and less with more smoothness, with the equator staying put; weights 0 move nothing; bad
// input is refused.
#include "vesalius/fit/smooth_displacement.h"

#include "vesalius/core/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <utility>

namespace vesalius::fit {
namespace {

// Icosahedron split once (each triangle into four, midpoints pushed to the sphere): 42 vertices, 80 faces.
TriMesh sphere(double radius) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  MatrixX3d V(12, 3);
  V << -1, t, 0, 1, t, 0, -1, -t, 0, 1, -t, 0, 0, -1, t, 0, 1, t, 0, -1, -t, 0, 1, -t, t, 0, -1, t, 0, 1, -t, 0, -1,
      -t, 0, 1;
  MatrixX3i F(20, 3);
  F << 0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3, 9, 4, 3, 4,
      2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1;
  std::vector<Eigen::Vector3d> points;
  for (Eigen::Index i = 0; i < V.rows(); ++i) points.push_back(V.row(i).transpose());
  std::map<std::pair<int, int>, int> midpoint;
  auto middle = [&](int a, int b) {
    const auto key = std::minmax(a, b);
    auto [it, inserted] = midpoint.try_emplace(key, int(points.size()));
    if (inserted) points.push_back((points[std::size_t(a)] + points[std::size_t(b)]) / 2);
    return it->second;
  };
  TriMesh mesh;
  mesh.F.resize(80, 3);
  for (int f = 0; f < 20; ++f) {
    const int a = F(f, 0), b = F(f, 1), c = F(f, 2), ab = middle(a, b), bc = middle(b, c), ca = middle(c, a);
    mesh.F.row(4 * f) << a, ab, ca;
    mesh.F.row(4 * f + 1) << b, bc, ab;
    mesh.F.row(4 * f + 2) << c, ca, bc;
    mesh.F.row(4 * f + 3) << ab, bc, ca;
  }
  mesh.V.resize(Eigen::Index(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) mesh.V.row(Eigen::Index(i)) = radius * points[i].normalized();
  return mesh;
}

TEST(SmoothDisplacement, ALonePullTranslatesTheWholeSurface) {
  const TriMesh s = sphere(10);
  const MatrixX3d point = s.V.row(0), move = Eigen::RowVector3d(1, -2, 3);
  const MatrixX3d U = smoothDisplacement(s, point, move, Eigen::VectorXd::Ones(1));
  for (Eigen::Index i = 0; i < U.rows(); ++i) EXPECT_LT((U.row(i) - move).norm(), 1e-6) << "vertex " << i;
}

TEST(SmoothDisplacement, OppositePullsStretchLessThanAskedAndLessWhenStiffer) {
  const TriMesh s = sphere(10);
  Eigen::Index top = 0, bottom = 0;
  s.V.col(1).maxCoeff(&top);
  s.V.col(1).minCoeff(&bottom);
  MatrixX3d points(2, 3), moves(2, 3);
  points << s.V.row(top), s.V.row(bottom);
  moves << 0, 5, 0, 0, -5, 0;
  double previous = 5;
  for (double smoothness : {0.1, 1.0, 10.0}) {
    const MatrixX3d U = smoothDisplacement(s, points, moves, Eigen::VectorXd::Ones(2), {smoothness});
    const double up = U(top, 1);
    EXPECT_GT(up, 0) << smoothness;
    EXPECT_LT(up, previous) << "stiffer moves the pulled vertex less: " << smoothness;
    EXPECT_NEAR(U(bottom, 1), -up, 1e-9) << smoothness;
    for (Eigen::Index i = 0; i < s.V.rows(); ++i) {
      if (std::abs(s.V(i, 1)) < 1e-9) {
        EXPECT_NEAR(U(i, 1), 0.0, 1e-9) << "equator vertex " << i;
      }
    }
    previous = up;
  }
}

TEST(SmoothDisplacement, ZeroWeightsMoveNothingAndBadInputIsRefused) {
  const TriMesh s = sphere(10);
  const MatrixX3d points = s.V.topRows(3), moves = MatrixX3d::Constant(3, 3, 4.0);
  EXPECT_EQ(smoothDisplacement(s, points, moves, Eigen::VectorXd::Zero(3)).norm(), 0.0);
  EXPECT_THROW(smoothDisplacement(s, points, moves, -Eigen::VectorXd::Ones(3)), UsageError);
  EXPECT_THROW(smoothDisplacement(s, points, moves.topRows(2), Eigen::VectorXd::Ones(3)), UsageError);
  EXPECT_THROW(smoothDisplacement(s, points, moves, Eigen::VectorXd::Ones(3), {0.0}), UsageError);
}

}  // namespace
}  // namespace vesalius::fit
