// Motion retargeting (retarget.h): onto the motion's own skeleton it is exact; a single source rotation
// turns exactly the mapped target joint and its descendants; the CMU motion on MakeHuman's skeleton keeps
// the pelvis in one piece, the target's bone lengths and the feet on the floor.
#include "vesalius/posing/retarget.h"

#include "vesalius/core/error.h"

#include "motion_test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

using namespace vesalius;
using posing::Retargeter;

namespace {

posing::JointMap identityMap(const Skeleton& skeleton) {
  posing::JointMap map;
  for (const Joint& joint : skeleton.joints) map.pairs.emplace_back(joint.name, joint.name);
  return map;
}

posing::RetargetOptions cmuOntoLps() {
  posing::RetargetOptions options;
  options.sourceAxes = io::yUpToLps();
  return options;
}

// The CMU motion with one frame of all-zero channels (its rest, a T-pose) and, optionally, one rotation.
Motion cmuSingleFrame(const std::string& joint = "", int channel = 0, double degrees = 0) {
  Motion motion = test::cmuMotion();
  motion.values = Eigen::MatrixXd::Zero(1, motion.values.cols());
  if (joint.empty()) return motion;
  Eigen::Index column = 0;
  for (int j = 0; j < motion.skeleton.find(joint); ++j) column += Eigen::Index(motion.channels[j].size());
  motion.values(0, column + channel) = degrees;
  return motion;
}

bool descends(const Skeleton& skeleton, int j, int ancestor) {
  for (; j >= 0; j = skeleton.joints[j].parent)
    if (j == ancestor) return true;
  return false;
}

TEST(Retarget, OntoItselfReproducesTheMotion) {
  const Motion& motion = test::cmuMotion();
  const Retargeter retarget(motion.skeleton, motion.skeleton, identityMap(motion.skeleton));
  EXPECT_DOUBLE_EQ(retarget.rootScale(), 1.0);
  double worst = 0;
  for (int frame = 0; frame < motion.frameCount(); frame += 97) {
    const auto expected = motion.worldPose(frame), got = retarget.pose(expected);
    for (std::size_t j = 0; j < got.size(); ++j)
      worst = std::max(worst, (got[j].matrix() - expected[j].matrix()).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst, 1e-9);
}

TEST(Retarget, OneSourceRotationTurnsOnlyTheMappedJointAndItsDescendants) {
  const Skeleton& target = test::makeHumanSkeletonLps();
  const Motion rest = cmuSingleFrame(), bent = cmuSingleFrame("LeftLeg", 2, 30.0);  // Z Y X: X is channel 2
  const Retargeter retarget(rest.skeleton, target, posing::cmuToMakeHumanJointMap(), cmuOntoLps());
  const auto a = retarget.pose(rest.worldPose(0)), b = retarget.pose(bent.worldPose(0));
  const int knee = target.find("lowerleg01.L");
  ASSERT_GE(knee, 0);
  EXPECT_NEAR(test::rotationDegrees(b[knee].linear() * a[knee].linear().transpose()), 30.0, 1e-9);
  // About the source's knee axis (its X, the LPS left axis): a pure flexion of the target's knee.
  const Eigen::AngleAxisd turn(b[knee].linear() * a[knee].linear().transpose());
  EXPECT_NEAR(std::abs(turn.axis().x()), 1.0, 1e-9);
  double still = 0, moved = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < target.joints.size(); ++j) {
    const double change = (b[j].matrix() - a[j].matrix()).cwiseAbs().maxCoeff();
    if (!descends(target, int(j), knee)) still = std::max(still, change);
    else moved = std::min(moved, (b[j].linear() - a[j].linear()).norm());
  }
  EXPECT_LT(still, 1e-9);
  EXPECT_GT(moved, 0.1);  // every descendant turned (a 30° rotation differs from I by 0.73 in norm)
  EXPECT_GT((b[target.find("foot.L")].translation() - a[target.find("foot.L")].translation()).norm(), 100.0);
}

TEST(Retarget, RestDirectionsAlignToTheSourceRest) {
  // In the source's rest (CMU's T-pose) every aligned target bone points as its source bone does, so
  // MakeHuman's A-pose arms rise to horizontal.
  const Skeleton& target = test::makeHumanSkeletonLps();
  const Motion rest = cmuSingleFrame();
  const Retargeter retarget(rest.skeleton, target, posing::cmuToMakeHumanJointMap(), cmuOntoLps());
  const auto posed = retarget.pose(rest.worldPose(0));
  const auto source = rest.skeleton.restWorld();
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"LeftArm", "upperarm01.L"}, {"LeftUpLeg", "upperleg01.L"}, {"RightForeArm", "lowerarm01.R"}}) {
    const int s = rest.skeleton.find(from), t = target.find(to);
    const Eigen::Vector3d child = rest.skeleton.joints[s + 1].restLocal.translation();  // the only child
    const Eigen::Vector3d ds = io::yUpToLps() * source[s].linear() * child;
    const Eigen::Vector3d dt = posed[t].linear() * target.joints[t].tail;
    EXPECT_LT(std::acos(std::clamp(ds.normalized().dot(dt.normalized()), -1.0, 1.0)), 1e-7) << to;
  }
  // CMU's upper arm is horizontal at rest: the target's now is too (its A-pose arm is ~45° down).
  const Eigen::Vector3d arm = posed[target.find("upperarm01.L")].linear() * target.joints[target.find("upperarm01.L")].tail;
  EXPECT_LT(std::abs(arm.normalized().z()), 0.05);
}

