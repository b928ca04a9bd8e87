// A rigged anatomy ready to be posed frame after frame (Sujar et al. 2018, §3.4-3.5, §4): the rig (core/anatomy_rig.h)
// and its meshes at rest, embedded once in the rest tets. Each pose then costs one skinning of the tets (LBS,
// DQS, CoR or the co-rotational FEM reference), the restoration of the volume it loses or gains
// (volume_restoration.h), the local repair of the tets it inverts or flattens (untangle_tets.h; both our
// additions to Sujar et al. 2018, on unless turned off; when the repair moved vertices, the volume its moves lost is
// restored once more and what that flattened repaired) and one carrying of the embedded meshes (the bone
// meshes moved rigidly with their joints instead). `vesalius pose`,
// `vesalius patient --pose` and the viewer `vesalius-poser` all pose through it, so the viewer shows what
// the commands write.
// Deviation from §3.5: skinning and carrying run on the CPU (TBB inside the skinners), not on the GPU.
#pragma once

#include "vesalius/core/anatomy_rig.h"
#include "vesalius/core/mesh.h"
#include "vesalius/core/tet_embedding.h"
#include "vesalius/posing/untangle_tets.h"
#include "vesalius/posing/volume_restoration.h"

#include <Eigen/Geometry>

#include <optional>
#include <string>
#include <vector>

namespace vesalius::posing {

// The methods RigPoser::skinTets takes: lbs, dqs, cor or fem.
bool isSkinningMethod(const std::string& method);

class RigPoser {
 public:
  // meshes: at rest, one per rig.meshes name, in that order. restoreVolume: give each skinned pose's tets
  // back their rest volumes by a smooth displacement; untangle: then repair the inverted or flat tets (the
  // bone vertices stay in both).
  RigPoser(AnatomyRig rig, std::vector<TriMesh> meshes, bool untangle = true, bool restoreVolume = true);

  const AnatomyRig& rig() const { return rig_; }
  const std::vector<TriMesh>& meshes() const { return meshes_; }  // at rest, in rig().meshes order
  const std::vector<TetEmbedding>& embeddings() const { return embeddings_; }
  int meshIndex(const std::string& stem) const;  // of the mesh named <stem>.*, -1 if none

  // world: posed world transforms of the rig's joints. Writes the #V by 3 posed tet vertices into `tets`
  // (kept by a caller posing many frames). method: lbs, dqs, cor or fem (UsageError otherwise; BadInput
  // for cor on a rig without centres of rotation). Returns what the restoration and the repair did (all zero
  // for a step that is off). Over both rounds of repair: the volume and bad tets after the last, the largest
  // move of a round, the sums of steps, regions, freed bone vertices and seconds.
  struct Repairs {
    VolumeRestoreResult restore;
    UntangleResult untangle;
  };
  Repairs skinTets(const std::vector<Eigen::Isometry3d>& world, const std::string& method, MatrixX3d& tets) const;
  // tets: #V by 3 posed tet vertices, skinned for `world` (skinTets). Writes, per mesh, its #P by 3 posed
  // vertices into `carried`: a bone mesh (AnatomyRig::meshJoint) moved rigidly by its joint's rest-to-posed
  // map, every other mesh carried by the tets.
  void carry(const MatrixX3d& tets, const std::vector<Eigen::Isometry3d>& world, std::vector<MatrixX3d>& carried) const;

 private:
  AnatomyRig rig_;
  std::vector<TriMesh> meshes_;
  std::vector<TetEmbedding> embeddings_;
  MatrixX3d centres_;  // the rig's centres of rotation, empty if it has none
  std::optional<VolumeRestorer> restore_;  // none when the restoration is off
  std::optional<TetUntangler> untangle_;    // none when the repair is off
};

}  // namespace vesalius::posing
