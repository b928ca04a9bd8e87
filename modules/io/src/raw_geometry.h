// The grid geometry of an image header read through the ITK seam (image_io_itk.h), for the readers on the
// Eigen side of it (image_io.cpp, slicer_segmentation.cpp).
#pragma once

#include "image_io_itk.h"
#include "vesalius/core/grid.h"

namespace vesalius::io {

GridGeometry geometryOf(const itk_seam::RawHeader& header);

}  // namespace vesalius::io