TEST(Retarget, ThePelvisStaysOnePieceWithTheRoot) {
  // CMU's LHipJoint and RHipJoint are fixed offsets (their channels are 0 in every frame of 01_01): the hips
  // sit where the root carries them. Aligning MakeHuman's pelvis halves to them turned the halves apart.
  const Motion& motion = test::cmuMotion();
  const Skeleton& target = test::makeHumanSkeletonLps();
  const Retargeter retarget(motion.skeleton, target, posing::cmuToMakeHumanJointMap(), cmuOntoLps());
  const auto rest = target.restWorld();
  const int root = target.find("root");
  double worst = 0;
  for (int frame : {0, 750, 1750}) {
    const auto posed = retarget.pose(motion.worldPose(frame));
    for (const std::string hip : {"upperleg01.L", "upperleg01.R"}) {
      const int j = target.find(hip);
      const Eigen::Vector3d atRest = rest[root].inverse() * rest[j].translation();
      worst = std::max(worst, (posed[root].inverse() * posed[j].translation() - atRest).norm());
    }
  }
  EXPECT_LT(worst, 1e-9);  // mm; before, the halves' alignment moved the hips
}

TEST(Retarget, AMotionFromItsFirstFrameStartsOnTheRig) {
  // CMU's rest is at the studio origin: frame 0 stands 1.2 m from it. With the first frame as the stance
  // the motion starts where the rig stands, its feet on the rig's floor.
  const Motion& motion = test::cmuMotion();
  const Skeleton& target = test::makeHumanSkeletonLps();
  posing::RetargetOptions options = cmuOntoLps();
  const Retargeter fromRest(motion.skeleton, target, posing::cmuToMakeHumanJointMap(), options);
  options.sourceStance = motion.worldPose(0);
  const Retargeter fromFirstFrame(motion.skeleton, target, posing::cmuToMakeHumanJointMap(), options);
  const auto rest = target.restWorld();
  const int root = target.find("root");
  const auto first = fromFirstFrame.pose(motion.worldPose(0));
  const Eigen::Vector3d moved = first[root].translation() - rest[root].translation();
  EXPECT_LT(moved.head<2>().norm(), 1e-9);  // L and P: where the rig stands
  double lowestRest = std::numeric_limits<double>::infinity(), lowestFirst = lowestRest;
  for (std::size_t j = 0; j < rest.size(); ++j) {
    lowestRest = std::min(lowestRest, rest[j].translation().z());
    lowestFirst = std::min(lowestFirst, first[j].translation().z());
  }
  std::printf("frame 0 from its first frame: root moved %.1f mm up, lowest joint %.1g mm above the rest floor; "
              "from the BVH rest the root is %.0f mm from the rig's\n",
              moved.z(), lowestFirst - lowestRest,
              (fromRest.pose(motion.worldPose(0))[root].translation() - rest[root].translation()).norm());
  EXPECT_LT(std::abs(lowestFirst - lowestRest), 1e-9);
  // Later frames move by the source's displacement from frame 0, scaled.
  const int later = 1750;
  const Eigen::Vector3d a = fromFirstFrame.pose(motion.worldPose(later))[root].translation() - first[root].translation();
  const Eigen::Vector3d b = fromFirstFrame.rootScale() * io::yUpToLps() *
                            (motion.worldPose(later).front().translation() - motion.worldPose(0).front().translation());
  EXPECT_LT((a - b).norm(), 1e-9);
}

