// The stages of segmentCtTissues (ct_tissues.h), one per source file, internal to segmentation.
#pragma once

#include "skin_shell.h"
#include "vesalius/segmentation/ct_tissues.h"

namespace vesalius::segmentation::detail {

// Bone inside the body (stage 3).
Mask ctBone(const Image& ct, const Mask& body, const CtTissueOptions& options);

// Fat outside the muscle-wall envelope (stage 4). `fat`: fat-range voxels of the body outside skin and
// bone; `interior`: body voxels that are neither skin nor fat.
Mask subcutaneousFat(const Mask& body, const Mask& fat, const Mask& interior, const CtTissueOptions& o);

}  // namespace vesalius::segmentation::detail
