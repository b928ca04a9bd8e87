// The virtual patient: one patient's CT in, that patient's anatomy out, by the seeds' methods in their
// order (docs/virtual-patient.md). buildVirtualPatient runs, on core types:
//  1. segmentation: the CT's tissue classes (segmentation/ct_tissues.h); the skin is the body's outer
//     surface, its vertices where the field of view cut the body marked as cut (scan_anatomy.h).
//  2. fat: the subcutaneous fat thickness at every skin vertex from the shortest-path fat forests of the
//     scan's skin and subcutaneous fat classes (seed 000 §5; fat/fat_forest.h, fat/thickness_at_vertices.h);
//     0 on the cut, which is not skin.
//  3. the anatomy inside the field of view: with an organ/bone label map, each label as a closed tissue
//     surface of its kind (scan_anatomy.h), and each organ with a template in `templates` replaced by that
//     template fitted by plastic strains to markers on its label (seed 002; organ_fit.h). Without one, the
//     scan's own bone class as one bone tissue.
//  4. beyond the field of view: given the full-body reference, the reference completed into the patient's
//     partial skin and transferred into it (reference_completion.h; seed 000): a whole body around the scan.
//  5. the rig: with an organ map holding the pelvis (hips, sacrum) and the femurs, the rig of the patient's
//     body and bones that carries the model (patient_rig.h; seed 001); posePatient then poses it.
// Not yet (docs/virtual-patient.md): the model and the completed body merged into one (inside the field of
// view the completed body's bones registered onto the patient's labels, seed 000 §8), organs pushed apart
// where they touch (seed 002 §4.1.4).
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/grid.h"
#include "vesalius/core/label_map.h"
#include "vesalius/core/progress.h"
#include "vesalius/patient/organ_fit.h"
#include "vesalius/patient/patient_rig.h"
#include "vesalius/patient/reference_completion.h"
#include "vesalius/patient/scan_anatomy.h"

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
  ScanAnatomyOptions surfaces;
  OrganFitOptions organFit;
  bool rig = true;  // rig the model when the organ map has its bones
  PatientRigOptions rigging;
  // The full-body reference (full_body_reference.h) to complete into the patient beyond the field of view;
  // none: no completion. The caller's, not copied.
  const ReferenceAnatomy* fullBodyReference = nullptr;
  ReferenceCompletionOptions completion;
};

struct FittedOrgan {
  std::string organ, templateSource;
  OrganFit fit;
};

struct VirtualPatient {
  ReferenceAnatomy anatomy;      // skin (cut vertices marked) and tissues, mm LPS
  Eigen::VectorXd fatThickness;  // #skin V: subcutaneous fat, mm
  LabelMap tissueClasses;        // the CT's tissue classes, on its grid
  // Each label name of the organ map the model represents, and the tissues (names in anatomy.tissues)
  // that represent it.
  std::map<std::string, std::vector<std::string>> labelTissues;
  std::vector<FittedOrgan> fits;
  std::optional<ReferenceCompletion> completion;  // with options.fullBodyReference
  std::optional<PatientRig> rig;  // none without an organ map holding the pelvis and femurs
  std::string noRigBecause;       // why there is no rig, in the user's words
  std::vector<std::pair<std::string, double>> stageSeconds;  // in the order they ran
};

// ct: a CT in HU. organs: its organ/bone segmentation on the same grid, or null. Throws BadInput naming
// `scanSource` for a scan with no body, naming `organsSource` for a label map on another grid or one in
// which neither a template's organ nor any other label has voxels.
VirtualPatient buildVirtualPatient(const Image& ct, const LabelMap* organs, const std::vector<OrganTemplate>& templates,
                                   const VirtualPatientOptions& options, const std::string& scanSource,
                                   const std::string& organsSource, Progress* progress = nullptr);

}  // namespace vesalius::patient
