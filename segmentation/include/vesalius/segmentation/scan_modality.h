// The modality of a scan, which decides how its tissue classes are found: a CT's from Hounsfield units
// (ct_tissues.h), an MRI's from the scan's own histogram (mri_tissues.h).
#pragma once

#include "vesalius/core/grid.h"
#include "vesalius/core/label_map.h"
#include "vesalius/core/progress.h"
#include "vesalius/segmentation/label_ops.h"

#include <string>

namespace vesalius::segmentation {

enum class Modality { Ct, Mri };

// "ct" or "mri".
std::string modalityName(Modality modality);

// The modality a scan's values show. A CT holds air, which reads −1000 HU (scanners pad beyond the
// reconstructed field with −1024 HU or lower), so a CT has values at or below −500 HU; an MRI's arbitrary
// units start near 0 (the shipped abdominal MRI reads −47 to 833). A CT without a voxel of air (no lung,
// no bowel gas, no air around the body) is taken for an MRI: name the modality for such a crop.
Modality guessModality(const Image& scan);

// The tissue classes of `scan` by its modality: segmentCtTissues or segmentMriTissues with their default
// options but the skin's thickness (mm). `progress` may be null.
LabelMap segmentTissues(const Image& scan, Modality modality, double skinThicknessMm = 2.0,
                        Progress* progress = nullptr);

// The class labels the fat forests need (fat/fat_forest.h), which both modalities have.
struct SkinAndFatLabels {
  Label skin, subcutaneousFat;
};
SkinAndFatLabels skinAndFatLabels(Modality modality);

// The body (1 inside, holes filled) as the modality's segmentation finds it: segmentCtBody or
// segmentMriBody with default options.
Mask segmentBody(const Image& scan, Modality modality);

}  // namespace vesalius::segmentation
