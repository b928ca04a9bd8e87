#include "vesalius/rigging/rig_session.h"

#include "vesalius/io/anatomy_rig_io.h"
#include "vesalius/io/body_axes.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/text_file.h"

namespace vesalius::rigging {

namespace {

// A foreign motion (+Y up) starts where the rig stands: its first frame is the stance. Our own
// skeleton.bvh (mm LPS) already holds the rig's positions and is replayed as written. A scan's bone
// skeleton (skeleton_from_bones.h) stands in the anatomical position, its legs down as in a motion
// capture's rest, so its bones are not turned to the motion's rest directions: theirs come from bones the
// scan cuts short (a femur cut below its neck points along the neck, 60 degrees off the leg), which the
// alignment would turn into the leg's direction.
posing::RetargetOptions retargetOptions(bool motionLps, const Motion& motion, const Skeleton& rig) {
  posing::RetargetOptions options;
  if (motionLps) return options;
  options.sourceAxes = io::yUpToLps();
  if (motion.frameCount() > 0) options.sourceStance = motion.worldPose(0);
  options.alignRestDirections = !posing::isBoneSkeleton(rig);
  return options;
}

}  // namespace

posing::JointMap motionJointMap(const std::string& mapPath, const Skeleton& source, const Skeleton& rig) {
  if (!mapPath.empty()) return posing::parseJointMap(io::readTextFile(mapPath), mapPath);
  return posing::defaultJointMap(source, rig);
}

RetargetedMotion::RetargetedMotion(Motion motion, const std::string& mapPath, bool motionLps, const Skeleton& rig)
    : motion_(std::move(motion)),
      retargeter_(motion_.skeleton, rig, motionJointMap(mapPath, motion_.skeleton, rig), retargetOptions(motionLps, motion_, rig),
                  mapPath.empty() ? "default joint map" : mapPath) {}

std::vector<Eigen::Isometry3d> RetargetedMotion::pose(int frame) const {
  return retargeter_.pose(motion_.worldPose(frame));
}

posing::RigPoser readRigPoser(const std::string& dir, bool untangle, bool restoreVolume) {
  AnatomyRig rig = io::readAnatomyRig(dir);
  std::vector<TriMesh> meshes;
  for (const std::string& path : rig.meshes) meshes.push_back(io::readTriMesh(path));
  return posing::RigPoser(std::move(rig), std::move(meshes), untangle, restoreVolume);
}

}  // namespace vesalius::rigging
