// Tissue classes of a CT scan from Hounsfield units: air, skin, subcutaneous fat, other fat, soft tissue
// and bone.
//
// Method (each stage a Progress stage):
//  1. body: HU > bodyMinHu, opened by a ball of bodyOpeningMm (drops the table and clothing, which touch
//     the body only through thin bridges), largest 26-connected component, holes filled per axial slice
//     and then in 3-D (lungs and bowel gas belong to the body).
//  2. skin: body voxels whose centre lies within skinThicknessMm of the body surface, measured with a
//     Euclidean distance map in mm; the surface is taken half the smallest spacing outside the centres of
//     the outermost voxels, so a 2 mm skin on 3 mm voxels is the outer voxel layer.
//  3. bone: HU >= boneMinHu, closed by boneClosingMm, marrow filled per axial slice, components smaller
//     than minBoneComponentMl dropped (calcifications, contrast specks).
//  4. fat: fatMinHu <= HU <= fatMaxHu. Subcutaneous fat is the fat outside the muscle wall: the non-fat
//     interior (body minus skin, fat and bone-free gaps... i.e. every non-fat, non-skin body voxel) is closed
//     by muscleWallClosingMm, its largest component taken and its holes filled per axial slice; fat outside
//     that envelope and connected through fat to the skin is subcutaneous, all other fat is "fat".
//  5. the rest of the body is soft tissue if HU > fatMaxHu and air (0) if HU < fatMinHu (gas in lungs and
//     bowel, partial volume).
// Label ids are fixed (CtTissue); bone is split into cortical and trabecular by HU when asked.
// Shapes: the result has the geometry of `ct`. Values of `ct` are HU.
#pragma once

#include "vesalius/core/label_map.h"
#include "vesalius/core/progress.h"
#include "vesalius/segmentation/label_ops.h"

namespace vesalius::segmentation {

enum CtTissue : Label {
  kCtAir = 0,
  kCtSkin = 1,
  kCtSubcutaneousFat = 2,
  kCtFat = 3,
  kCtSoftTissue = 4,
  kCtBone = 5,             // "bone", or "cortical_bone" when splitBone
  kCtTrabecularBone = 6,   // only when splitBone
};

struct CtTissueOptions {
  float bodyMinHu = -500.0f;
  double bodyOpeningMm = 3.0;
  double skinThicknessMm = 2.0;
  float fatMinHu = -190.0f;
  float fatMaxHu = -30.0f;
  float boneMinHu = 200.0f;
  double boneClosingMm = 3.0;
  double maxMarrowAreaMm2 = 2500.0;
  double minBoneComponentMl = 0.5;
  double muscleWallClosingMm = 12.0;
  bool splitBone = false;
  float corticalMinHu = 700.0f;  // with splitBone: bone at or above this is cortical, below trabecular
};

// The body mask of stage 1 (1 inside the body, holes filled), geometry of `ct`.
Mask segmentCtBody(const Image& ct, const CtTissueOptions& options);

// All stages; `progress` may be null. Throws BadInput if `ct` has no voxel above bodyMinHu.
LabelMap segmentCtTissues(const Image& ct, const CtTissueOptions& options = {},
                          Progress* progress = nullptr);

// The label table of segmentCtTissues: skin, subcutaneous_fat, fat, soft_tissue, bone (or
// cortical_bone and trabecular_bone), with fixed colours.
LabelTable ctTissueTable(bool splitBone);

}  // namespace vesalius::segmentation
