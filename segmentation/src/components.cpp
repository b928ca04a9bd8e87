// Connected components of masks (label_ops.h): ITK's union-find labelling sorted by size; small pieces by
// core's flood (small_pieces.h).
#include "itk_bridge.h"
#include "vesalius/core/error.h"
#include "vesalius/core/small_pieces.h"
#include "vesalius/segmentation/label_ops.h"

#include <itkConnectedComponentImageFilter.h>
#include <itkRelabelComponentImageFilter.h>

#include <vector>

namespace vesalius::segmentation {
namespace {

using MaskImage = itk::Image<std::uint8_t, 3>;
using ComponentImage = itk::Image<std::uint32_t, 3>;

// Components of `mask` numbered 1, 2, ... by decreasing size.
Grid<std::uint32_t> sortedComponents(const Mask& mask, Connectivity connectivity) {
  auto label = itk::ConnectedComponentImageFilter<MaskImage, ComponentImage>::New();
  label->SetInput(detail::toItk(mask));
  label->SetFullyConnected(connectivity == Connectivity::Full);
  auto relabel = itk::RelabelComponentImageFilter<ComponentImage, ComponentImage>::New();
  relabel->SetInput(label->GetOutput());
  relabel->Update();
  return detail::fromItk<std::uint32_t>(relabel->GetOutput());
}

Grid<std::uint32_t> components(const Mask& mask) {
  auto label = itk::ConnectedComponentImageFilter<MaskImage, ComponentImage>::New();
  label->SetInput(detail::toItk(mask));
  label->SetFullyConnected(true);
  label->Update();
  return detail::fromItk<std::uint32_t>(label->GetOutput());
}

}  // namespace

Mask largestComponent(const Mask& mask, Connectivity connectivity) {
  const Grid<std::uint32_t> sorted = sortedComponents(mask, connectivity);
  Mask out(sorted.geometry);
  for (std::size_t n = 0; n < out.values.size(); ++n) out.values[n] = sorted.values[n] == 1;
  return out;
}

Mask componentsTouching(const Mask& mask, const Mask& seeds) {
  if (seeds.values.size() != mask.values.size())
    throw BadInput("", "seed mask and mask have different sizes");
  const Grid<std::uint32_t> labelled = components(mask);
  std::vector<std::uint8_t> touched(1, 0);
  for (std::size_t n = 0; n < labelled.values.size(); ++n) {
    const std::uint32_t c = labelled.values[n];
    if (c >= touched.size()) touched.resize(c + 1, 0);
    if (c != 0 && seeds.values[n]) touched[c] = 1;
  }
  Mask out(mask.geometry);
  for (std::size_t n = 0; n < out.values.size(); ++n) out.values[n] = touched[labelled.values[n]];
  return out;
}

Mask removeSmallComponents(const Mask& mask, std::int64_t minVoxels) {
  Mask kept = mask;
  dropSmallPieces(kept, minVoxels);
  return kept;
}

}  // namespace vesalius::segmentation
