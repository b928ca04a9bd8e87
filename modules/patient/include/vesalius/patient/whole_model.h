// The virtual patient's whole model: the full-body reference completed into the patient
// (reference_completion.h) holding, inside the scan's field of view, the patient's own anatomy.
//  - Bones with a label: each reference bone that `boneLabels` pairs with a label of the organ map (the hip
//    bones, the femurs) keeps its mesh and its name and is brought onto that label
//    (bone_onto_label.h). Its group was already placed on the labels by the transfer's per-bone
//    registration (transfer::AnatomyTransferOptions::boneTargets), so the muscles and the bones beyond
//    the field of view follow it; here the mesh takes the label's shape. Bones on labels that share voxel
//    faces (the hip bones at the symphysis, a femoral head in its acetabulum, the bladder against a hip
//    bone) each take their own label's boundary, and where those cross each other or the scan's tissues of
//    neighbouring labels they are moved apart (meshing/label_surfaces_apart.h), as the labels' own surfaces
//    are.
//  - Reference bones that labels show bone by bone: OpenSim gives the spine, the rib cage with the
//    scapulae and the skull as one mesh each, where the organ map has a label per vertebra and per rib.
//    Inside the field of view the labels' surfaces take their place: the reference mesh keeps only its
//    faces wholly beyond the scan (`replacedInsideScan`), its cut closed by fans (core/cap_holes.h) so
//    that it keeps an inside.
//  - Every other tissue of the patient's anatomy (the fitted organs, other bones and muscles of the labels)
//    is added under its label's name; a reference tissue of the same name gives way to it. A bone of the
//    labels that `groupLabels` pairs with an OpenSim body joins that body's group (the sacrum the pelvis,
//    vertebrae and ribs the torso), so that a rig of the model moves it with that body's joint.
//  - The skin is the completed skin (the scan's skin where the scan sees skin, the reference's beyond).
//  - The reference's tissues that reach into the patient's (its rib cage above the scan into the liver that
//    a template continued there, its tibiae and patellae into femurs brought onto larger labels) are bent
//    out of them, inside the skin (transfer/tissues_bent_apart.h); the patient's own tissues do not move.
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/label_map.h"
#include "vesalius/meshing/label_surfaces_apart.h"
#include "vesalius/patient/bone_onto_label.h"
#include "vesalius/transfer/tissues_bent_apart.h"

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

// Rajagopal's trunk meshes that TotalSegmentator's labels show bone by bone, and the labels that show them
// (a name ending in '*' is a prefix): its CT labels name each vertebra, its MR labels all as "vertebrae".
inline std::vector<std::pair<std::string, std::string>> defaultReferenceBonesReplacedInsideScan() {
  return {{"hat_spine", "vertebrae*"}, {"hat_ribs_scap", "rib_*"}, {"hat_skull", "skull"}};
}

// Rajagopal's bone groups (OpenSim's bodies) and the TotalSegmentator labels that show them; a name
// ending in '*' is a prefix.
inline std::vector<std::pair<std::string, std::string>> defaultBoneGroupLabels() {
  return {{"pelvis", "hip_left"},   {"pelvis", "hip_right"},   {"pelvis", "sacrum"},     {"femur_l", "femur_left"},
          {"femur_r", "femur_right"}, {"torso", "vertebrae*"}, {"torso", "rib_*"},       {"torso", "sternum"},
          {"torso", "costal_cartilages"}, {"torso", "scapula_*"}, {"torso", "clavicula_*"}, {"skull", "skull"}};
}

// Whether label `name` is `pattern` (a name ending in '*' is a prefix).
bool labelMatches(const std::string& name, const std::string& pattern);

struct WholeModelOptions {
  // Reference tissue → label: the tissue brought onto the label's shape; pairs whose tissue or label is
  // missing are skipped.
  std::vector<std::pair<std::string, std::string>> boneLabels = defaultReferenceBoneLabels();
  // OpenSim body → label: the bone group a bone of the labels joins (and the transfer's per-bone targets,
  // boneGroupTargets).
  std::vector<std::pair<std::string, std::string>> groupLabels = defaultBoneGroupLabels();
  // Reference tissue → label: inside the scan the labels' tissues take the place of the tissue's faces.
  std::vector<std::pair<std::string, std::string>> replacedInsideScan = defaultReferenceBonesReplacedInsideScan();
  // The bones are placed by the transfer's per-bone registration: no affine step of their own, so the
  // group's map keeps them where the muscles and the bones beyond the scan were carried.
  BoneOntoLabelOptions bones = placedBones();
  // The bend of the reference's tissues out of the patient's: how far apart they should end, and its
  // reaches (a rib's, then a patella's), up to three passes. Rounds 0: no bend.
  transfer::InsideSkinWarpOptions apart = apartBend();

  static BoneOntoLabelOptions placedBones() {
    BoneOntoLabelOptions o;
    o.affineTargets = 0;
    return o;
  }
  static transfer::InsideSkinWarpOptions apartBend() {
    transfer::InsideSkinWarpOptions o;
    o.marginMm = 0.5;
    o.passes = 3;
    return o;
  }
};

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
  meshing::LabelSurfacesApart bonesApart;          // the bones on labels moved apart from each other
  meshing::LabelSurfacesApart bonesApartFromScan;  // and from the scan's tissues, in the field of view
  // Each reference tissue that the labels replaced inside the scan, and how many of its faces went (a
  // tissue whose faces all went is gone from the model).
  std::vector<std::pair<std::string, long>> replacedFaces;
  // The reference's tissues bent out of the patient's.
  transfer::TissuesBentApart apart;
};

// completed: the reference completed into the patient; inFov: the patient's anatomy inside the field of
// view (its tissues named by their labels); organs: the organ map (null: the completed reference alone,
// with the completed skin). Throws what registerBoneOntoLabel throws.
WholeModel wholeModel(const ReferenceAnatomy& completed, const ReferenceAnatomy& inFov, const LabelMap* organs,
                      const WholeModelOptions& options, const std::string& organsSource);

// For each bone group of `reference` (ReferenceTissue::group) that `groupLabels` pairs with labels that
// have voxels in `organs`, `pointsPerGroup` points spread over those labels' boundary inside the scan: the
// targets of the transfer's per-bone registration (transfer::AnatomyTransferOptions::boneTargets).
std::map<std::string, MatrixX3d> boneGroupTargets(const ReferenceAnatomy& reference, const LabelMap& organs,
                                                  const std::vector<std::pair<std::string, std::string>>& groupLabels,
                                                  int pointsPerGroup = 2000);

}  // namespace vesalius::patient
