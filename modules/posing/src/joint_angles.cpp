#include "vesalius/posing/joint_angles.h"

#include "vesalius/core/error.h"

#include <charconv>
#include <cmath>
#include <set>
#include <sstream>

namespace vesalius::posing {
namespace {

double parseAngle(const std::string& text, const std::string& item) {
  double value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(value))
    throw UsageError("joint angles: '" + item + "': '" + text + "' is not a finite number of degrees");
  return value;
}

JointAngle parseItem(const std::string& item) {
  const std::size_t eq = item.find('=');
  if (eq == std::string::npos) throw UsageError("joint angles: '" + item + "' is not joint=x,y,z");
  JointAngle angle;
  angle.joint = item.substr(0, eq);
  if (angle.joint.empty()) throw UsageError("joint angles: '" + item + "' names no joint");
  std::vector<std::string> numbers(1);
  for (char c : item.substr(eq + 1)) {
    if (c == ',') numbers.emplace_back();
    else numbers.back() += c;
  }
  if (numbers.size() != 3)
    throw UsageError("joint angles: '" + item + "' needs three angles x,y,z in degrees, found " +
                     std::to_string(numbers.size()));
  for (int k = 0; k < 3; ++k) angle.degrees[k] = parseAngle(numbers[k], item);
  return angle;
}

}  // namespace

std::vector<JointAngle> parseJointAngles(const std::string& text) {
  std::string spaced = text;
  for (char& c : spaced)
    if (c == ';') c = ' ';
  std::istringstream in(spaced);
  std::vector<JointAngle> angles;
  std::set<std::string> seen;
  for (std::string item; in >> item;) {
    angles.push_back(parseItem(item));
    if (!seen.insert(angles.back().joint).second)
      throw UsageError("joint angles: joint '" + angles.back().joint + "' is given twice");
  }
  return angles;
}

std::vector<Eigen::Isometry3d> poseFromJointAngles(const Skeleton& skeleton, const std::vector<JointAngle>& angles) {
  std::vector<Eigen::Isometry3d> local(skeleton.joints.size());
  for (std::size_t j = 0; j < local.size(); ++j) local[j] = skeleton.joints[j].restLocal;
  const double kDegree = M_PI / 180.0;
  for (const JointAngle& angle : angles) {
    const int j = skeleton.find(angle.joint);
    if (j < 0) throw UsageError("joint angles: the skeleton has no joint '" + angle.joint + "'");
    local[j].linear() = local[j].linear() * (Eigen::AngleAxisd(angle.degrees.x() * kDegree, Eigen::Vector3d::UnitX()) *
                                             Eigen::AngleAxisd(angle.degrees.y() * kDegree, Eigen::Vector3d::UnitY()) *
                                             Eigen::AngleAxisd(angle.degrees.z() * kDegree, Eigen::Vector3d::UnitZ()))
                                                .toRotationMatrix();
  }
  std::vector<Eigen::Isometry3d> world = local;
  for (std::size_t j = 0; j < world.size(); ++j)
    if (skeleton.joints[j].parent >= 0) world[j] = world[skeleton.joints[j].parent] * local[j];
  return world;
}

}  // namespace vesalius::posing
