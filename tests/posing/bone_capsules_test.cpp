// Capsule bone regions (bone_capsules.h) in a box body with two bones along its axis.
#include "vesalius/posing/bone_capsules.h"

#include "vesalius/core/error.h"

#include "test_tets.h"

#include <gtest/gtest.h>

using namespace vesalius;

namespace {

// A 100 × 20 × 20 mm box of tets with two bones along x at y = z = 10: 0..50 and 50..100.
struct TwoBoneBox {
  TetMesh mesh = test::boxTets(50, 10, 10, 2.0);
  TriMesh skin;
  Skeleton skeleton;
  TwoBoneBox() {
    skin.V = mesh.V;
    skin.F = tetBoundary(mesh.T);
    Joint a{"a", -1, Eigen::Isometry3d(Eigen::Translation3d(0, 10, 10)), Eigen::Vector3d(50, 0, 0)};
    Joint b{"b", 0, Eigen::Isometry3d(Eigen::Translation3d(50, 0, 0)), Eigen::Vector3d(50, 0, 0)};
    skeleton.joints = {a, b};
  }
};

TEST(BoneCapsules, MarksTheTrimmedCapsulesOfRadiusAFractionOfTheClearance) {
  const TwoBoneBox box;
  posing::BoneCapsuleOptions options;
  options.radiusFraction = 0.5;  // clearance is 10 mm along the whole trimmed segments: radius 5 mm
  options.endTrim = 0.2;         // bone a: x in [10, 40], bone b: x in [60, 90]
  const Eigen::VectorXi bone = posing::boneCapsuleVertices(box.mesh.V, box.skeleton, box.skin, options);
  int counted[2] = {0, 0};
  for (Eigen::Index v = 0; v < box.mesh.V.rows(); ++v) {
    const Eigen::Vector3d p = box.mesh.V.row(v);
    const double x = p.x(), r = std::hypot(p.y() - 10, p.z() - 10);
    const double axial = x < 50 ? std::max({10 - x, x - 40, 0.0}) : std::max({60 - x, x - 90, 0.0});
    const bool inside = std::hypot(axial, r) <= 5 + 1e-9;
    EXPECT_EQ(bone[v], inside ? (x < 50 ? 0 : 1) : -1) << p.transpose();
    if (bone[v] >= 0) ++counted[bone[v]];
  }
  EXPECT_GT(counted[0], 50);
  EXPECT_EQ(counted[0], counted[1]);
}

TEST(BoneCapsules, RefusesBadOptions) {
  const TwoBoneBox box;
  posing::BoneCapsuleOptions options;
  options.radiusFraction = 1.0;
  EXPECT_THROW(posing::boneCapsuleVertices(box.mesh.V, box.skeleton, box.skin, options), UsageError);
  options = {};
  options.endTrim = 0.5;
  EXPECT_THROW(posing::boneCapsuleVertices(box.mesh.V, box.skeleton, box.skin, options), UsageError);
}

}  // namespace
