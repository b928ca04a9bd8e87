// What posing must not break (Sujar et al.'s claims, measured per pose): inverted or flat tets, posed/rest tet
// volumes, the skin's volume change, and the tissue vertices that leave their tet.
#pragma once

#include "vesalius/core/anatomy_rig.h"
#include "vesalius/core/mesh.h"
#include "vesalius/core/tet_embedding.h"
#include "vesalius/posing/untangle_tets.h"
#include "vesalius/posing/volume_restoration.h"

#include <Eigen/Core>

#include <limits>
#include <vector>

namespace vesalius::posing {

struct PoseQuality {
  long inverted = 0;             // posed tets with signed volume <= 0 (inverted or flat)
  double minVolumeRatio = 0;     // smallest posed / rest tet volume
  double skinVolumeChangePct = std::numeric_limits<double>::quiet_NaN();  // posed / rest skin volume - 1, %
  double tetVolumeChangePct = 0;  // posed / rest volume of the whole tet mesh - 1, %
  double skinnedTetVolumeChangePct = 0;  // the same as skinned, before the restoration and the repair
  long leftOutside = 0;          // tissue vertices inside the rest tets that are not inside their posed tet
  // Bone meshes moved rigidly (AnatomyRig::meshJoint): how far their vertices inside the rest tets are from
  // where the tets would have carried them, mm; the tissue next to a bone is carried by the tets.
  double boneMeshGapMax = 0, boneMeshGapMean = 0;
  VolumeRestoreResult restore;   // the restoration before these were measured (zeros if off)
  UntangleResult untangle;       // the repair after it (zeros if off)
};

// Measures PoseQuality against the rest rig, whose tet volumes, skin volume (the mesh named "skin") and
// inside vertices it keeps. A vertex is inside when its rest barycentric weights are all >= -1e-9
// (TetLocator::locate's tolerance); it has left when its posed position, re-expressed in its posed tet, has
// a weight below -1e-9 or none (a flat tet). The carrying (TetEmbedding::apply) keeps the weights under any
// invertible tet map, inverted ones included, so this checks the carried meshes end to end and catches
// flat tets. Bone meshes moved rigidly are not carried: their distance from the tets' carrying is measured
// instead.
class QualityMeter {
 public:
  static constexpr double kTolerance = 1e-9;

  // meshes and embeddings: at rest, in rig.meshes order (RigPoser's); kept by reference.
  QualityMeter(const AnatomyRig& rig, const std::vector<TriMesh>& meshes, const std::vector<TetEmbedding>& embeddings);

  long insideAtRest() const { return inside_; }  // tissue vertices inside the rest tets, over the carried meshes

  // posedTets: #V by 3 posed tet vertices; carried: per mesh, its #P by 3 posed vertices. The restoration
  // and repair fields are left zero for the caller.
  PoseQuality operator()(const MatrixX3d& posedTets, const std::vector<MatrixX3d>& carried) const;

 private:
  MatrixX4i T_;
  Eigen::VectorXd restVolumes_;
  const std::vector<TetEmbedding>& embeddings_;
  std::vector<bool> rigid_;  // per mesh: a bone mesh moved rigidly
  int skin_ = -1;
  MatrixX3i skinF_;
  double restSkinVolume_ = 0;
  long inside_ = 0;
};

}  // namespace vesalius::posing
