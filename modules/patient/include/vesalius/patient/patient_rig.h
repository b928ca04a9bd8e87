// The virtual patient made posable (Sujar et al. 2018): the rig of the patient's model, and the patient posed with it.
//
// Two rigs (rigging/body_rig.h), both with bone weights and CoR centres of rotation:
//  - rigWholeModel: the rig of the whole model (whole_model.h), as `rig --reference` makes it: the
//    skeleton from the model's own bone meshes (posing/skeleton_from_bone_meshes.h: pelvis, legs, torso,
//    arms; OpenSim's body names), the tets of the inside of the model's skin, the bones nested in it.
//    Inside the scan the hip bones and femurs are the patient's (placed on the labels), so the hips turn
//    about the patient's own hip centres.
//  - rigPatient: without the whole model, the rig of the scan's body inside its field of view from the
//    bones of the organ map (posing/skeleton_from_bones.h: pelvis from the hips and sacrum, the femurs, the
//    lumbar vertebrae), every voxel of the CT's tissue classes or of the organ map.
// A pose (posing/rig_poser.h) skins the tets, restores their volume, repairs the tets it inverts, carries
// the meshes, and re-poses the scan and its organ map with the tets (posing/posed_volume.h, Sujar et al. 2018, §5).
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/anatomy_rig.h"
#include "vesalius/core/grid.h"
#include "vesalius/core/label_map.h"
#include "vesalius/core/progress.h"
#include "vesalius/posing/pose_quality.h"
#include "vesalius/posing/skeleton_from_bones.h"
#include "vesalius/rigging/body_rig.h"

#include <Eigen/Geometry>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace vesalius::patient {

struct PatientRigOptions {
  // The whole model's rig: 8 mm voxels keep the hands' bones (at 10 mm some have none) and make the
  // shipped CT's model about 23,000 tets in about 13 s (docs/virtual-patient.md).
  rigging::RigOptions modelRig = defaultModelRig();
  posing::SkeletonFromBoneMeshesOptions modelBones;

  // The scan's rig without the whole model: the whole body, not the bones' box; about 20,000 tets at 6 mm
  // voxels, the shipped CT's rig in about 5 s. Finer voxels keep the thin tissue where the scan cuts the
  // thighs, a voxel or two below the hip joints, whose tets a flexed hip inverts and the repair then
  // inflates: both hips flexed 30 degrees change the skin's volume by 2.0 % at 4 mm and 20,000 tets, 0.7 %
  // at 6 mm (docs/virtual-patient.md).
  rigging::RigOptions rig = defaultRig();
  posing::SkeletonFromBonesOptions bones;

  static rigging::RigOptions defaultModelRig() {
    rigging::RigOptions o;
    o.voxelSize = 8.0;
    o.targetTets = 20000;
    return o;
  }
  static rigging::RigOptions defaultRig() {
    rigging::RigOptions o;
    o.voxelSize = 6.0;
    o.targetTets = 20000;
    o.margin = 1e6;
    return o;
  }
};

struct PatientRig {
  AnatomyRig rig;  // its meshes named as `meshes`
  // What the rig carries, at rest: "skin.obj" (the anatomy's skin), then "<tissue>.obj" per tissue.
  std::vector<std::pair<std::string, TriMesh>> meshes;
  std::string hipLeft, hipRight;  // the joints that turn the left and right hips
  std::vector<std::pair<std::string, double>> stageSeconds;
};

// model: the whole model (a closed skin, OpenSim's bone meshes among its tissues), mm LPS; the rig carries
// it. Throws what rigging::rigFromReference throws, naming `source`.
PatientRig rigWholeModel(const ReferenceAnatomy& model, const PatientRigOptions& options, const std::string& source,
                         Progress* progress = nullptr);

// tissueClasses: the CT's tissue classes (segmentation/ct_tissues.h, 0 outside the body); organs: its
// organ/bone map on the same grid; anatomy: the model to carry. Throws BadInput naming
// `organsSource` when the map lacks the bones the skeleton needs (posing/skeleton_from_bones.h).
PatientRig rigPatient(const LabelMap& tissueClasses, const LabelMap& organs, const ReferenceAnatomy& anatomy,
                      const PatientRigOptions& options, const std::string& organsSource, Progress* progress = nullptr);

struct PatientPoseOptions {
  std::string method = "cor";  // lbs, dqs, cor or fem (posing/rig_poser.h)
  bool restoreVolume = true, untangle = true;
};

struct PosedPatient {
  MatrixX3d tets;                      // #V by 3 posed rig vertices
  std::vector<MatrixX3d> meshes;       // per rig mesh, its #P by 3 posed vertices
  // The CT and the organ map (when given) re-posed, on the scan's grid grown to hold the posed body.
  Image scan;
  std::optional<LabelMap> organs;
  posing::PoseQuality quality;
  long tissueVerticesInsideAtRest = 0;
};

// world: posed world transforms of rig.rig.skeleton's joints. The scan is re-posed by the tets that hold
// it at rest: its grid grows to hold them posed, whatever else of the model the rig carries. Throws
// UsageError for an unknown method.
PosedPatient posePatient(const PatientRig& rig, const std::vector<Eigen::Isometry3d>& world, const Image& ct,
                         const LabelMap* organs, const PatientPoseOptions& options = {});

}  // namespace vesalius::patient
