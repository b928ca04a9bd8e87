#include "tissue_colour.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <numeric>
#include <regex>

namespace vesalius::poser {

namespace {

const Eigen::Vector3d kBone(0.92, 0.90, 0.80), kMuscle(0.72, 0.22, 0.20);
const std::array<Eigen::Vector3d, 6> kOrgans{{{0.55, 0.25, 0.45}, {0.80, 0.55, 0.25}, {0.35, 0.55, 0.35},
                                             {0.30, 0.45, 0.70}, {0.75, 0.70, 0.30}, {0.60, 0.35, 0.25}}};

}  // namespace

Eigen::Vector3d tissueColour(const std::string& stem) {
  std::string name = stem;
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
  const auto has = [&name](const char* pattern) { return std::regex_search(name, std::regex(pattern)); };
  if (has("bone|skeleton|skull|vertebra|sacrum|rib|sternum|costal|femur|humerus|scapula|clavicula|tibia|fibula|"
          "patella|radius|ulna|^hip_"))
    return kBone;
  if (has("muscle|gluteus|iliopsoas|autochthon")) return kMuscle;
  return kOrgans[std::accumulate(name.begin(), name.end(), std::size_t(0),
                                 [](std::size_t sum, unsigned char c) { return 31 * sum + c; }) %
                 kOrgans.size()];
}

}  // namespace vesalius::poser
