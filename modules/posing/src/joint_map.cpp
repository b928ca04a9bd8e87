#include "vesalius/posing/joint_map.h"

#include "vesalius/core/error.h"

#include <set>
#include <sstream>

namespace vesalius::posing {

JointMap parseJointMap(std::string_view text, const std::string& source) {
  JointMap map;
  std::set<std::string> targets;
  std::istringstream in{std::string(text)};
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string where = "line " + std::to_string(number) + ": ";
    const std::size_t hash = line.find('#');
    std::istringstream fields(line.substr(0, hash));
    std::string from, to, extra;
    if (!(fields >> from)) continue;
    if (!(fields >> to)) throw BadInput(source, where + "'" + from + "' has no target joint");
    if (fields >> extra) throw BadInput(source, where + "expected two joint names, found a third ('" + extra + "')");
    if (!targets.insert(to).second) throw BadInput(source, where + "target joint '" + to + "' is mapped twice");
    map.pairs.emplace_back(from, to);
  }
  return map;
}

JointMap cmuToMakeHumanJointMap() {
  JointMap map;
  map.pairs = {
      {"Hips", "root"},
      {"LowerBack", "spine05"},
      {"Spine", "spine03"},
      {"Spine1", "spine01"},
      {"Neck", "neck01"},
      {"Neck1", "neck03"},
      {"Head", "head"},
  };
  for (const auto& [cmu, mh] : std::vector<std::pair<std::string, std::string>>{{"Left", ".L"}, {"Right", ".R"}}) {
    map.pairs.insert(map.pairs.end(), {
                                          {cmu + "UpLeg", "upperleg01" + mh},
                                          {cmu + "Leg", "lowerleg01" + mh},
                                          {cmu + "Foot", "foot" + mh},
                                          {cmu + "Shoulder", "clavicle" + mh},
                                          {cmu + "Arm", "upperarm01" + mh},
                                          {cmu + "ForeArm", "lowerarm01" + mh},
                                          {cmu + "Hand", "wrist" + mh},
                                      });
  }
  return map;
}

JointMap cmuToBoneSkeletonJointMap() {
  JointMap map;
  map.pairs = {{"Hips", "pelvis"}, {"LeftUpLeg", "femur_left"}, {"RightUpLeg", "femur_right"}, {"LowerBack", "vertebrae_L5"}};
  return map;
}

JointMap cmuToMeshSkeletonJointMap() {
  JointMap map;
  map.pairs = {{"Hips", "pelvis"}, {"Spine1", "torso"}};
  for (const auto& [cmu, side] : std::vector<std::pair<std::string, std::string>>{{"Left", "_l"}, {"Right", "_r"}})
    map.pairs.insert(map.pairs.end(), {{cmu + "UpLeg", "femur" + side},
                                       {cmu + "Leg", "tibia" + side},
                                       {cmu + "Foot", "talus" + side},
                                       {cmu + "Arm", "humerus" + side},
                                       {cmu + "ForeArm", "ulna" + side},
                                       {cmu + "Hand", "hand" + side}});
  return map;
}

bool isMeshSkeleton(const Skeleton& skeleton) { return skeleton.find("femur_l") >= 0 && skeleton.find("femur_r") >= 0; }

bool isBoneSkeleton(const Skeleton& skeleton) {
  return skeleton.find("femur_left") >= 0 && skeleton.find("femur_right") >= 0;
}

JointMap defaultJointMap(const Skeleton& source, const Skeleton& target) {
  JointMap shared;
  for (const Joint& joint : target.joints)
    if (source.find(joint.name) >= 0) shared.pairs.emplace_back(joint.name, joint.name);
  if (shared.pairs.size() * 2 >= target.joints.size()) return shared;
  if (isBoneSkeleton(target)) return cmuToBoneSkeletonJointMap();
  if (isMeshSkeleton(target)) return cmuToMeshSkeletonJointMap();
  return cmuToMakeHumanJointMap();
}

}  // namespace vesalius::posing
