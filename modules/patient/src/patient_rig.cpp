#include "vesalius/patient/patient_rig.h"

#include "vesalius/core/error.h"
#include "vesalius/posing/posed_volume.h"
#include "vesalius/posing/rig_poser.h"
#include "vesalius/rigging/body_rig.h"
#include "vesalius/rigging/rigid_bone_parts.h"

#include <algorithm>
#include <map>

namespace vesalius::patient {

namespace {

// The map the rig is made of: the skeleton's bone labels of `organs` where they are, a label of its own
// ("body") on every other voxel of the body (tissue classes or organs), 0 outside.
LabelMap rigLabels(const LabelMap& tissueClasses, const LabelMap& organs, const posing::SkeletonFromBonesOptions& bones) {
  std::vector<std::string> names{bones.hipLeft, bones.hipRight, bones.sacrum, bones.femurLeft, bones.femurRight};
  names.insert(names.end(), bones.spine.begin(), bones.spine.end());
  std::vector<bool> isBone(65536, false);
  LabelMap map;
  Label body = 1;
  for (const std::string& name : names)
    if (const LabelEntry* e = organs.table.find(name)) {
      isBone[e->id] = true;
      map.table.add(*e);
      body = std::max<Label>(body, Label(e->id + 1));
    }
  map.table.add({body, "body", defaultLabelColor(body)});
  map.labels = Grid<Label>(organs.labels.geometry, 0);
  for (std::size_t v = 0; v < map.labels.values.size(); ++v) {
    const Label o = organs.labels.values[v];
    if (isBone[o]) map.labels.values[v] = o;
    else if (o != 0 || tissueClasses.labels.values[v] != 0) map.labels.values[v] = body;
  }
  return map;
}

// The scan's grid grown (same spacing and axes) to hold the posed vertices of every tet with a vertex
// inside the scan at rest: a flexed thigh leaves the field of view of a scan that ends below the hips.
// The tets beyond the scan (a whole model's arms and head) carry none of it.
GridGeometry gridHolding(const GridGeometry& scan, const TetMesh& rest, const MatrixX3d& posed) {
  const Eigen::Vector3d first = Eigen::Vector3d::Constant(-0.5), last = scan.size.cast<double>().array() - 0.5;
  std::vector<char> inScan(std::size_t(rest.V.rows()));
  for (Eigen::Index v = 0; v < rest.V.rows(); ++v) {
    const Eigen::Vector3d index = scan.worldToIndex(rest.V.row(v).transpose());
    inScan[std::size_t(v)] = (index.array() >= first.array()).all() && (index.array() <= last.array()).all();
  }
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = (scan.size - Eigen::Vector3i::Ones()).cast<double>();
  for (Eigen::Index t = 0; t < rest.T.rows(); ++t) {
    if (!inScan[std::size_t(rest.T(t, 0))] && !inScan[std::size_t(rest.T(t, 1))] && !inScan[std::size_t(rest.T(t, 2))] &&
        !inScan[std::size_t(rest.T(t, 3))])
      continue;
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d index = scan.worldToIndex(posed.row(rest.T(t, k)).transpose());
      lo = lo.cwiseMin(index);
      hi = hi.cwiseMax(index);
    }
  }
  const Eigen::Vector3d from = lo.array().floor(), to = hi.array().ceil();
  GridGeometry grown = scan;
  grown.origin = scan.indexToWorld(from);
  grown.size = (to - from).cast<int>() + Eigen::Vector3i::Ones();
  return grown;
}

// The rig's meshes: the model's skin, then its tissues, named by file; the bones the rig was made of move
// rigidly with their joints.
void carry(PatientRig& rig, const ReferenceAnatomy& model, const std::map<std::string, int>& boneJoints) {
  rig.meshes.emplace_back("skin.obj", model.skin);
  for (const ReferenceTissue& t : model.tissues) rig.meshes.emplace_back(t.name + ".obj", t.mesh);
  for (const auto& [name, mesh] : rig.meshes) rig.rig.meshes.push_back(name);
  rig.rig.meshJoint = rigging::meshJoints(rig.rig.meshes, boneJoints);
}

}  // namespace

PatientRig rigPatient(const LabelMap& tissueClasses, const LabelMap& organs, const ReferenceAnatomy& anatomy,
                      const PatientRigOptions& options, const std::string& organsSource, Progress* progress) {
  if (tissueClasses.labels.geometry.size != organs.labels.geometry.size)
    throw BadInput(organsSource, "the organ map's grid differs from the tissue classes'");
  rigging::BuiltRig built =
      rigging::rigFromBoneLabels(rigLabels(tissueClasses, organs, options.bones), options.bones, options.rig, organsSource, progress);
  PatientRig rig;
  rig.rig = std::move(built.rig);
  rig.stageSeconds = std::move(built.stageSeconds);
  carry(rig, anatomy, built.boneJoints);
  rig.hipLeft = options.bones.femurLeft;
  rig.hipRight = options.bones.femurRight;
  return rig;
}

PatientRig rigWholeModel(const ReferenceAnatomy& model, const PatientRigOptions& options, const std::string& source,
                         Progress* progress) {
  rigging::BuiltRig built = rigging::rigFromReference(model, options.modelBones, options.modelRig, source, progress);
  PatientRig rig;
  rig.rig = std::move(built.rig);
  rig.stageSeconds = std::move(built.stageSeconds);
  carry(rig, model, built.boneJoints);
  rig.hipLeft = "femur_l";  // OpenSim's body names (skeleton_from_bone_meshes.h)
  rig.hipRight = "femur_r";
  return rig;
}

PosedPatient posePatient(const PatientRig& rig, const std::vector<Eigen::Isometry3d>& world, const Image& ct,
                         const LabelMap* organs, const PatientPoseOptions& options) {
  if (!posing::isSkinningMethod(options.method)) throw UsageError("skinning method must be lbs, dqs, cor or fem, not " + options.method);
  std::vector<TriMesh> meshes;
  for (const auto& [name, mesh] : rig.meshes) meshes.push_back(mesh);
  const posing::RigPoser poser(rig.rig, std::move(meshes), options.untangle, options.restoreVolume);
  PosedPatient posed;
  const posing::RigPoser::Repairs repairs = poser.skinTets(world, options.method, posed.tets);
  poser.carry(posed.tets, world, posed.meshes);
  const posing::QualityMeter meter(poser.rig(), poser.meshes(), poser.embeddings());
  posed.quality = meter(posed.tets, posed.meshes);
  posed.quality.restore = repairs.restore;
  posed.quality.untangle = repairs.untangle;
  posed.quality.skinnedTetVolumeChangePct = 100 * repairs.restore.volumeChangeBefore;
  posed.tissueVerticesInsideAtRest = meter.insideAtRest();
  posing::PosedVolumeOptions grid;
  grid.outputGeometry = gridHolding(ct.geometry, rig.rig.tets, posed.tets);
  const posing::RigidParts bones =
      rigging::rigidBoneParts(rig.rig, poser.meshes(), posed.meshes, world, ct.geometry, *grid.outputGeometry);
  grid.rigid = &bones;
  posed.scan = posing::poseImage(rig.rig.tets.V, rig.rig.tets.T, posed.tets, ct, grid);
  if (organs) posed.organs = posing::poseLabels(rig.rig.tets.V, rig.rig.tets.T, posed.tets, *organs, grid);
  return posed;
}

}  // namespace vesalius::patient
