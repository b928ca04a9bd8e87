// Copies between vesalius::Grid and itk::Image (internal to segmentation; the only place ITK meets core).
//
// Both store voxels with i fastest, then j, then k, so a buffer copy keeps the layout. Origin, spacing
// and direction carry over unchanged: the columns of GridGeometry::direction are the columns of ITK's
// direction matrix.
#pragma once

#include "vesalius/core/grid.h"

#include <itkImage.h>

#include <algorithm>

namespace vesalius::segmentation::detail {

template <class T>
typename itk::Image<T, 3>::Pointer toItk(const Grid<T>& grid) {
  using ImageType = itk::Image<T, 3>;
  const GridGeometry& g = grid.geometry;
  typename ImageType::SizeType size;
  typename ImageType::PointType origin;
  typename ImageType::SpacingType spacing;
  typename ImageType::DirectionType direction;
  for (unsigned a = 0; a < 3; ++a) {
    size[a] = static_cast<itk::SizeValueType>(g.size[a]);
    origin[a] = g.origin[a];
    spacing[a] = g.spacing[a];
    for (unsigned b = 0; b < 3; ++b) direction(a, b) = g.direction(a, b);
  }
  auto image = ImageType::New();
  image->SetRegions(typename ImageType::RegionType(size));
  image->SetOrigin(origin);
  image->SetSpacing(spacing);
  image->SetDirection(direction);
  image->Allocate();
  std::copy(grid.values.begin(), grid.values.end(), image->GetBufferPointer());
  return image;
}

// `image` must have a buffered region starting at index 0 (as every filter output here has).
template <class Out, class In>
Grid<Out> fromItk(const itk::Image<In, 3>* image) {
  GridGeometry g;
  const auto size = image->GetBufferedRegion().GetSize();
  for (unsigned a = 0; a < 3; ++a) {
    g.size[a] = static_cast<int>(size[a]);
    g.origin[a] = image->GetOrigin()[a];
    g.spacing[a] = image->GetSpacing()[a];
    for (unsigned b = 0; b < 3; ++b) g.direction(a, b) = image->GetDirection()(a, b);
  }
  Grid<Out> grid(g);
  const In* buffer = image->GetBufferPointer();
  std::transform(buffer, buffer + grid.values.size(), grid.values.begin(),
                 [](In v) { return static_cast<Out>(v); });
  return grid;
}

}  // namespace vesalius::segmentation::detail
