// Euclidean distance maps in mm (label_ops.h), by ITK's SignedMaurerDistanceMapImageFilter.
#include "itk_bridge.h"
#include "vesalius/segmentation/label_ops.h"

#include <itkSignedMaurerDistanceMapImageFilter.h>

#include <algorithm>
#include <limits>

namespace vesalius::segmentation {

Grid<float> distanceToMaskMm(const Mask& mask) {
  if (countVoxels(mask) == 0) return Grid<float>(mask.geometry, std::numeric_limits<float>::infinity());
  using MaskImage = itk::Image<std::uint8_t, 3>;
  using DistanceImage = itk::Image<float, 3>;
  auto filter = itk::SignedMaurerDistanceMapImageFilter<MaskImage, DistanceImage>::New();
  filter->SetInput(detail::toItk(mask));
  filter->SetBackgroundValue(0);
  filter->SetUseImageSpacing(true);
  filter->SetSquaredDistance(false);
  filter->SetInsideIsPositive(false);
  filter->Update();
  // Outside the mask the signed map is the distance to the nearest mask voxel centre; inside it is
  // negative (depth), which this function reports as 0.
  Grid<float> distance = detail::fromItk<float>(filter->GetOutput());
  for (float& d : distance.values) d = std::max(d, 0.0f);
  return distance;
}

}  // namespace vesalius::segmentation
