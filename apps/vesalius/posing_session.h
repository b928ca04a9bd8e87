// A rigged anatomy ready to be posed frame after frame (seed 001 §3.4-3.5, §4): the rig of an anatomy
// directory (anatomy_rig.h), its meshes at rest embedded once in the rest tets, and a BVH motion
// retargeted once onto its skeleton. Each frame then costs one skinning of the tets (LBS, DQS, CoR or the
// co-rotational FEM reference), the restoration of the volume it loses or gains (posing/volume_restoration.h),
// the local repair of the tets it inverts or flattens (posing/untangle_tets.h; both our additions to the seed,
// on unless turned off) and one carrying of the embedded meshes. `vesalius pose` and the viewer
// `vesalius-poser` both pose through it, so the viewer shows what the command writes.
// Deviation from §3.5: skinning and carrying run on the CPU (TBB inside the skinners), not on the GPU.
#pragma once

#include "anatomy_rig.h"

#include "vesalius/core/mesh.h"
#include "vesalius/core/skeleton.h"
#include "vesalius/core/tet_embedding.h"
#include "vesalius/posing/joint_map.h"
#include "vesalius/posing/retarget.h"
#include "vesalius/posing/untangle_tets.h"
#include "vesalius/posing/volume_restoration.h"

#include <Eigen/Geometry>

#include <optional>
#include <string>
#include <vector>

namespace vesalius::cli {

// The joint map from `source` (a motion's skeleton) to the rig's: the file `mapPath` if not empty, else the
// names shared with the rig's skeleton (a MakeHuman BVH pose) when at least half of the rig's joints are
// among them, else the CMU defaults (posing/joint_map.h).
posing::JointMap motionJointMap(const std::string& mapPath, const Skeleton& source, const Skeleton& rig);

// A BVH motion retargeted onto a rig's skeleton. The motion is +Y up (BVH, CMU, MakeHuman) unless
// motionLps (a skeleton.bvh written by vesalius, mm LPS). Throws BadInput for a bad BVH or joint map.
class RetargetedMotion {
 public:
  RetargetedMotion(const std::string& bvhPath, const std::string& mapPath, bool motionLps, const Skeleton& rig);

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

// The methods PosingSession::skinTets takes.
bool isSkinningMethod(const std::string& method);  // lbs, dqs, cor or fem

class PosingSession {
 public:
  // Reads the anatomy directory and its meshes and embeds the meshes in the rest tets. restoreVolume: give
  // each skinned pose's tets back their rest volumes by a smooth displacement; untangle: then repair the
  // inverted or flat tets (the bone vertices stay in both).
  explicit PosingSession(const std::string& anatomyDir, bool untangle = true, bool restoreVolume = true);

  const AnatomyRig& rig() const { return rig_; }
  const std::vector<TriMesh>& meshes() const { return meshes_; }  // at rest, in rig().meshes order
  const std::vector<TetEmbedding>& embeddings() const { return embeddings_; }
  int meshIndex(const std::string& stem) const;  // of DIR/meshes/<stem>.*, -1 if none

  // world: posed world transforms of the rig's joints. Writes the #V by 3 posed tet vertices into `tets`
  // (kept by a caller posing many frames). method: lbs, dqs, cor or fem (UsageError otherwise; BadInput
  // for cor on a rig without centres of rotation). Returns what the restoration and the repair did (all zero
  // for a step that is off).
  struct Repairs {
    posing::VolumeRestoreResult restore;
    posing::UntangleResult untangle;
  };
  Repairs skinTets(const std::vector<Eigen::Isometry3d>& world, const std::string& method, MatrixX3d& tets) const;
  // tets: #V by 3 posed tet vertices. Writes, per mesh, its #P by 3 carried vertices into `carried`.
  void carry(const MatrixX3d& tets, std::vector<MatrixX3d>& carried) const;

 private:
  AnatomyRig rig_;
  std::vector<TriMesh> meshes_;
  std::vector<TetEmbedding> embeddings_;
  MatrixX3d centres_;  // the rig's centres of rotation, empty if it has none
  std::optional<posing::VolumeRestorer> restore_;  // none when the restoration is off
  std::optional<posing::TetUntangler> untangle_;    // none when the repair is off
};

}  // namespace vesalius::cli
