// Shared by the motion tests: the CMU motion of testdata and MakeHuman's default skeleton in LPS mm.
#pragma once

#include "vesalius/core/skeleton.h"
#include "vesalius/io/body_axes.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/motion_io.h"
#include "vesalius/io/skeleton_io.h"

#include <string>

namespace vesalius::test {

inline const Motion& cmuMotion() {
  static const Motion motion = io::readBvh(std::string(VESALIUS_TESTDATA) + "/motion/01_01.bvh");
  return motion;
}

// default.mhskel on base.obj, converted from decimetres, +Y up to millimetres, LPS.
inline const Skeleton& makeHumanSkeletonLps() {
  static const Skeleton skeleton = [] {
    const std::string body = std::string(VESALIUS_TESTDATA) + "/body/";
    const Skeleton mh = io::readMakeHumanSkeleton(body + "default.mhskel", io::readTriMesh(body + "base.obj").V);
    return io::transformSkeleton(mh, io::yUpToLps(), 100.0);
  }();
  return skeleton;
}

inline double rotationDegrees(const Eigen::Matrix3d& r) {
  return Eigen::AngleAxisd(r).angle() * 180.0 / M_PI;
}

}  // namespace vesalius::test
