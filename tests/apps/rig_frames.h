// frames.txt of an anatomy directory (io/anatomy_rig_io.h): per joint name, its rest world
// rotation row by row; for the rig and pose integration tests.
#pragma once

#include <Eigen/Core>

#include <fstream>
#include <map>
#include <sstream>
#include <string>

namespace vesalius::test {

inline std::map<std::string, Eigen::Matrix3d> readRigFrames(const std::string& path) {
  std::map<std::string, Eigen::Matrix3d> frames;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string name;
    Eigen::Matrix3d R;
    fields >> name;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) fields >> R(r, c);
    if (fields) frames[name] = R;
  }
  return frames;
}

}  // namespace vesalius::test
