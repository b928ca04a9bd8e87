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

}  // namespace vesalius::posing
