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
//  3. bone: HU >= boneMinHu, closed by boneClosingMm, holes up to maxMarrowAreaMm2 filled in axial,
//     coronal and sagittal slices (marrow, whose cortex is closed in some view), components smaller than
//     minBoneComponentMl dropped (calcifications, contrast specks). The default threshold, 140 HU, is
//     below the textbook 200 HU because trabecular bone at 3 mm voxels reads 100-200 HU; it is a
//     compromise with contrast-enhanced organs, which in the shipped CT read mostly 100-150 HU, so a few of
//     their voxels become bone.
//  4. fat: fatMinHu <= HU <= fatMaxHu. Subcutaneous fat is the fat outside the muscle wall, found as
//     the outer fat layer: the non-fat interior (every body voxel that is neither skin nor fat, bone
//     included), without a shell of muscleWallMinDepthMm under the surface (skin and dermis), is reduced
//     to its largest component (the wall and what it holds; septa and vessels in the fat are islands),
//     closed by muscleWallClosingMm (bridging gaps in the wall) and filled per axial slice. Fat outside
//     that envelope is subcutaneous; all other fat is "fat".
//  5. the rest of the body is soft tissue if HU > fatMaxHu and air (0) if HU < fatMinHu (gas in lungs and
//     bowel, partial volume).
// Checked against TotalSegmentator's labels of example_ct_sm (tests/segmentation): Dice 0.93 for
// subcutaneous fat, 0.88 for bone.
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
  kCtBone = 5,            // "bone", or "cortical_bone" when splitBone
  kCtTrabecularBone = 6,  // only when splitBone
};

struct CtTissueOptions {
  float bodyMinHu = -500.0f;
  double bodyOpeningMm = 3.0;
  double skinThicknessMm = 2.0;
  float fatMinHu = -190.0f;
  float fatMaxHu = -30.0f;
  float boneMinHu = 140.0f;
  double boneClosingMm = 3.0;
  double maxMarrowAreaMm2 = 2500.0;
  double minBoneComponentMl = 0.5;
  double muscleWallClosingMm = 12.0;
  double muscleWallMinDepthMm = 6.0;
  bool splitBone = false;
  float corticalMinHu = 600.0f;  // with splitBone: bone at or above this is cortical, below trabecular
};

// The body mask of stage 1 (1 inside the body, holes filled), geometry of `ct`.
Mask segmentCtBody(const Image& ct, const CtTissueOptions& options);

// All stages; `progress` may be null. Throws BadInput if `ct` has no voxel above bodyMinHu.
LabelMap segmentCtTissues(const Image& ct, const CtTissueOptions& options = {}, Progress* progress = nullptr);

// The label table of segmentCtTissues: skin, subcutaneous_fat, fat, soft_tissue, bone (or
// cortical_bone and trabecular_bone), with fixed colours.
LabelTable ctTissueTable(bool splitBone);

}  // namespace vesalius::segmentation
