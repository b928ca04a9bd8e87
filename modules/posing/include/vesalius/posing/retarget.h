// Motion retargeting: a pose of a motion's skeleton (a BVH frame) carried onto our skeleton, as the
// per-joint world transforms skinning consumes (Sujar et al. 2018, §3.5: "techniques such as retargeting [44] ...
// can be directly applied to our system").
//
// Method, per target joint t (parents first), with source joint s = map(t):
//   D_s = R_s,posed · R_s,restᵀ        the source joint's world rotation away from its rest (source axes)
//   D   = C D_s Cᵀ                      the same rotation in target axes (C = options.sourceAxes)
//   R_t,posed = D · A_t · R_t,rest      A_t: the rest-direction alignment below
// An unmapped joint keeps its rest rotation relative to its parent: R_t,posed = R_parent,posed · L_t,rest.
// Every joint sits where its posed parent carries its rest offset (the target's own bone lengths, exactly);
// a mapped root moves by the source root's displacement from its stance (options.sourceStance, by default
// the source's rest), in target axes, times the ratio of the two skeletons' hip heights (root above the
// lowest joint along up, both in that stance), which also converts the units (CMU's 5.64 cm units to our
// millimetres), and is lifted so that in the stance the target's lowest joint stands on the target's rest
// floor (MakeHuman's A-pose legs do not reach as low as the same legs turned to CMU's rest).
//
// Why world deltas with an alignment: the two rest poses differ (CMU's rest is a T-pose with the legs
// apart, MakeHuman's an A-pose). Copying local rotations (or world deltas alone) reproduces the source's
// rotation *away from its rest*, so a CMU arm hanging down (80° below its T-pose) would put MakeHuman's
// arm 80° below its A-pose, into the hip. A_t is the smallest rotation taking the target bone's rest
// direction (joint to tail) onto the source bone's rest direction (joint to its only child or its End
// Site), so the target first takes the source's rest pose and then follows its deltas: bone directions
// match the source's whatever the two rests. A joint without a direction on either side (a joint with
// several children in the source, such as CMU's Hips and Spine1) is not aligned (A_t = I).
// Retargeting a skeleton onto itself is exact (A_t = I, tests/posing/retarget_test.cpp).
#pragma once

#include "vesalius/core/skeleton.h"
#include "vesalius/posing/joint_map.h"

#include <Eigen/Geometry>

#include <optional>
#include <string>
#include <vector>

namespace vesalius::posing {

struct RetargetOptions {
  Eigen::Matrix3d sourceAxes = Eigen::Matrix3d::Identity();  // C: source world axes to target world axes
  Eigen::Vector3d sourceUp = Eigen::Vector3d::UnitY();       // up in source axes (BVH: +Y), for hip heights
  bool alignRestDirections = true;                           // A_t above; off gives A_t = I
  // The source's stance (#source-joints world transforms, as Motion::worldPose gives): the pose in which
  // ours stands at its rest place on its rest floor, and in which the hip heights are compared; the
  // source's rest if not given. A motion capture's rest is at its studio's origin (CMU's Hips at 0, the
  // subject 1.2 m from it in frame 0, legs apart); playback passes the first frame, so a motion starts
  // where the rig stands.
  std::optional<std::vector<Eigen::Isometry3d>> sourceStance;
};

class Retargeter {
 public:
  // source: the motion's skeleton at rest; target: ours at rest. Pairs of `map` naming a joint absent from
  // either skeleton are skipped (listed by skipped()). Throws BadInput (naming `mapSource`) if no pair
  // matches, UsageError if options.sourceAxes is not a rotation or sourceUp is zero.
  Retargeter(const Skeleton& source, const Skeleton& target, const JointMap& map, const RetargetOptions& options = {},
             const std::string& mapSource = "joint map");

  // sourceWorld: #source-joints posed world transforms (Motion::worldPose). Returns #target-joints posed
  // world transforms. Throws UsageError if sourceWorld has the wrong size.
  std::vector<Eigen::Isometry3d> pose(const std::vector<Eigen::Isometry3d>& sourceWorld) const;

  double rootScale() const { return rootScale_; }                              // target / source hip height
  const std::vector<std::string>& skipped() const { return skipped_; }        // "source -> target" pairs

 private:
  Skeleton target_;
  std::vector<Eigen::Isometry3d> sourceRest_, targetRest_;
  std::vector<int> driver_;                 // per target joint: its source joint, -1 if unmapped
  std::vector<Eigen::Matrix3d> alignment_;  // per target joint: A_t
  Eigen::Matrix3d axes_;
  double rootScale_ = 1.0;
  Eigen::Vector3d rootLift_ = Eigen::Vector3d::Zero();  // puts the target's feet on its rest floor in the stance
  std::vector<Eigen::Isometry3d> sourceStance_;          // options.sourceStance or the source's rest
  std::vector<std::string> skipped_;
};

}  // namespace vesalius::posing
