// Tissue classes of a T1-weighted MRI, which has no Hounsfield units: body, skin, subcutaneous fat and
// bone where it is dark (on a head, the scalp fat and the skull).
//
// Method (each stage a Progress stage):
//  1. body: the scan smoothed by a Gaussian of smoothingMm (sigma), thresholded at bodyOtsuFraction times
//     Otsu's threshold of all voxels (otsu.h), largest 26-connected component, holes filled per axial
//     slice (airways, the ear canals and whatever opens through the cut faces) and then in 3-D (skull,
//     sinuses). Otsu's level lies between air and the mean of all tissue; the outermost layers (skin,
//     on T1 also the skull and CSF) are darker than that mean, and a partial-volume edge is crossed at
//     half its intensity, hence the fraction (0.5: on the head MRI Otsu's level is 49 and skin reads
//     16-50, so the full level would drop the skin).
//  2. skin: body voxels within skinThicknessMm of the body surface (as for CT, ct_tissues.h).
//  3. layer levels: a three-class Otsu of the raw values in the band under the skin down to
//     layerDepthMm splits dark (cortical bone, CSF, air), middle (muscle, grey matter) and bright (fat,
//     whose short T1 makes it the brightest tissue) values.
//  4. subcutaneous fat: bright band voxels connected to the skin through bright band voxels: the bright
//     layer under the skin. Bright tissue deeper in (white matter, marrow behind an intact cortex) is not
//     connected and stays out.
//  5. bone: dark body voxels (not skin or fat) within maxBoneDistanceMm of the skin or fat, in the
//     26-connected components that reach to within boneSeedDistanceMm of it and hold at least
//     minBoneComponentMl: the dark layer under the scalp. T1 gives cortical bone and CSF the same dark
//     values, so the bone class also holds the thin CSF layer under the skull (and 0.5 % of the brain
//     extracted by BET on the head MRI).
//  6. the rest of the body is soft tissue (brain, muscle, organs).
// Checked on the Colin27 head (tests/segmentation/mri_tissues_test.cpp): one body component without holes;
// above the skull base (MNI z = -21 mm; below it the foramen magnum and orbits open the skull) the bone
// class encloses 99.6 % of BET's brain and no scalp, and the scalp fat stays >= 6.7 mm from the brain.
// On an abdominal MR the fat found is the brighter outer part of the subcutaneous layer: the surface
// coil's falloff darkens its inner part below the band's upper level (docs/methods/mri-tissues.md).
// Shapes: the result has the geometry of `scan`; values are arbitrary MRI units.
#pragma once

#include "vesalius/core/label_map.h"
#include "vesalius/core/progress.h"
#include "vesalius/segmentation/label_ops.h"

namespace vesalius::segmentation {

enum MriTissue : Label {
  kMriBackground = 0,
  kMriSkin = 1,
  kMriSubcutaneousFat = 2,  // the scalp fat on a head
  kMriBone = 3,             // dark bone (and the CSF next to it); the skull on a head
  kMriSoftTissue = 4,
};

struct MriTissueOptions {
  double smoothingMm = 1.0;
  double bodyOtsuFraction = 0.5;
  double skinThicknessMm = 2.0;
  double layerDepthMm = 15.0;
  double maxBoneDistanceMm = 20.0;  // the temporal bone lies under up to ~15 mm of temporalis muscle
  double boneSeedDistanceMm = 1.5;
  double minBoneComponentMl = 0.5;
};

// The body mask of stage 1 (1 inside the body, holes filled), geometry of `scan`. Throws BadInput if
// the scan is constant (no threshold) or nothing survives.
Mask segmentMriBody(const Image& scan, const MriTissueOptions& options = {});

// All stages; `progress` may be null.
LabelMap segmentMriTissues(const Image& scan, const MriTissueOptions& options = {}, Progress* progress = nullptr);

// The label table of segmentMriTissues: skin, subcutaneous_fat, bone, soft_tissue, with the colours of
// ctTissueTable for the same tissues.
LabelTable mriTissueTable();

}  // namespace vesalius::segmentation
