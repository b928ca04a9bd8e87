// Gaussian smoothing in mm for the MRI body threshold (mri_stages.h).
#include "itk_bridge.h"
#include "mri_stages.h"
#include "vesalius/core/error.h"

#include <itkSmoothingRecursiveGaussianImageFilter.h>

#include <cmath>

namespace vesalius::segmentation::detail {

Grid<float> gaussianSmoothMm(const Grid<float>& image, double sigmaMm) {
  if (!(sigmaMm >= 0.0) || !std::isfinite(sigmaMm)) throw UsageError("smoothing must be a finite number of mm >= 0");
  if (sigmaMm == 0.0) return image;
  using ImageType = itk::Image<float, 3>;
  auto filter = itk::SmoothingRecursiveGaussianImageFilter<ImageType, ImageType>::New();
  filter->SetInput(toItk(image));
  filter->SetSigma(sigmaMm);  // in physical units: ITK divides by each axis' spacing
  filter->SetNormalizeAcrossScale(false);
  filter->Update();
  return fromItk<float>(filter->GetOutput());
}

}  // namespace vesalius::segmentation::detail
