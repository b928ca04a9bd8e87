// The virtual patient: one patient's CT or MRI in, that patient's anatomy out, by the papers' methods in
// their order (docs/virtual-patient.md). buildVirtualPatient runs, on core types:
//  1. segmentation: the scan's tissue classes (segmentation/ct_tissues.h, or mri_tissues.h for an MRI); the
//     skin is the body's outer surface, its vertices where the field of view cut the body marked as cut
//     (scan_anatomy.h).
//  2. fat: the subcutaneous fat thickness at every skin vertex from the shortest-path fat forests of the
//     scan's skin and subcutaneous fat classes (Dicko et al. 2013, §5; fat/fat_forest.h, fat/thickness_at_vertices.h);
//     0 on the cut, which is not skin.
//  3. the anatomy inside the field of view: with an organ/bone label map, each label as a closed tissue
//     surface of its kind (scan_anatomy.h), the surfaces moved apart where they cross
//     (meshing/label_surfaces_apart.h), and each organ with a template in `templates` replaced by that
//     template fitted by plastic strains to markers on its label (Wang et al. 2021; organ_fit.h), the fitted
//     organs pushed apart where they touch (Wang et al. 2021, §4.1.4; organ_separation.h) and bent out of the
//     other labels' tissues (bendOrgansOffLabels, Dicko et al. 2013's rule of no interpenetration). Without one, a
//     CT's own bone class as one bone tissue (an MRI's dark class is not bone alone: the skin only).
//  4. beyond the field of view: given the full-body reference, the reference completed into the patient's
//     partial skin and transferred into it (reference_completion.h; Dicko et al. 2013): a whole body around the scan.
//  5. the whole model (whole_model.h): the completed reference with, inside the field of view, the
//     patient's bones (the reference's meshes placed on the labels by the transfer's per-bone registration,
//     Dicko et al. 2013, §8 with the label as target, then refined onto them) and the patient's other tissues;
//     Dicko et al.'s rules measured on it (transfer/anatomy_rules.h).
//  6. the rig (patient_rig.h; Sujar et al. 2018) that carries the model: the whole model's own rig (its bone
//     meshes, its skin), or without the reference the rig of the scan's body and the organ map's bones
//     (the pelvis and femurs needed); posePatient then poses it.
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/grid.h"
#include "vesalius/core/label_map.h"
#include "vesalius/core/progress.h"
#include "vesalius/meshing/label_surfaces_apart.h"
#include "vesalius/patient/organ_fit.h"
#include "vesalius/patient/organ_separation.h"
#include "vesalius/patient/patient_rig.h"
#include "vesalius/patient/reference_completion.h"
#include "vesalius/patient/scan_anatomy.h"
#include "vesalius/patient/whole_model.h"
#include "vesalius/transfer/anatomy_rules.h"

