#include "vesalius/patient/patient_rig.h"

#include "vesalius/core/error.h"
#include "vesalius/posing/posed_volume.h"
#include "vesalius/posing/rig_poser.h"

#include <algorithm>

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

// The scan's grid grown (same spacing and axes) to hold every posed tet vertex: a flexed thigh leaves the
// field of view of a scan that ends below the hips.
GridGeometry gridHolding(const GridGeometry& scan, const MatrixX3d& posed) {
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = (scan.size - Eigen::Vector3i::Ones()).cast<double>();
  for (Eigen::Index v = 0; v < posed.rows(); ++v) {
    const Eigen::Vector3d index = scan.worldToIndex(posed.row(v).transpose());
    lo = lo.cwiseMin(index);
    hi = hi.cwiseMax(index);
  }
  const Eigen::Vector3d first = lo.array().floor(), last = hi.array().ceil();
  GridGeometry grown = scan;
  grown.origin = scan.indexToWorld(first);
  grown.size = (last - first).cast<int>() + Eigen::Vector3i::Ones();
  return grown;
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
  rig.meshes.emplace_back("skin.obj", anatomy.skin);
  for (const ReferenceTissue& t : anatomy.tissues) rig.meshes.emplace_back(t.name + ".obj", t.mesh);
  for (const auto& [name, mesh] : rig.meshes) rig.rig.meshes.push_back(name);
  rig.hipLeft = options.bones.femurLeft;
  rig.hipRight = options.bones.femurRight;
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
  poser.carry(posed.tets, posed.meshes);
  const posing::QualityMeter meter(poser.rig(), poser.meshes(), poser.embeddings());
  posed.quality = meter(posed.tets, posed.meshes);
  posed.quality.restore = repairs.restore;
  posed.quality.untangle = repairs.untangle;
  posed.quality.skinnedTetVolumeChangePct = 100 * repairs.restore.volumeChangeBefore;
  posed.tissueVerticesInsideAtRest = meter.insideAtRest();
  posing::PosedVolumeOptions grid;
  grid.outputGeometry = gridHolding(ct.geometry, posed.tets);
  posed.scan = posing::poseImage(rig.rig.tets.V, rig.rig.tets.T, posed.tets, ct, grid);
  if (organs) posed.organs = posing::poseLabels(rig.rig.tets.V, rig.rig.tets.T, posed.tets, *organs, grid);
  return posed;
}

}  // namespace vesalius::patient