TEST(Retarget, CmuMotionOnMakeHumanKeepsBoneLengthsAndFeetOnTheFloor) {
  const Motion& motion = test::cmuMotion();
  const Skeleton& target = test::makeHumanSkeletonLps();
  posing::RetargetOptions options = cmuOntoLps();
  options.sourceStance = motion.worldPose(0);  // as `vesalius pose` plays it
  const Retargeter retarget(motion.skeleton, target, posing::cmuToMakeHumanJointMap(), options);
  EXPECT_TRUE(retarget.skipped().empty());
  // Hip heights: CMU ~16.8 units (~0.95 m), MakeHuman ~0.9 m: about 55 mm per CMU unit.
  EXPECT_GT(retarget.rootScale(), 45.0);
  EXPECT_LT(retarget.rootScale(), 65.0);
  const auto rest = target.restWorld();
  const auto sourceStance = motion.worldPose(0);
  auto lowest = [](const std::vector<Eigen::Isometry3d>& pose, const Skeleton& s, const std::vector<std::string>& names,
                   const Eigen::Vector3d& up) {
    double h = std::numeric_limits<double>::infinity();
    for (const auto& n : names) h = std::min(h, pose[s.find(n)].translation().dot(up));
    return h;
  };
  const std::vector<std::string> targetFeet{"foot.L", "foot.R", "toe1-1.L", "toe1-1.R"};
  const std::vector<std::string> sourceFeet{"LeftFoot", "RightFoot", "LeftToeBase", "RightToeBase"};
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ(), sourceUp = Eigen::Vector3d::UnitY();
  const double floor = lowest(rest, target, targetFeet, up), sourceFloor = lowest(sourceStance, motion.skeleton, sourceFeet, sourceUp);
  double worstLength = 0, worstFloor = 0;
  for (int frame = 0; frame < motion.frameCount(); frame += 11) {
    const auto posed = retarget.pose(motion.worldPose(frame));
    for (std::size_t j = 0; j < target.joints.size(); ++j) {
      const int p = target.joints[j].parent;
      if (p < 0) continue;
      worstLength = std::max(worstLength, std::abs((posed[j].translation() - posed[p].translation()).norm() -
                                                   (rest[j].translation() - rest[p].translation()).norm()));
    }
    // The target's lowest foot joint above its rest floor, against the source's, scaled.
    const double targetLift = lowest(posed, target, targetFeet, up) - floor;
    const double sourceLift =
        retarget.rootScale() * (lowest(motion.worldPose(frame), motion.skeleton, sourceFeet, sourceUp) - sourceFloor);
    worstFloor = std::max(worstFloor, std::abs(targetLift - sourceLift));
  }
  EXPECT_LT(worstLength, 1e-9);
  std::printf("lowest foot joint, target vs scaled source: worst %.1f mm\n", worstFloor);
  // Measured 33.9 mm (different leg proportions); 70 mm with the source's rest as the stance (its legs
  // apart), 36 mm when MakeHuman's pelvis halves were aligned to CMU's hip offsets, which moved the hips.
  EXPECT_LT(worstFloor, 45.0);
}

TEST(Retarget, RefusesAMapMatchingNothingAndPosesOfTheWrongSize) {
  const Motion& motion = test::cmuMotion();
  posing::JointMap none;
  none.pairs = {{"Nope", "root"}};
  EXPECT_THROW(Retargeter(motion.skeleton, test::makeHumanSkeletonLps(), none), BadInput);
  const Retargeter retarget(motion.skeleton, motion.skeleton, identityMap(motion.skeleton));
  EXPECT_THROW(retarget.pose({}), UsageError);
}

}  // namespace
