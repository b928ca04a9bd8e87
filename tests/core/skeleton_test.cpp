// Skeleton rest transforms and BVH-style motion channels against hand-computed transforms.
#include "vesalius/core/error.h"
#include "vesalius/core/skeleton.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace vesalius {
namespace {

Joint joint(const std::string& name, int parent, const Eigen::Isometry3d& local) {
  Joint j;
  j.name = name;
  j.parent = parent;
  j.restLocal = local;
  return j;
}

Eigen::Isometry3d translation(double x, double y, double z) {
  return Eigen::Isometry3d(Eigen::Translation3d(x, y, z));
}

Skeleton chain() {
  const Eigen::Isometry3d rootLocal =
      translation(1, 0, 0) * Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ());
  const Eigen::Isometry3d handLocal =
      translation(0, 0, 3) * Eigen::AngleAxisd(M_PI / 6, Eigen::Vector3d::UnitX());
  Skeleton s;
  s.joints = {joint("root", -1, rootLocal), joint("arm", 0, translation(0, 2, 0)),
              joint("hand", 1, handLocal)};
  return s;
}

TEST(Skeleton, FindsJointsByName) {
  const Skeleton s = chain();
  EXPECT_EQ(s.find("root"), 0);
  EXPECT_EQ(s.find("hand"), 2);
  EXPECT_EQ(s.find("foot"), -1);
}

TEST(Skeleton, RestWorldComposesParentsFirst) {
  const Skeleton s = chain();
  const std::vector<Eigen::Isometry3d> world = s.restWorld();
  ASSERT_EQ(world.size(), 3u);
  EXPECT_TRUE(world[0].isApprox(s.joints[0].restLocal, 1e-14));
  EXPECT_TRUE(world[2].isApprox(s.joints[0].restLocal * s.joints[1].restLocal * s.joints[2].restLocal,
                                1e-14));
  // By hand: the root turns +y into -x, so the arm sits at (1,0,0) + (-2,0,0) and the hand 3 above.
  EXPECT_NEAR((world[1].translation() - Eigen::Vector3d(-1, 0, 0)).norm(), 0.0, 1e-14);
  EXPECT_NEAR((world[2].translation() - Eigen::Vector3d(-1, 0, 3)).norm(), 0.0, 1e-14);
  // The hand's local y axis: tilted 30 degrees towards its z about x, then turned by the root.
  const Eigen::Vector3d handY = world[2].linear() * Eigen::Vector3d::UnitY();
  EXPECT_NEAR((handY - Eigen::Vector3d(-std::cos(M_PI / 6), 0, std::sin(M_PI / 6))).norm(), 0.0, 1e-14);
}

TEST(Skeleton, ValidateRejectsBadHierarchies) {
  EXPECT_NO_THROW(chain().validate("walk.bvh"));
  Skeleton s = chain();
  s.joints[1].parent = 2;
  EXPECT_THROW(s.validate("walk.bvh"), BadInput);
  s = chain();
  s.joints[1].parent = 1;
  EXPECT_THROW(s.validate("walk.bvh"), BadInput);
  s = chain();
  s.joints[2].name = "root";
  try {
    s.validate("walk.bvh");
    ADD_FAILURE() << "validate accepted a repeated name";
  } catch (const BadInput& e) {
    EXPECT_EQ(e.file(), "walk.bvh");
  }
}

// Rz(a) Ry(b) Rx(c), degrees, written out entry by entry.
Eigen::Matrix3d zyx(double a, double b, double c) {
  const double d = M_PI / 180;
  const double ca = std::cos(a * d), sa = std::sin(a * d), cb = std::cos(b * d), sb = std::sin(b * d),
               cc = std::cos(c * d), sc = std::sin(c * d);
  Eigen::Matrix3d R;
  R << ca * cb, ca * sb * sc - sa * cc, ca * sb * cc + sa * sc,  //
      sa * cb, sa * sb * sc + ca * cc, sa * sb * cc - ca * sc,   //
      -sb, cb * sc, cb * cc;
  return R;
}

Motion twoJointMotion() {
  using C = Channel;
  Motion m;
  m.skeleton.joints = {joint("Hips", -1, translation(1, 2, 3)), joint("Spine", 0, translation(0, 5, 0))};
  m.channels = {{C::Xposition, C::Yposition, C::Zposition, C::Zrotation, C::Yrotation, C::Xrotation},
                {C::Zrotation, C::Yrotation, C::Xrotation}};
  m.values.resize(2, 9);
  m.values << 10, 20, 30, 90, 90, 0, 30, 45, 60,  //
      0, 0, 0, 0, 0, 0, 0, 0, 0;
  return m;
}

TEST(Motion, LocalPoseAppliesZyxChannelsAfterTheOffset) {
  const Motion m = twoJointMotion();
  EXPECT_EQ(m.frameCount(), 2);
  const std::vector<Eigen::Isometry3d> local = m.localPose(0);
  ASSERT_EQ(local.size(), 2u);
  Eigen::Matrix3d rootRotation;  // Rz(90) Ry(90) by hand
  rootRotation << 0, -1, 0,  //
      0, 0, 1,               //
      -1, 0, 0;
  EXPECT_NEAR((local[0].linear() - rootRotation).norm(), 0.0, 1e-14);
  EXPECT_NEAR((local[0].translation() - Eigen::Vector3d(11, 22, 33)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((zyx(90, 90, 0) - rootRotation).norm(), 0.0, 1e-14);
  EXPECT_NEAR((local[1].linear() - zyx(30, 45, 60)).norm(), 0.0, 1e-14);
  EXPECT_NEAR((local[1].translation() - Eigen::Vector3d(0, 5, 0)).norm(), 0.0, 1e-14);
}

TEST(Motion, WorldPoseComposesLocalPoses) {
  const Motion m = twoJointMotion();
  const std::vector<Eigen::Isometry3d> world = m.worldPose(0);
  ASSERT_EQ(world.size(), 2u);
  // The spine's offset (0,5,0) turned by the root: (-5,0,0) from the root at (11,22,33).
  EXPECT_NEAR((world[1].translation() - Eigen::Vector3d(6, 22, 33)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((world[1].linear() - zyx(90, 90, 0) * zyx(30, 45, 60)).norm(), 0.0, 1e-14);
  // A frame of zeros is the rest pose.
  const std::vector<Eigen::Isometry3d> rest = m.worldPose(1);
  const std::vector<Eigen::Isometry3d> expected = m.skeleton.restWorld();
  for (int j = 0; j < 2; ++j) EXPECT_TRUE(rest[j].isApprox(expected[j], 1e-14));
}

TEST(Motion, OtherChannelOrdersApplyInFileOrder) {
  Motion m = twoJointMotion();
  m.channels[1] = {Channel::Xrotation, Channel::Yrotation, Channel::Zrotation};
  const Eigen::Matrix3d expected = (Eigen::AngleAxisd(M_PI / 6, Eigen::Vector3d::UnitX()) *
                                    Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitY()) *
                                    Eigen::AngleAxisd(M_PI / 3, Eigen::Vector3d::UnitZ()))
                                       .toRotationMatrix();
  EXPECT_NEAR((m.localPose(0)[1].linear() - expected).norm(), 0.0, 1e-14);
}

}  // namespace
}  // namespace vesalius
