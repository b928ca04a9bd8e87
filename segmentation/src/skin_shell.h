// The skin shell of a body mask, shared by the CT and MRI tissue classifiers (internal to segmentation).
#pragma once

#include "vesalius/segmentation/label_ops.h"

namespace vesalius::segmentation::detail {

// Body voxels whose centres lie within thicknessMm of the body surface.
Mask skinShell(const Mask& body, double thicknessMm);

}  // namespace vesalius::segmentation::detail
