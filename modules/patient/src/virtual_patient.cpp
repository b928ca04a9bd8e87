#include "vesalius/patient/virtual_patient.h"

#include "labels_with_voxels.h"

#include "vesalius/core/error.h"
#include "vesalius/core/stage_clock.h"
#include "vesalius/fat/fat_forest.h"
#include "vesalius/fat/thickness_at_vertices.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/segmentation/ct_tissues.h"
#include "vesalius/segmentation/label_ops.h"

#include <algorithm>
#include <sstream>

namespace vesalius::patient {

namespace {

// Without an organ map: the skin and the scan's bone class as one bone, the sagittal plane through the
// skin's centroid across the scan's left-right axis.
ReferenceAnatomy classAnatomy(const Image& ct, const LabelMap& classes, const ScanAnatomyOptions& options,
                              const std::string& scanSource) {
  ReferenceAnatomy anatomy;
  anatomy.skin = scanSkin(ct, options, scanSource, anatomy.skinCutVertices);
  // The bone class is many thin pieces, which decimation tears and then takes long over (tens of seconds
  // for the shipped CT at 3,000 triangles); its surface is kept as flying edges and smoothing make it.
  const segmentation::Mask bone = segmentation::maskOf(classes.labels, segmentation::kCtBone);
  if (segmentation::countVoxels(bone) > 0) {
    TriMesh mesh = meshing::labelSurface(classes, segmentation::kCtBone);
    mesh.faceAttributes = {};
    anatomy.tissues.push_back({"bone", TissueKind::Bone, "", false, std::move(mesh)});
  }
  anatomy.sagittal.point = anatomy.skin.V.colwise().mean().transpose();
  anatomy.sagittal.normal = (ct.geometry.direction * Eigen::Vector3d::UnitX()).normalized();
  return anatomy;
}

Eigen::VectorXd fatAtSkin(const LabelMap& classes, const ReferenceAnatomy& anatomy, const std::string& scanSource) {
  const fat::FatForest forest(segmentation::maskOf(classes.labels, segmentation::kCtSkin),
                              segmentation::maskOf(classes.labels, segmentation::kCtSubcutaneousFat), {}, scanSource);
  Eigen::VectorXd thickness = fat::thicknessAtVertices(forest, anatomy.skin.V, anatomy.skin.F).thickness;
  for (const int v : anatomy.skinCutVertices) thickness[v] = 0;
  return thickness;
}

// Before any work: the organ map on the scan's grid, and at least one of its labels with voxels named as
// the model knows organs and bones (a template's organ, or a bone or muscle name of classifyTissue).
void checkOrganMap(const Image& ct, const LabelMap& organs, const std::vector<OrganTemplate>& templates,
                   const std::string& scanSource, const std::string& organsSource) {
  const GridGeometry &a = organs.labels.geometry, &b = ct.geometry;
  if (a.size != b.size || (a.origin - b.origin).norm() > 1e-3 || (a.spacing - b.spacing).norm() > 1e-6 ||
      (a.direction - b.direction).norm() > 1e-6)
    throw BadInput(organsSource, "the label map's grid differs from the scan's (" + scanSource + ")");
  const LabelsWithVoxels present(organs);
  for (const LabelEntry& e : organs.table.entries) {
    if (!present.has(e.id)) continue;
    ReferenceTissue t{e.name, TissueKind::Other, "", false, {}};
    classifyTissue(t);
    const bool hasTemplate = std::any_of(templates.begin(), templates.end(), [&](const OrganTemplate& o) { return o.organ == e.name; });
    if (hasTemplate || t.kind != TissueKind::Organ) return;
  }
  throw BadInput(organsSource, "no label with voxels is named as an organ with a template or a bone or muscle "
                               "(TotalSegmentator's names, e.g. liver, hip_left); is the label table the right one?");
}

// Why the patient will have no rig, in the user's words, or empty if it will have one: the whole model
// (with the reference) is rigged from its own bones, the scan alone from the organ map's pelvis and femurs
// (the spine is optional).
std::string noRigBecause(const LabelMap* organs, const VirtualPatientOptions& options, bool withReference) {
  if (!options.rig) return "not asked for";
  if (withReference) return "";
  if (!organs) return "no organ map: the skeleton comes from its bone labels";
  const posing::SkeletonFromBonesOptions& bones = options.rigging.bones;
  const LabelsWithVoxels present(*organs);
  std::string missing;
  for (const std::string& name : {bones.hipLeft, bones.hipRight, bones.sacrum, bones.femurLeft, bones.femurRight})
    if (!present.idOf(name)) missing += " " + name;
  return missing.empty() ? "" : "the organ map has no voxels of" + missing;
}

}  // namespace

void checkVirtualPatientInputs(const Image& ct, const LabelMap* organs, const std::vector<OrganTemplate>& templates,
                               const VirtualPatientOptions& options, bool withReference, bool posed,
                               const std::string& scanSource, const std::string& organsSource) {
  // Segmentation's first test, without its work (segmentation/ct_tissues.h).
  const float bodyMinHu = segmentation::CtTissueOptions{}.bodyMinHu;
  if (std::none_of(ct.values.begin(), ct.values.end(), [&](float v) { return v >= bodyMinHu; })) {
    std::ostringstream problem;
    problem << "CT has no body: no voxel at or above " << bodyMinHu << " HU";
    throw BadInput(scanSource, problem.str());
  }
  if (organs) checkOrganMap(ct, *organs, templates, scanSource, organsSource);
  if (!posed) return;
  if (const std::string why = noRigBecause(organs, options, withReference); !why.empty())
    throw BadInput(organs ? organsSource : scanSource, "cannot pose the patient: " + why);
}

VirtualPatient buildVirtualPatient(const Image& ct, const LabelMap* organs, const std::vector<OrganTemplate>& templates,
                                   const VirtualPatientOptions& options, const std::string& scanSource,
                                   const std::string& organsSource, Progress* progress) {
  checkVirtualPatientInputs(ct, organs, templates, options, options.fullBodyReference != nullptr, false, scanSource,
                            organsSource);
  VirtualPatient patient;
  StageClock clock(patient.stageSeconds);
  try {
    patient.tissueClasses = segmentation::segmentCtTissues(ct, {}, progress);
  } catch (const BadInput& e) {
    if (!e.file().empty()) throw;
    throw BadInput(scanSource, e.problem());
  }
  clock.end("segmentation");

  if (organs) {
    patient.anatomy = scanAnatomy(ct, *organs, options.surfaces, scanSource, organsSource, progress);
    if (patient.anatomy.tissues.empty()) throw BadInput(organsSource, "no label of its table has voxels");
  } else {
    patient.anatomy = classAnatomy(ct, patient.tissueClasses, options.surfaces, scanSource);
  }
  patient.anatomy.name = "patient (" + scanSource + ")";
  clock.end("anatomy from labels");

  patient.fatThickness = fatAtSkin(patient.tissueClasses, patient.anatomy, scanSource);
  clock.end("fat forests");

  // Each tissue represents its own label; the fits below replace a label's surface by a fitted template.
  for (const ReferenceTissue& tissue : patient.anatomy.tissues) patient.labelTissues[tissue.name] = {tissue.name};
  for (const OrganTemplate& t : templates) {
    const auto tissue = std::find_if(patient.anatomy.tissues.begin(), patient.anatomy.tissues.end(),
                                     [&](const ReferenceTissue& r) { return r.name == t.organ; });
    // Only with an organ map: not in it, or without voxels, the organ has no tissue to replace.
    if (!organs || tissue == patient.anatomy.tissues.end()) continue;
    FittedOrgan fitted{t.organ, t.source,
                       fitOrganToLabel(t.surface, *organs, organs->table.resolve(t.organ), options.organFit,
                                       organsSource, progress)};
    patient.fits.push_back(std::move(fitted));
    clock.end("fit " + t.organ);
  }
  if (patient.fits.size() > 1) {
    std::vector<OrganFit*> fitted;
    for (FittedOrgan& f : patient.fits) fitted.push_back(&f.fit);
    patient.organSeparation = separateOrgans(fitted, options.organSeparation);
    clock.end("organ separation");
  }
  for (const FittedOrgan& f : patient.fits)
    for (ReferenceTissue& r : patient.anatomy.tissues)
      if (r.name == f.organ) r.mesh = f.fit.surface;
  patient.anatomy.validate(scanSource);

  if (options.fullBodyReference) {
    ReferenceCompletionOptions completion = options.completion;
    if (organs)
      completion.transfer.transfer.boneTargets =
          boneGroupTargets(*options.fullBodyReference, *organs, options.boneGroupLabels);
    patient.completion = completeWithReference(patient.anatomy, patient.fatThickness, *options.fullBodyReference,
                                               completion, progress);
    clock.end("reference completion");
    if (progress) progress->begin("whole model", "the reference's bones onto the patient's labels");
    patient.whole = wholeModel(patient.completion->anatomy, patient.anatomy, organs, options.referenceBoneLabels,
                               options.boneRefinement, organsSource);
    patient.whole->anatomy.name = "patient (" + scanSource + ") completed with " + options.fullBodyReference->name;
    if (progress) progress->end();
    clock.end("whole model");
    const TransferIntoBody& t = patient.completion->transfer;
    transfer::AnatomyRulesOptions rules;
    rules.referenceSkinDistance = &t.referenceBody.signedDistance;
    rules.referenceSkinCavities = &t.referenceBody.cavities;
    rules.deepMm = completion.transfer.voxelSizeMm;
    patient.rules = transfer::checkAnatomyRules(*options.fullBodyReference, patient.whole->anatomy,
                                                &t.transferred.finalField, rules);
    clock.end("anatomy rules");
  }

  patient.noRigBecause = noRigBecause(organs, options, patient.whole.has_value());
  if (patient.noRigBecause.empty()) {
    if (patient.whole)
      patient.rig = rigWholeModel(patient.whole->anatomy, options.rigging, scanSource + " (the whole model)", progress);
    else
      patient.rig = rigPatient(patient.tissueClasses, *organs, patient.anatomy, options.rigging, organsSource, progress);
    clock.end("rig");
  }
  return patient;
}

}  // namespace vesalius::patient
