// The virtual patient's whole model: the full-body reference completed into the patient
// (reference_completion.h) holding, inside the scan's field of view, the patient's own anatomy.
//  - Bones with a label: each reference bone that `boneLabels` pairs with a label of the organ map (the hip
//    bones, the femurs) keeps its mesh and its name and is brought onto that label
//    (bone_onto_label.h). Its group was already placed on the labels by the transfer's per-bone
//    registration (transfer::AnatomyTransferOptions::boneTargets), so the muscles and the bones beyond
//    the field of view follow it; here the mesh takes the label's shape.
//  - Every other tissue of the patient's anatomy (the fitted organs, other bones and muscles of the labels)
//    is added under its label's name; a reference tissue of the same name gives way to it.
//  - The skin is the completed skin (the scan's skin where the scan sees skin, the reference's beyond).
// Not yet: the reference's spine and rib cage are one mesh each (OpenSim's), which the patient's own
// vertebrae and ribs overlap inside the field of view.
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/label_map.h"
#include "vesalius/patient/bone_onto_label.h"

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace vesalius::patient {

// Rajagopal's OpenSim bone meshes (the full-body reference's names) and TotalSegmentator's labels. Not
// the sacrum: its label holds the sacral canal and foramina, which OpenSim's closed sacrum has not, and
// the mesh brought onto it reached Dice 0.90 on the shipped CT against 0.97 for the label's own surface;
// the label's surface, a tissue of the same name, takes the reference sacrum's place.
inline std::vector<std::pair<std::string, std::string>> defaultReferenceBoneLabels() {
  return {{"l_pelvis", "hip_left"}, {"r_pelvis", "hip_right"}, {"l_femur", "femur_left"}, {"r_femur", "femur_right"}};
}

struct RegisteredBone {
  std::string tissue, label;
  BoneOntoLabel registration;
};

struct WholeModel {
  ReferenceAnatomy anatomy;
  // Each label name of the organ map the model represents and the tissues (names in anatomy.tissues)
  // that represent it.
  std::map<std::string, std::vector<std::string>> labelTissues;
  std::vector<RegisteredBone> bones;
};

// completed: the reference completed into the patient; inFov: the patient's anatomy inside the field of
// view (its tissues named by their labels); organs: the organ map (null: the completed reference alone,
// with the completed skin). boneLabels: reference tissue → label, pairs whose tissue or label is missing
// are skipped. Throws what registerBoneOntoLabel throws.
WholeModel wholeModel(const ReferenceAnatomy& completed, const ReferenceAnatomy& inFov, const LabelMap* organs,
                      const std::vector<std::pair<std::string, std::string>>& boneLabels,
                      const BoneOntoLabelOptions& options, const std::string& organsSource);

// Rajagopal's bone groups (OpenSim's bodies) and the TotalSegmentator labels that show them; a name
// ending in '*' is a prefix.
inline std::vector<std::pair<std::string, std::string>> defaultBoneGroupLabels() {
  return {{"pelvis", "hip_left"},    {"pelvis", "hip_right"},   {"pelvis", "sacrum"}, {"femur_l", "femur_left"},
          {"femur_r", "femur_right"}, {"torso", "vertebrae_*"}, {"torso", "rib_*"}};
}

// For each bone group of `reference` (ReferenceTissue::group) that `groupLabels` pairs with labels that
// have voxels in `organs`, `pointsPerGroup` points spread over those labels' boundary inside the scan: the
// targets of the transfer's per-bone registration (transfer::AnatomyTransferOptions::boneTargets).
std::map<std::string, MatrixX3d> boneGroupTargets(const ReferenceAnatomy& reference, const LabelMap& organs,
                                                  const std::vector<std::pair<std::string, std::string>>& groupLabels,
                                                  int pointsPerGroup = 2000);

}  // namespace vesalius::patient
