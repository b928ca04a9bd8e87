#include "vesalius/patient/virtual_patient.h"

#include "labels_with_voxels.h"

#include "vesalius/core/error.h"
#include "vesalius/core/stage_clock.h"
#include "vesalius/fat/fat_forest.h"
#include "vesalius/fat/thickness_at_vertices.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/posing/skeleton_from_bone_meshes.h"
#include "vesalius/rigging/body_rig.h"
#include "vesalius/segmentation/ct_tissues.h"
#include "vesalius/segmentation/label_ops.h"
#include "vesalius/segmentation/scan_modality.h"

#include <algorithm>
#include <functional>
#include <sstream>

namespace vesalius::patient {

namespace {

// Without an organ map: the skin and, on a CT, the scan's bone class as one bone; the sagittal plane
// through the skin's centroid across the scan's left-right axis. An MRI's dark class is no bone tissue to
// carry: T1 gives cortical bone, CSF and gas the same dark values (segmentation/mri_tissues.h), so an MRI
// without labels has the skin alone, which then aligns the reference by itself.
ReferenceAnatomy classAnatomy(const Image& scan, const LabelMap& classes, const ScanAnatomyOptions& options,
                              const std::string& scanSource) {
  ReferenceAnatomy anatomy;
  anatomy.skin = scanSkin(scan, options, scanSource, anatomy.skinCutVertices);
  // The bone class is many thin pieces, whose handles and crumbs a decimated surface would keep or lose;
  // its surface is kept as flying edges and smoothing make it.
  const segmentation::Mask bone = segmentation::maskOf(classes.labels, segmentation::kCtBone);
  if (options.modality == segmentation::Modality::Ct && segmentation::countVoxels(bone) > 0) {
    TriMesh mesh = meshing::labelSurface(classes, segmentation::kCtBone);
    mesh.faceAttributes = {};
    anatomy.tissues.push_back({"bone", TissueKind::Bone, "", false, std::move(mesh)});
  }
  anatomy.sagittal.point = anatomy.skin.V.colwise().mean().transpose();
  anatomy.sagittal.normal = (scan.geometry.direction * Eigen::Vector3d::UnitX()).normalized();
  return anatomy;
}

Eigen::VectorXd fatAtSkin(const LabelMap& classes, segmentation::Modality modality, const ReferenceAnatomy& anatomy,
                          const std::string& scanSource) {
  const segmentation::SkinAndFatLabels labels = segmentation::skinAndFatLabels(modality);
  const fat::FatForest forest(segmentation::maskOf(classes.labels, labels.skin),
                              segmentation::maskOf(classes.labels, labels.subcutaneousFat), {}, scanSource);
  Eigen::VectorXd thickness = fat::thicknessAtVertices(forest, anatomy.skin.V, anatomy.skin.F).thickness;
  for (const int v : anatomy.skinCutVertices) thickness[v] = 0;
  return thickness;
}

// Before any work: the organ map on the scan's grid, and at least one of its labels with voxels named as
// the model knows organs and bones (a template's organ, or a bone or muscle name of classifyTissue).
void checkOrganMap(const Image& scan, const LabelMap& organs, const std::vector<OrganTemplate>& templates,
                   const std::string& scanSource, const std::string& organsSource) {
  const GridGeometry &a = organs.labels.geometry, &b = scan.geometry;
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

// The bone labels the rig is meshed with: one per joint of the whole model's skeleton, or without the model
// the organ map's hips, sacrum and femurs and its lumbar vertebrae upward from the sacrum (as
// posing::skeletonFromBones chains them).
std::size_t rigBones(const LabelMap* organs, const VirtualPatientOptions& options, bool withReference) {
  if (withReference) return posing::meshSkeletonJoints().size();
  const posing::SkeletonFromBonesOptions& bones = options.rigging.bones;
  const LabelsWithVoxels present(*organs);
  std::size_t count = 5;
  for (const std::string& vertebra : bones.spine) {
    if (!present.idOf(vertebra)) break;
    ++count;
  }
  return count;
}

// The templates fitted: those whose organ has voxels in the organ map (the scan's anatomy has a tissue
// for every label with voxels).
std::vector<const OrganTemplate*> templatesToFit(const LabelMap* organs, const std::vector<OrganTemplate>& templates) {
  std::vector<const OrganTemplate*> fitted;
  if (!organs) return fitted;
  const LabelsWithVoxels present(*organs);
  for (const OrganTemplate& t : templates)
    if (present.idOf(t.organ)) fitted.push_back(&t);
  return fitted;
}

// Each stage begun on the progress under its name and timed under it (VirtualPatient::stageSeconds).
class Stages {
 public:
  Stages(std::vector<std::pair<std::string, double>>& seconds, Progress* progress) : clock_(seconds), progress_(progress) {}
  void begin(const std::string& name, const std::string& comment) {
    if (progress_) progress_->begin(name, comment);
  }
  void end(const std::string& name) {
    if (progress_) progress_->end();
    clock_.end(name);
  }

 private:
  StageClock clock_;
  Progress* progress_;
};

}  // namespace

std::vector<std::pair<std::string, double>> virtualPatientStages(const LabelMap* organs,
                                                                 const std::vector<OrganTemplate>& templates,
                                                                 const VirtualPatientOptions& options, bool withReference) {
  // Seconds on the shipped CT with its labels (docs/benchmarks.md, the virtual patient); an organ fit at
  // the mean of the four templates'.
  std::vector<std::pair<std::string, double>> stages{{"segmentation", 3}, {"anatomy from labels", 10}, {"fat forests", 3}};
  const std::vector<const OrganTemplate*> fitted = templatesToFit(organs, templates);
  for (const OrganTemplate* t : fitted) stages.emplace_back("fit " + t->organ, 35);
  if (fitted.size() > 1) stages.emplace_back("organ separation", 5);
  if (!fitted.empty()) stages.emplace_back("organs off labels", 13);
  if (withReference)
    stages.insert(stages.end(), {{"reference completion", 45}, {"whole model", 15}, {"anatomy rules", 3}});
  if (noRigBecause(organs, options, withReference).empty()) stages.emplace_back("rig", 16);
  return stages;
}

void checkVirtualPatientInputs(const Image& scan, const LabelMap* organs, const std::vector<OrganTemplate>& templates,
                               const VirtualPatientOptions& options, bool withReference, bool posed,
                               const std::string& scanSource, const std::string& organsSource) {
  // Segmentation's first test, without its work (segmentation/ct_tissues.h, mri_tissues.h).
  if (options.surfaces.modality == segmentation::Modality::Ct) {
    const float bodyMinHu = segmentation::CtTissueOptions{}.bodyMinHu;
    if (std::none_of(scan.values.begin(), scan.values.end(), [&](float v) { return v >= bodyMinHu; })) {
      std::ostringstream problem;
      problem << "CT has no body: no voxel at or above " << bodyMinHu << " HU";
      throw BadInput(scanSource, problem.str());
    }
  } else if (std::adjacent_find(scan.values.begin(), scan.values.end(), std::not_equal_to<float>()) ==
             scan.values.end()) {
    throw BadInput(scanSource, "MRI has no body: every voxel has the same value");
  }
  if (organs) checkOrganMap(scan, *organs, templates, scanSource, organsSource);
  const std::string noRig = noRigBecause(organs, options, withReference);
  if (noRig.empty())
    rigging::checkRigTargetTets(withReference ? options.rigging.modelRig.targetTets : options.rigging.rig.targetTets,
                                rigBones(organs, options, withReference), withReference);
  if (posed && !noRig.empty()) throw BadInput(organs ? organsSource : scanSource, "cannot pose the patient: " + noRig);
}

VirtualPatient buildVirtualPatient(const Image& scan, const LabelMap* organs, const std::vector<OrganTemplate>& templates,
                                   const VirtualPatientOptions& options, const std::string& scanSource,
                                   const std::string& organsSource, Progress* progress) {
  checkVirtualPatientInputs(scan, organs, templates, options, options.fullBodyReference != nullptr, false, scanSource,
                            organsSource);
  VirtualPatient patient;
  Stages stages(patient.stageSeconds, progress);
  stages.begin("segmentation", "skin, fat, bone and soft tissue classes");
  try {
    patient.tissueClasses = segmentation::segmentTissues(scan, options.surfaces.modality, 2.0, progress);
  } catch (const BadInput& e) {
    if (!e.file().empty()) throw;
    throw BadInput(scanSource, e.problem());
  }
  stages.end("segmentation");

  stages.begin("anatomy from labels", organs ? "the skin and a surface per label"
                                      : options.surfaces.modality == segmentation::Modality::Ct ? "the skin and the bone class"
                                                                                                : "the skin");
  if (organs) {
    patient.anatomy = scanAnatomy(scan, *organs, options.surfaces, scanSource, organsSource, progress);
    if (patient.anatomy.tissues.empty()) throw BadInput(organsSource, "no label of its table has voxels");
    std::vector<TriMesh*> surfaces;
    for (ReferenceTissue& t : patient.anatomy.tissues) surfaces.push_back(&t.mesh);
    patient.labelsApart = meshing::moveLabelSurfacesApart(surfaces, &organs->labels.geometry, options.labelsApart);
  } else {
    patient.anatomy = classAnatomy(scan, patient.tissueClasses, options.surfaces, scanSource);
  }
  patient.anatomy.name = "patient (" + scanSource + ")";
  stages.end("anatomy from labels");

  stages.begin("fat forests", "subcutaneous fat thickness at the skin");
  patient.fatThickness = fatAtSkin(patient.tissueClasses, options.surfaces.modality, patient.anatomy, scanSource);
  stages.end("fat forests");

  // Each tissue represents its own label; the fits below replace a label's surface by a fitted template.
  for (const ReferenceTissue& tissue : patient.anatomy.tissues) patient.labelTissues[tissue.name] = {tissue.name};
  for (const OrganTemplate* t : templatesToFit(organs, templates)) {
    stages.begin("fit " + t->organ, "the template fitted to the label by plastic strains");
    FittedOrgan fitted{t->organ, t->source,
                       fitOrganToLabel(t->surface, *organs, organs->table.resolve(t->organ), options.organFit,
                                       organsSource, progress)};
    patient.fits.push_back(std::move(fitted));
    stages.end("fit " + t->organ);
  }
  if (patient.fits.size() > 1) {
    stages.begin("organ separation", "fitted organs that touch pushed apart");
    std::vector<OrganFit*> fitted;
    for (FittedOrgan& f : patient.fits) fitted.push_back(&f.fit);
    patient.organSeparation = separateOrgans(fitted, options.organSeparation);
    stages.end("organ separation");
  }
  for (const FittedOrgan& f : patient.fits)
    for (ReferenceTissue& r : patient.anatomy.tissues)
      if (r.name == f.organ) r.mesh = f.fit.surface;
  if (!patient.fits.empty()) {
    stages.begin("organs off labels", "fitted organs bent out of the other labels' tissues");
    std::vector<std::string> names;
    std::vector<OrganFit*> fitted;
    for (FittedOrgan& f : patient.fits) names.push_back(f.organ), fitted.push_back(&f.fit);
    patient.organsOffLabels =
        bendOrgansOffLabels(patient.anatomy, names, fitted, organs->labels.geometry, options.organsOffLabels);
    stages.end("organs off labels");
  }
  patient.anatomy.validate(scanSource);

  if (options.fullBodyReference) {
    stages.begin("reference completion", "the full-body reference completed into the patient beyond the scan");
    ReferenceCompletionOptions completion = options.completion;
    if (organs)
      completion.transfer.transfer.boneTargets =
          boneGroupTargets(*options.fullBodyReference, *organs, options.whole.groupLabels);
    patient.completion = completeWithReference(patient.anatomy, patient.fatThickness, *options.fullBodyReference,
                                               completion, progress);
    stages.end("reference completion");
    stages.begin("whole model", "the reference's bones onto the patient's labels");
    patient.whole = wholeModel(patient.completion->anatomy, patient.anatomy, organs, options.whole, organsSource);
    patient.whole->anatomy.name = "patient (" + scanSource + ") completed with " + options.fullBodyReference->name;
    stages.end("whole model");
    stages.begin("anatomy rules", "Dicko et al.'s rules on the whole model");
    const TransferIntoBody& t = patient.completion->transfer;
    transfer::AnatomyRulesOptions rules;
    rules.referenceSkinDistance = &t.referenceBody.signedDistance;
    rules.referenceSkinCavities = &t.referenceBody.cavities;
    rules.deepMm = completion.transfer.voxelSizeMm;
    patient.rules = transfer::checkAnatomyRules(*options.fullBodyReference, patient.whole->anatomy,
                                                &t.transferred.finalField, rules);
    stages.end("anatomy rules");
  }

  patient.noRigBecause = noRigBecause(organs, options, patient.whole.has_value());
  if (patient.noRigBecause.empty()) {
    stages.begin("rig", "tets, bone weights and centres of rotation");
    if (patient.whole)
      patient.rig = rigWholeModel(patient.whole->anatomy, options.rigging, scanSource + " (the whole model)", progress);
    else
      patient.rig = rigPatient(patient.tissueClasses, *organs, patient.anatomy, options.rigging, organsSource, progress);
    stages.end("rig");
  }
  return patient;
}

}  // namespace vesalius::patient