#include <Eigen/Core>

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace vesalius::patient {

// A closed organ surface in any frame and scale, for the organ of label name `organ` (TotalSegmentator's).
struct OrganTemplate {
  std::string organ;
  TriMesh surface;
  std::string source;  // names it in messages and reports
};

struct VirtualPatientOptions {
  ScanAnatomyOptions surfaces;  // its modality also picks the tissue classification (CT or MRI)
  OrganFitOptions organFit;
  meshing::LabelSurfacesApartOptions labelsApart;  // the labels' tissues moved apart where they cross
  OrganSeparationOptions organSeparation;
  // The fitted organs bent out of the other labels' tissues (bendOrgansOffLabels): how far apart they should
  // end, and the bend's reaches (an organ's notch, then a vessel's groove), up to three passes. Rounds 0: no
  // bend.
  transfer::InsideSkinWarpOptions organsOffLabels = offLabelsBend();
  bool rig = true;  // rig the whole model, or without the reference the scan when the organ map has its bones
  PatientRigOptions rigging;
  // The full-body reference (full_body_reference.h) to complete into the patient beyond the field of view;
  // none: no completion. The caller's, not copied.
  const ReferenceAnatomy* fullBodyReference = nullptr;
  ReferenceCompletionOptions completion;
  // The whole model (whole_model.h); its groupLabels also name the labels the transfer's per-bone
  // registration places each reference bone group on (Dicko et al. 2013, §8).
  WholeModelOptions whole;

  static transfer::InsideSkinWarpOptions offLabelsBend() {
    transfer::InsideSkinWarpOptions o;
    o.marginMm = 0.5;
    o.radiiMm = {30.0, 10.0};
    o.passes = 3;
    return o;
  }
};

struct FittedOrgan {
  std::string organ, templateSource;
  OrganFit fit;
};

struct VirtualPatient {
  // Inside the field of view: the scan's skin (cut vertices marked) and the tissues of its labels, mm LPS.
  ReferenceAnatomy anatomy;
  Eigen::VectorXd fatThickness;  // #skin V: subcutaneous fat, mm
  LabelMap tissueClasses;        // the CT's tissue classes, on its grid
  // Each label name of the organ map the model represents, and the tissues (names in anatomy.tissues)
  // that represent it.
  std::map<std::string, std::vector<std::string>> labelTissues;
  meshing::LabelSurfacesApart labelsApart;  // the labels' tissues moved apart where they cross
  std::vector<FittedOrgan> fits;
  std::vector<OrganPairSeparation> organSeparation;  // indices into fits; every pair, touching or not
  transfer::TissuesBentApart organsOffLabels;        // the fits bent out of the other labels' tissues
  std::optional<ReferenceCompletion> completion;  // with options.fullBodyReference
  std::optional<WholeModel> whole;                // with the completion: the whole model
  std::optional<transfer::AnatomyRules> rules;    // Dicko et al.'s rules on the whole model (anatomy_rules.h)
  // Carries model(). None without the whole model and an organ map holding the pelvis and femurs.
  std::optional<PatientRig> rig;
  std::string noRigBecause;  // why there is no rig, in the user's words
  std::vector<std::pair<std::string, double>> stageSeconds;  // in the order they ran

  // The whole model, or without the reference the anatomy inside the field of view.
  const ReferenceAnatomy& model() const { return whole ? whole->anatomy : anatomy; }
};

// What buildVirtualPatient refuses, without its work, for a caller with long work of its own before it (the
// full-body reference): a CT without a voxel of the body's density or a constant MRI (naming `scanSource`;
// options.surfaces.modality says which the scan is), an organ map on
// another grid or with no label the model knows (naming `organsSource`), and when the patient is to be posed
// (`posed`), a patient without a rig: without the reference (`withReference` false), one without an organ map
// holding the pelvis and femurs (naming the organ map, or the scan without one). Throws BadInput; and
// UsageError for a rig's tet target below what its bones' surfaces allow (rigging::checkRigTargetTets).
void checkVirtualPatientInputs(const Image& scan, const LabelMap* organs, const std::vector<OrganTemplate>& templates,
                               const VirtualPatientOptions& options, bool withReference, bool posed,
                               const std::string& scanSource, const std::string& organsSource);

// The stages buildVirtualPatient will run on these inputs, by the names it begins them with on its
// progress and reports them under (VirtualPatient::stageSeconds), each with its relative cost (its wall
// time on the shipped CT): a command's progress plan (core/progress.h). withReference: whether
// options.fullBodyReference will be set (a caller plans before it reads the reference).
std::vector<std::pair<std::string, double>> virtualPatientStages(const LabelMap* organs,
                                                                 const std::vector<OrganTemplate>& templates,
                                                                 const VirtualPatientOptions& options, bool withReference);

// scan: a CT in HU or an MRI, as options.surfaces.modality says. organs: its organ/bone segmentation on the
// same grid, or null. Throws BadInput naming
// `scanSource` for a scan with no body, naming `organsSource` for a label map on another grid or one in
// which neither a template's organ nor any other label has voxels.
VirtualPatient buildVirtualPatient(const Image& scan, const LabelMap* organs, const std::vector<OrganTemplate>& templates,
                                   const VirtualPatientOptions& options, const std::string& scanSource,
                                   const std::string& organsSource, Progress* progress = nullptr);

}  // namespace vesalius::patient
