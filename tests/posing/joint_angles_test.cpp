// Joint-angle poses (joint_angles.h): parsing and its errors, and the pose they give.
#include "vesalius/posing/joint_angles.h"
#include "vesalius/posing/joint_map.h"
#include "vesalius/posing/skeleton_from_bone_meshes.h"

#include "vesalius/core/error.h"

#include "motion_test_support.h"

#include <gtest/gtest.h>

#include <algorithm>

using namespace vesalius;

namespace {

TEST(JointAngles, ParsesItemsSeparatedBySemicolonsOrSpaces) {
  const auto angles = posing::parseJointAngles("upperleg01.L=30,0,0; lowerleg01.L=-60,1.5,2e1  head=0,0,-5");
  ASSERT_EQ(angles.size(), 3u);
  EXPECT_EQ(angles[1].joint, "lowerleg01.L");
  EXPECT_EQ(angles[1].degrees, Eigen::Vector3d(-60, 1.5, 20));
  EXPECT_EQ(angles[2].degrees, Eigen::Vector3d(0, 0, -5));
  EXPECT_TRUE(posing::parseJointAngles("  ").empty());
}

TEST(JointAngles, RefusesMalformedItems) {
  for (const char* bad : {"thigh", "=1,2,3", "thigh=1,2", "thigh=1,2,3,4", "thigh=1,x,3", "thigh=1,,3", "thigh=nan,0,0",
                          "thigh=1e999,0,0", "thigh=1,2,3 thigh=0,0,0"})
    EXPECT_THROW(posing::parseJointAngles(bad), UsageError) << bad;
  try {
    posing::parseJointAngles("thigh.L=30,zero,0");
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("'zero' is not a finite number"), std::string::npos) << e.what();
  }
}

TEST(JointAngles, RefusesAnUnknownJoint) {
  EXPECT_THROW(posing::poseFromJointAngles(test::makeHumanSkeletonLps(), posing::parseJointAngles("thigh.L=30,0,0")),
               UsageError);
}

TEST(JointAngles, TurnsTheJointAboutItsRestFrameAndCarriesItsDescendants) {
  const Skeleton& skeleton = test::makeHumanSkeletonLps();
  const auto rest = skeleton.restWorld();
  const auto posed = posing::poseFromJointAngles(skeleton, posing::parseJointAngles("upperleg01.L=-30,0,0"));
  const int hip = skeleton.find("upperleg01.L"), knee = skeleton.find("lowerleg01.L"), other = skeleton.find("foot.R");
  EXPECT_NEAR(test::rotationDegrees(posed[hip].linear() * rest[hip].linear().transpose()), 30.0, 1e-9);
  // The knee swings about the hip's left (x) axis: forward (anterior, -y in LPS) for a negative angle.
  const Eigen::Vector3d thigh = rest[knee].translation() - rest[hip].translation();
  const Eigen::Vector3d expected =
      rest[hip].translation() + Eigen::AngleAxisd(-M_PI / 6, Eigen::Vector3d::UnitX()) * thigh;
  EXPECT_LT((posed[knee].translation() - expected).norm(), 1e-9);
  EXPECT_LT(posed[knee].translation().y(), rest[knee].translation().y() - 100);  // > 10 cm forward
  EXPECT_LT((posed[other].matrix() - rest[other].matrix()).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(JointAngles, AppliesXThenYThenZIntrinsically) {
  const Skeleton& skeleton = test::makeHumanSkeletonLps();
  const int j = skeleton.find("head");
  const auto posed = posing::poseFromJointAngles(skeleton, posing::parseJointAngles("head=10,20,30"));
  const Eigen::Matrix3d local = posed[skeleton.find("neck03")].linear().transpose() * posed[j].linear();
  const Eigen::Matrix3d expected = (Eigen::AngleAxisd(10 * M_PI / 180, Eigen::Vector3d::UnitX()) *
                                    Eigen::AngleAxisd(20 * M_PI / 180, Eigen::Vector3d::UnitY()) *
                                    Eigen::AngleAxisd(30 * M_PI / 180, Eigen::Vector3d::UnitZ()))
                                       .toRotationMatrix();
  EXPECT_LT((local - skeleton.joints[j].restLocal.linear() * expected).norm(), 1e-12);
}

TEST(JointMap, ParsesPairsAndComments) {
  const auto map = posing::parseJointMap("# CMU to ours\n\nHips root  # pelvis\n LeftUpLeg\tupperleg01.L\n", "m.txt");
  ASSERT_EQ(map.pairs.size(), 2u);
  EXPECT_EQ(map.pairs[1], std::make_pair(std::string("LeftUpLeg"), std::string("upperleg01.L")));
}

TEST(JointMap, RefusesBadLinesNamingTheFileAndLine) {
  for (const char* bad : {"Hips\n", "Hips root extra\n", "Hips root\nSpine root\n"}) {
    try {
      posing::parseJointMap(bad, "m.txt");
      FAIL() << bad;
    } catch (const BadInput& e) {
      EXPECT_EQ(std::string(e.what()).rfind("m.txt: line ", 0), 0u) << e.what();
    }
  }
}

TEST(JointMap, DefaultCmuMapNamesJointsOfBothSkeletons) {
  const auto map = posing::cmuToMakeHumanJointMap();
  EXPECT_EQ(map.pairs.size(), 21u);
  for (const auto& [from, to] : map.pairs) {
    EXPECT_GE(test::cmuMotion().skeleton.find(from), 0) << from;
    EXPECT_GE(test::makeHumanSkeletonLps().find(to), 0) << to;
  }
}

// The skeleton of bone meshes (OpenSim's bodies): every one of its joints driven by a CMU joint, and the
// default map for a motion onto it.
TEST(JointMap, CmuOntoBoneMeshSkeletonDrivesEveryJoint) {
  const std::vector<std::string> joints = posing::meshSkeletonJoints();
  ASSERT_EQ(joints.size(), 14u);
  Skeleton target;
  for (const std::string& name : joints) target.joints.push_back({name, name == "pelvis" ? -1 : 0});
  const posing::JointMap map = posing::defaultJointMap(test::cmuMotion().skeleton, target);
  EXPECT_EQ(map.pairs.size(), joints.size());
  for (const std::string& joint : joints)
    EXPECT_TRUE(std::any_of(map.pairs.begin(), map.pairs.end(), [&](const auto& p) { return p.second == joint; })) << joint;
  for (const auto& [from, to] : map.pairs) EXPECT_GE(test::cmuMotion().skeleton.find(from), 0) << from;
}

}  // namespace
