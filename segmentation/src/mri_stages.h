// The stages of segmentMriTissues (mri_tissues.h), internal to segmentation.
#pragma once

#include "vesalius/segmentation/mri_tissues.h"

namespace vesalius::segmentation::detail {

// The image blurred by a Gaussian of standard deviation sigmaMm in world units (ITK's recursive
// Gaussian, Deriche's IIR approximation), spacing honoured per axis.
Grid<float> gaussianSmoothMm(const Grid<float>& image, double sigmaMm);

struct MriLayers {
  Mask fat, bone;
};

// Stages 3-5: subcutaneous fat and dark bone under the skin.
MriLayers mriLayers(const Image& scan, const Mask& body, const Mask& skin, const MriTissueOptions& options);

}  // namespace vesalius::segmentation::detail
