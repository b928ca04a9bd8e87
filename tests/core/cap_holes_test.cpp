// Holes closed by fans (cap_holes.h): the capped surface is closed and consistently oriented, and encloses
// the volume of the cut solid with flat caps. And the vertex normals of mesh_measures.h on the same cube.
#include "vesalius/core/cap_holes.h"
#include "vesalius/core/keep_faces.h"
#include "vesalius/core/mesh_measures.h"

#include "test_shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>
#include <utility>

namespace vesalius {
namespace {

// Every directed edge once, and its reverse once: closed and consistently oriented.
bool closedAndOriented(const TriMesh& m) {
  std::map<std::pair<int, int>, int> directed;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) ++directed[{m.F(f, k), m.F(f, (k + 1) % 3)}];
  for (const auto& [edge, count] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    if (count != 1 || reverse == directed.end() || reverse->second != 1) return false;
  }
  return true;
}

// The unit cube, 12 outward triangles.
TriMesh cube() {
  TriMesh m;
  m.V.resize(8, 3);
  m.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
  m.F.resize(12, 3);
  m.F << 0, 2, 1, 0, 3, 2,  // bottom (z = 0), seen from below
      4, 5, 6, 4, 6, 7,     // top (z = 1)
      0, 1, 5, 0, 5, 4,     // y = 0
      2, 3, 7, 2, 7, 6,     // y = 1
      1, 2, 6, 1, 6, 5,     // x = 1
      0, 4, 7, 0, 7, 3;     // x = 0
  return m;
}

TEST(CapHoles, ACubeWithoutItsTopGetsItBack) {
  TriMesh open = cube();
  ASSERT_TRUE(closedAndOriented(open));
  open.faceAttributes.integer["id"] = Eigen::VectorXi::LinSpaced(12, 0, 11);
  open = keepFaces(open, {true, true, false, false, true, true, true, true, true, true, true, true});
  ASSERT_FALSE(closedAndOriented(open));
  const TriMesh capped = capHoles(open);
  EXPECT_TRUE(closedAndOriented(capped));
  ASSERT_EQ(capped.V.rows(), 9);
  ASSERT_EQ(capped.F.rows(), 14);  // 10 kept, one per edge of the square hole
  EXPECT_TRUE(capped.V.row(8).isApprox(Eigen::RowVector3d(0.5, 0.5, 1.0)));
  EXPECT_NEAR(enclosedVolume(capped.V, capped.F), 1.0, 1e-12);
  // A cap triangle takes the attributes of the face across its edge (the sides, ids 4 to 11).
  for (Eigen::Index f = 10; f < 14; ++f) EXPECT_GE(capped.faceAttributes.integer.at("id")[f], 4);
  capped.validate("capped cube");
}

// Area-weighted vertex normals (mesh_measures.h) of the cube: each corner's along its diagonal, outward, of
// unit length; a vertex no triangle uses has none.
TEST(VertexNormals, TheCubesCornersPointAlongTheirDiagonals) {
  TriMesh m = cube();
  m.V.conservativeResize(9, 3);
  m.V.row(8) << 5, 5, 5;
  const MatrixX3d N = vertexNormals(m.V, m.F);
  ASSERT_EQ(N.rows(), 9);
  for (Eigen::Index v = 0; v < 8; ++v) {
    const Eigen::RowVector3d diagonal = (m.V.row(v).array() - 0.5).matrix().normalized();
    // A corner lies in one or two of each face's two triangles: its normal is (1 or 2, 1 or 2, 1 or 2)
    // normalized, each component signed as the diagonal's.
    const Eigen::Array3d size = N.row(v).cwiseAbs().transpose().array();
    EXPECT_GT((N.row(v).array() * diagonal.array()).minCoeff(), 0.0) << "corner " << v;
    EXPECT_LE(size.maxCoeff() / size.minCoeff(), 2.0 + 1e-12) << "corner " << v;
    EXPECT_NEAR(N.row(v).norm(), 1.0, 1e-12);
  }
  EXPECT_EQ(N.row(8).norm(), 0.0);
}

// A sphere with two caps cut off (by the faces wholly beyond |z| = 0.5, as a scan's box cuts a bone): two
// loops, each closed by a fan; the volume is that of the sphere's slab between the loops.
TEST(CapHoles, ASphereCutTwiceIsClosedWithTwoFans) {
  const TriMesh sphere = test::sphere(4);
  std::vector<bool> keep(std::size_t(sphere.F.rows()));
  for (Eigen::Index f = 0; f < sphere.F.rows(); ++f) {
    bool beyond = true;
    for (int k = 0; k < 3; ++k) beyond = beyond && std::abs(sphere.V(sphere.F(f, k), 2)) > 0.5;
    keep[std::size_t(f)] = !beyond;
  }
  const TriMesh cut = keepFaces(sphere, keep);
  const TriMesh capped = capHoles(cut);
  EXPECT_TRUE(closedAndOriented(capped));
  EXPECT_EQ(capped.V.rows(), cut.V.rows() + 2);
  // Each fan's centre lies at its loop's mean height: the enclosed volume is the unit ball's slab up to
  // those heights, less what the sphere's triangles cut off the ball (within 1 %).
  const double h1 = capped.V(capped.V.rows() - 2, 2), h2 = capped.V(capped.V.rows() - 1, 2);
  EXPECT_GT(std::abs(h1), 0.5);
  EXPECT_LT(h1 * h2, 0.0);  // one loop at each end
  const auto cap = [](double h) { return M_PI * (1 - h) * (1 - h) * (2 + h) / 3; };  // the ball beyond z = h
  const double slab = 4 * M_PI / 3 - cap(std::abs(h1)) - cap(std::abs(h2));
  const double volume = enclosedVolume(capped.V, capped.F);
  std::cout << "capped volume " << volume << ", the ball's slab between the fans' centres " << slab << '\n';
  EXPECT_NEAR(volume / slab, 1.0, 0.01);
  EXPECT_EQ(capHoles(sphere).F.rows(), sphere.F.rows());  // closed: as it was
}

}  // namespace
}  // namespace vesalius
