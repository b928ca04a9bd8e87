// Surface embedding (Wang et al. 2021, §4.3): a surface inside (and a little outside) a box tet mesh follows an
// affine deformation of the box exactly, keeps its triangles, uv and attributes, and a surface through
// tet-mesh vertices lands on their fitted positions for any deformation.
#include "vesalius/fit/embedding.h"

#include "test_shapes.h"
#include "test_tets.h"

#include <gtest/gtest.h>

namespace vesalius::fit {
namespace {

MatrixX3d affine(const MatrixX3d& V, const Eigen::Matrix3d& A, const Eigen::Vector3d& b) {
  return ((V * A.transpose()).rowwise() + b.transpose()).eval();
}

TEST(EmbedSurface, FollowsAnAffineMapExactlyInsideAndJustOutsideTheTetMesh) {
  const TetMesh box = test::boxTets(4, 3, 2, 10.0);  // [0, 40] x [0, 30] x [0, 20]
  // Radius 11 around the box centre: the poles at z = -1 and z = 21 lie outside the box.
  TriMesh surface = test::sphere(2, 11.0, Eigen::Vector3d(20, 15, 10));
  surface.UV = MatrixX2d::Random(surface.V.rows(), 2);
  surface.FUV = surface.F;
  surface.vertexAttributes.real["thickness"] = Eigen::MatrixXd::Random(surface.V.rows(), 1);
  surface.faceAttributes.integer[kLabel] = Eigen::VectorXi::Constant(surface.F.rows(), 7);
  ASSERT_LT(surface.V.col(2).minCoeff(), 0.0);

  Eigen::Matrix3d A;
  A << 1.3, 0.2, 0.0, 0.0, 0.8, 0.1, 0.05, 0.0, 1.1;
  const Eigen::Vector3d b(5, -3, 7);
  const TriMesh moved = embedSurface(surface, box.V, box.T, affine(box.V, A, b));

  EXPECT_LT((moved.V - affine(surface.V, A, b)).cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_EQ(moved.F, surface.F);
  EXPECT_EQ(moved.UV, surface.UV);
  EXPECT_EQ(moved.FUV, surface.FUV);
  EXPECT_EQ(moved.vertexAttributes.real.at("thickness"), surface.vertexAttributes.real.at("thickness"));
  EXPECT_EQ(moved.faceAttributes.integer.at(kLabel), surface.faceAttributes.integer.at(kLabel));
}

TEST(EmbedSurface, VerticesOnTetVerticesLandOnTheirFittedPositions) {
  const TetMesh box = test::boxTets(3, 3, 3, 5.0);
  TriMesh surface;
  surface.V.resize(3, 3);
  surface.V << box.V.row(5), box.V.row(21), box.V.row(40);
  surface.F.resize(1, 3);
  surface.F << 0, 1, 2;
  const MatrixX3d fitted = box.V + 3.0 * MatrixX3d::Random(box.V.rows(), 3);
  const TriMesh moved = embedSurface(surface, box.V, box.T, fitted);
  EXPECT_LT((moved.V.row(0) - fitted.row(5)).norm(), 1e-10);
  EXPECT_LT((moved.V.row(1) - fitted.row(21)).norm(), 1e-10);
  EXPECT_LT((moved.V.row(2) - fitted.row(40)).norm(), 1e-10);
}

}  // namespace
}  // namespace vesalius::fit
