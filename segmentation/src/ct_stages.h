// The stages of segmentCtTissues (ct_tissues.h), one per source file, internal to segmentation.
#pragma once

#include "vesalius/segmentation/ct_tissues.h"

namespace vesalius::segmentation::detail {

// Body voxels within thicknessMm of the body surface (ct_tissues.h, stage 2).
Mask skinShell(const Mask& body, double thicknessMm);

// Bone inside the body (stage 3).
Mask ctBone(const Image& ct, const Mask& body, const CtTissueOptions& options);

// Fat outside the muscle-wall envelope (stage 4). `fat`: fat-range voxels of the body outside skin and
// bone; `interior`: body voxels that are neither skin nor fat.
Mask subcutaneousFat(const Mask& body, const Mask& fat, const Mask& interior, const CtTissueOptions& o);

}  // namespace vesalius::segmentation::detail
