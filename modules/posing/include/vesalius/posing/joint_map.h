// Which joint of a motion's skeleton drives which joint of ours: the name map of motion retargeting
// (Sujar et al. 2018, §3.5, names retargeting as the way recorded motions reach the virtual skeleton; retarget.h).
//
// The file format is text, one pair a line, "# comment" lines and blank lines ignored:
//     # source (motion) joint    target (skeleton) joint
//     LeftUpLeg                  upperleg01.L
// A target joint appears at most once (it has one driver); a source joint may drive several targets.
// Target joints the map does not name keep their rest rotation relative to their parent (retarget.h).
#pragma once

#include "vesalius/core/skeleton.h"

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace vesalius::posing {

struct JointMap {
  std::vector<std::pair<std::string, std::string>> pairs;  // (source joint, target joint), file order
};

// Throws BadInput "<source>: line N: <problem>" for a line that is not two names or a target named twice.
JointMap parseJointMap(std::string_view text, const std::string& source);

// CMU motion-capture BVH names (testdata/motion/01_01.bvh: Hips, LHipJoint, LeftUpLeg, ...) onto the
// bones of MakeHuman's default.mhskel (root, pelvis.L, upperleg01.L, ...). MakeHuman splits the limbs and
// spine into more bones than CMU has joints; the map drives the first bone of each split (upperleg01.L
// for the thigh) and its unmapped continuation (upperleg02.L) follows rigidly. Fingers, toes and the face
// are not driven, nor are MakeHuman's pelvis halves (pelvis.L, pelvis.R): CMU's LHipJoint and RHipJoint
// are fixed offsets in the pelvis, and aligning the halves' rest directions to theirs (retarget.h) turned
// the two halves apart about the root in every frame, moving the hips and tearing the lower trunk (skin
// volume +3.2 % with DQS and -3.4 % with LBS in the T-pose of frame 0 from that alone).
JointMap cmuToMakeHumanJointMap();

// CMU names onto the skeleton of a scan's segmented bones (skeleton_from_bones.h: pelvis, femur_left,
// femur_right, vertebrae_L5 upward): the hips drive the pelvis, the thighs the femurs, the lower back the
// lowest vertebra, which carries the ones above it. A scan shows no more of the body, so nothing else is
// driven.
JointMap cmuToBoneSkeletonJointMap();

// CMU names onto the skeleton of bone meshes (skeleton_from_bone_meshes.h, OpenSim's bodies: pelvis,
// femur_l, tibia_l, talus_l, torso, humerus_l, ulna_l, hand_l, ...): the hips drive the pelvis, the upper
// spine (Spine1, the chest) the torso, which is one rigid bone from the lumbar joint up, and each limb
// segment its bone. CMU's clavicles, neck, head, fingers and toes have no bone of their own here.
JointMap cmuToMeshSkeletonJointMap();

// Whether `skeleton` is a skeleton of bone meshes (skeleton_from_bone_meshes.h): it has femur_l and femur_r.
bool isMeshSkeleton(const Skeleton& skeleton);

// Whether `skeleton` is a scan's bone skeleton (skeleton_from_bones.h): it has femur_left and femur_right.
bool isBoneSkeleton(const Skeleton& skeleton);

// The map a motion needs when none is given: the names `source` and `target` share when at least half of
// the target's joints are among them (a pose written for the same skeleton), else CMU's names onto the
// scan-bone or bone-mesh skeleton when the target is one, else CMU's onto MakeHuman's.
JointMap defaultJointMap(const Skeleton& source, const Skeleton& target);

}  // namespace vesalius::posing
