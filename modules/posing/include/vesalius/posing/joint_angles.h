// A single pose from joint angles typed on the command line (Sujar et al. 2018, §3.5: "our implementation allows
// animating the virtual model using direct kinematic").
//
// Syntax: one or more "joint=x,y,z" separated by ';' or white space, angles in degrees, e.g.
//     upperleg01.L=30,0,0; lowerleg01.L=-60,0,0
// Each joint turns by R = Rx(x)·Ry(y)·Rz(z) (intrinsic X, then Y, then Z) about its own rest frame,
// after its rest local transform: local = restLocal · R. Joints not named keep their rest local rotation,
// so a named joint carries its descendants with it. For a MakeHuman skeleton in LPS
// (skeleton_pose.h) the rest frames are the LPS axes: x = left, y = posterior, z = superior; by the
// right-hand rule a positive x angle swings a hanging thigh backward (extension), so hip flexion is
// negative x.
#pragma once

#include "vesalius/core/skeleton.h"

#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace vesalius::posing {

struct JointAngle {
  std::string joint;
  Eigen::Vector3d degrees = Eigen::Vector3d::Zero();  // x, y, z
};

// Throws UsageError naming the offending item: a missing '=', not three comma-separated numbers, a
// non-finite number, an empty joint name, a joint named twice.
std::vector<JointAngle> parseJointAngles(const std::string& text);

// Posed world transform of every joint of `skeleton` (#joints, as Motion::worldPose). Throws UsageError
// for a joint the skeleton does not have.
std::vector<Eigen::Isometry3d> poseFromJointAngles(const Skeleton& skeleton, const std::vector<JointAngle>& angles);

}  // namespace vesalius::posing
