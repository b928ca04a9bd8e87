// Shared by the body frame and skeleton placement tests: MakeHuman's neutral skin and default rig in LPS
// mm, and a generalized winding number for "is this point inside the skin".
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/core/skeleton.h"
#include "vesalius/io/body_axes.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/skeleton_io.h"
#include "vesalius/meshing/winding_number.h"
#include "vesalius/transfer/body_frame.h"
#include "vesalius/transfer/skeleton_placement.h"

#include <map>
#include <string>

namespace vesalius::test {

struct MakeHumanBody {
  TriMesh skin;  // testdata/body/shapes/mh_neutral_body.obj, the 'body' group of base.obj
  Skeleton rig;  // default.mhskel
  std::map<std::string, Eigen::Vector3d> joints;
  transfer::LegJoints legs;
};

inline const MakeHumanBody& makeHumanBody() {
  static const MakeHumanBody body = [] {
    const std::string dir = std::string(VESALIUS_TESTDATA) + "/body/";
    MakeHumanBody b;
    b.skin = io::readTriMesh(dir + "shapes/mh_neutral_body.obj");
    b.skin.V = io::transformPoints(b.skin.V, io::yUpToLps(), 100.0);
    const Skeleton rig = io::readMakeHumanSkeleton(dir + "default.mhskel", io::readTriMesh(dir + "base.obj").V);
    b.rig = io::transformSkeleton(rig, io::yUpToLps(), 100.0);
    b.joints = transfer::jointPositions(b.rig);
    b.legs = {b.joints.at("upperleg01.L"), b.joints.at("foot.L"), b.joints.at("upperleg01.R"), b.joints.at("foot.R")};
    return b;
  }();
  return body;
}

// Generalized winding number of the closed-ish surface (V, F) at each row of P, summed exactly
// (meshing/winding_number.h): about 1 inside, 0 outside, robust to small holes.
inline Eigen::VectorXd windingNumbers(const MatrixX3d& V, const MatrixX3i& F, const MatrixX3d& P) {
  return meshing::windingNumbers(V, F, P, meshing::WindingNumberOptions{0.0});
}

}  // namespace vesalius::test
