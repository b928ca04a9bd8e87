// Affine ICP: a lopsided ellipsoid mapped by a known affine map (shear and anisotropic scale, as between a
// template liver and a patient's) is recovered from points of the mapped surface; few targets change nothing.
#include "vesalius/fit/affine_icp.h"

#include "vesalius/core/triangle_tree.h"

#include "test_shapes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace vesalius::fit {
namespace {

// An ellipsoid of semi-axes about 10, 7 and 5 mm whose +x half is stretched 1.3 times: no symmetry an
// affine map could confuse.
TriMesh lopsided() {
  TriMesh s = test::sphere(3, 10.0);
  for (Eigen::Index v = 0; v < s.V.rows(); ++v)
    s.V.row(v) = Eigen::RowVector3d(s.V(v, 0) * (s.V(v, 0) > 0 ? 1.3 : 1.0), 0.7 * s.V(v, 1), 0.5 * s.V(v, 2));
  return s;
}

MatrixX3d mapped(const MatrixX3d& V, const Eigen::Matrix3d& A, const Eigen::RowVector3d& b) {
  return (V * A.transpose()).rowwise() + b;
}

TEST(AffineIcp, RecoversAKnownAffineMap) {
  const TriMesh surface = lopsided();
  Eigen::Matrix3d A;
  A << 1.15, 0.10, 0.0, -0.05, 0.90, 0.08, 0.0, 0.04, 1.10;
  const Eigen::RowVector3d b(1.5, -1.0, 0.5);
  const MatrixX3d targets = mapped(surface.V, A, b);
  const TriMesh fitted = refineAffineIcp(surface, targets);
  double gap = 0;  // what ICP minimises: the targets' distance to the surface
  for (const ClosestPoint& c : TriangleTree(fitted.V, fitted.F).closest(targets)) gap += std::sqrt(c.squaredDistance);
  gap /= double(targets.rows());
  EXPECT_GT((surface.V - targets).rowwise().norm().mean(), 1.0);
  EXPECT_LT(gap, 0.02);  // mm, on a 26 mm object
  // Closest-point pairs may slide along the surface, so vertices land near, not on, their images.
  EXPECT_LT((fitted.V - targets).rowwise().norm().mean(), 0.6);
  EXPECT_EQ(fitted.F, surface.F);
}

TEST(AffineIcp, KeepsTheSurfaceWithFewerTargetsThanTheMinimum) {
  const TriMesh surface = lopsided();
  const MatrixX3d targets = surface.V.topRows(19).array() + 2.0;
  EXPECT_EQ(refineAffineIcp(surface, targets).V, surface.V);
}

}  // namespace
}  // namespace vesalius::fit
