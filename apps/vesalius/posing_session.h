// Posing an anatomy rig folder from the command line and the viewer: the rig and its meshes read into a
// posing::RigPoser, and a BVH motion retargeted once onto the rig's skeleton. `vesalius pose` and the
// viewer `vesalius-poser` both pose through them, so the viewer shows what the command writes.
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/core/skeleton.h"
#include "vesalius/posing/joint_map.h"
#include "vesalius/posing/retarget.h"
#include "vesalius/posing/rig_poser.h"

#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace vesalius::cli {

// The joint map from `source` (a motion's skeleton) to the rig's: the file `mapPath` if not empty, else
// posing::defaultJointMap.
posing::JointMap motionJointMap(const std::string& mapPath, const Skeleton& source, const Skeleton& rig);

// A BVH motion retargeted onto a rig's skeleton. The motion is +Y up (BVH, CMU, MakeHuman) unless
// motionLps (a skeleton.bvh written by vesalius, mm LPS). Throws BadInput for a bad BVH or joint map.
class RetargetedMotion {
 public:
  RetargetedMotion(const std::string& bvhPath, const std::string& mapPath, bool motionLps, const Skeleton& rig);
  RetargetedMotion(Motion motion, const std::string& mapPath, bool motionLps, const Skeleton& rig);

  int frameCount() const { return motion_.frameCount(); }
  // Posed world transforms of the rig's joints at `frame` (0 <= frame < frameCount()).
  std::vector<Eigen::Isometry3d> pose(int frame) const;

 private:
  Motion motion_;
  posing::Retargeter retargeter_;
};

// A BVH file read for a command: a miscounted frame list is read as io::readBvh tolerates it, with its
// warning on stderr.
Motion readMotion(const std::string& bvhPath);

// The rig folder `dir` (io/anatomy_rig_io.h) and its meshes, embedded in its tets (posing/rig_poser.h).
posing::RigPoser readRigPoser(const std::string& dir, bool untangle = true, bool restoreVolume = true);

}  // namespace vesalius::cli
