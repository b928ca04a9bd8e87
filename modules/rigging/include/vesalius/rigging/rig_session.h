// A rig folder made ready to pose, and a motion retargeted onto its skeleton: what `vesalius pose`, `vesalius
// patient --motion` and the viewer `vesalius-poser` share, so the viewer shows what the commands write.
// The rig and its meshes are read from the folder (io/anatomy_rig_io.h) into a posing::RigPoser; a BVH
// motion is retargeted once (posing/retarget.h) by a joint map, the default one (posing/joint_map.h) or
// the user's file.
#pragma once

#include "vesalius/core/skeleton.h"
#include "vesalius/posing/joint_map.h"
#include "vesalius/posing/retarget.h"
#include "vesalius/posing/rig_poser.h"

#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace vesalius::rigging {

// The joint map from `source` (a motion's skeleton) to the rig's: the file `mapPath` if not empty, else
// posing::defaultJointMap. Throws BadInput naming the file for a bad map.
posing::JointMap motionJointMap(const std::string& mapPath, const Skeleton& source, const Skeleton& rig);

// A motion retargeted onto a rig's skeleton. The motion is +Y up (BVH, CMU, MakeHuman) unless motionLps
// (a skeleton.bvh written by vesalius, mm LPS). mapPath: a joint map file, or empty for the default map.
// Throws BadInput for a bad joint map or a motion the map cannot drive.
class RetargetedMotion {
 public:
  RetargetedMotion(Motion motion, const std::string& mapPath, bool motionLps, const Skeleton& rig);

  int frameCount() const { return motion_.frameCount(); }
  // Posed world transforms of the rig's joints at `frame` (0 <= frame < frameCount()).
  std::vector<Eigen::Isometry3d> pose(int frame) const;

 private:
  Motion motion_;
  posing::Retargeter retargeter_;
};

// The rig folder `dir` (io/anatomy_rig_io.h) and its meshes, embedded in its tets (posing/rig_poser.h).
posing::RigPoser readRigPoser(const std::string& dir, bool untangle = true, bool restoreVolume = true);

}  // namespace vesalius::rigging
