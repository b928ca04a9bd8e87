// Organs and muscles for the full-body reference (issue 30, item 3): the full-body reference (MakeHuman
// skin, OpenSim bones, full_body_reference.h) has no organs; this carries a labelled CT's organs and
// muscles into it by the virtual patient's own transfer, once, and the result is shipped
// (templates/reference-organs/) for buildFullBodyReference to add (FullBodySources::organs).
//  1. The virtual patient of the CT with its labels and the full-body reference (virtual_patient.h): the
//     reference completed into the CT's body and one model of it with, inside the field of view, the
//     CT's organs (templates fitted by plastic strains, Wang et al. 2021, pushed apart where they touch) and the
//     labels' other organs and muscles as surfaces.
//  2. That model carried back into the reference's own skin by the same transfer (Dicko et al. 2013, §7-8,
//     transfer_into_body.h): the completion made the model's skin from the reference's (the same
//     vertices), so it is taken back onto the reference's skin vertex by vertex, without erosion; each
//     bone group of the model is registered onto the reference's own bones of that group (§8's per-bone
//     registration with the target's bones known, transfer::AnatomyTransferOptions::boneTargets), and the
//     final field carries the organs and muscles with the skin and the bones.
//  3. Of the carried model, the tissues named in `tissues` (organs and muscles) kept, in the reference's
//     frame (mm LPS), with the reference's skin.
//  4. What the transfer left outside the reference's skin bent inside it, all kept tissues by one smooth
//     displacement (transfer/bones_warped_into_skin.h, as the reference's own bones are): the CT's
//     patient lay supine, flattening back and buttocks that MakeHuman's standing body rounds, and the
//     field carries what lies just under the skin (the back and gluteal muscles, the spleen's and liver's
//     outer faces) past it.
// Deviations, plainly: the organs are one CT's (one subject, its organ sizes), and an organ the CT's field
// of view cut (the liver's and spleen's tops, the aorta, the colon) keeps its cut face, flat where the
// scan ended; the muscles lie on the CT's own bones, which OpenSim's differ from, so they reach into the
// reference's bones; on the shipped CT the organs come out about 20 mm further up the body, relative to
// the reference's pelvis, than the CT's are relative to its own (docs/virtual-patient.md).
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/grid.h"
#include "vesalius/core/label_map.h"
#include "vesalius/core/progress.h"
#include "vesalius/patient/virtual_patient.h"
#include "vesalius/transfer/bones_warped_into_skin.h"

#include <Eigen/Core>

#include <string>
#include <utility>
#include <vector>

namespace vesalius::patient {

// The abdominal and pelvic organs, their vessels, and the gluteal, iliopsoas and back muscles of
// TotalSegmentator's labels (v1 and v2 share these names). Not the lungs, heart and airways: the shipped
// CT holds only their lowest centimetres.
inline std::vector<std::string> abdominalAndPelvicTissues() {
  return {"liver", "spleen", "kidney_left", "kidney_right", "gallbladder", "stomach", "pancreas",
          "adrenal_gland_left", "adrenal_gland_right", "duodenum", "small_bowel", "colon", "urinary_bladder",
          "aorta", "inferior_vena_cava", "portal_vein_and_splenic_vein", "iliac_artery_left",
          "iliac_artery_right", "iliac_vena_left", "iliac_vena_right", "gluteus_maximus_left",
          "gluteus_maximus_right", "gluteus_medius_left", "gluteus_medius_right", "gluteus_minimus_left",
          "gluteus_minimus_right", "iliopsoas_left", "iliopsoas_right", "autochthon_left", "autochthon_right"};
}

struct ReferenceOrgansOptions {
  VirtualPatientOptions patient = modest();  // step 1 (its fullBodyReference is set by referenceOrgans)
  TransferIntoBodyOptions transfer = ReferenceCompletionOptions::withFieldVoxel(4.0);  // step 2
  std::vector<std::string> tissues = abdominalAndPelvicTissues();  // step 3: kept when the model has them
  transfer::InsideSkinWarpOptions intoSkin;                          // step 4

  // Label surfaces of 2,000 triangles (a shipped folder of modest meshes), no rig.
  static VirtualPatientOptions modest() {
    VirtualPatientOptions o;
    o.surfaces.tissueFaces = 2000;
    o.rig = false;
    return o;
  }
};

struct CarriedTissue {
  std::string name;
  TissueKind kind = TissueKind::Organ;
  // Vertices, and those outside the reference's skin (winding number < 1/2) as carried and after step 4.
  long vertices = 0, outsideCarried = 0, outsideSkin = 0;
};

struct ReferenceOrgans {
  // The reference's skin with the kept tissues (organs, muscles), mm LPS in the reference's frame.
  ReferenceAnatomy anatomy;
  std::vector<CarriedTissue> carried;  // per anatomy.tissues
  double scanSkinToCompletedMeanMm = 0;  // step 1's completion: how closely the reference met the CT's skin
  double bendLargestMm = 0;              // step 4's largest move of a vertex
  std::vector<std::pair<std::string, double>> stageSeconds;  // in the order they ran
};

// ct: a CT in HU; organs: its organ label map on the same grid (TotalSegmentator's names); templates: the
// organ template library (buildVirtualPatient's); fullBodyReference: the full-body reference without
// organs (its organ and muscle tissues, if any, are left out of step 1). Throws BadInput naming
// `organsSource` if none of `options.tissues` comes out of step 1, and as buildVirtualPatient does.
ReferenceOrgans referenceOrgans(const Image& ct, const LabelMap& organs, const std::vector<OrganTemplate>& templates,
                                const ReferenceAnatomy& fullBodyReference, const ReferenceOrgansOptions& options,
                                const std::string& scanSource, const std::string& organsSource,
                                Progress* progress = nullptr);

}  // namespace vesalius::patient
