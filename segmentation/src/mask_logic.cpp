// Elementwise mask construction and logic (label_ops.h).
#include "vesalius/core/error.h"
#include "vesalius/segmentation/label_ops.h"

#include <algorithm>

namespace vesalius::segmentation {
namespace {

void requireSameSize(const Mask& a, const Mask& b) {
  if (a.geometry.size != b.geometry.size || a.values.size() != b.values.size())
    throw BadInput("", "masks of different sizes cannot be combined");
}

template <class Op>
Mask combine(const Mask& a, const Mask& b, Op op) {
  requireSameSize(a, b);
  Mask out(a.geometry);
  std::transform(a.values.begin(), a.values.end(), b.values.begin(), out.values.begin(),
                 [&](std::uint8_t x, std::uint8_t y) { return std::uint8_t(op(x != 0, y != 0)); });
  return out;
}

}  // namespace

Mask maskOf(const Grid<Label>& labels, Label id) {
  Mask out(labels.geometry);
  std::transform(labels.values.begin(), labels.values.end(), out.values.begin(),
                 [id](Label v) { return std::uint8_t(v == id); });
  return out;
}

Mask nonZeroMask(const Grid<Label>& labels) {
  Mask out(labels.geometry);
  std::transform(labels.values.begin(), labels.values.end(), out.values.begin(),
                 [](Label v) { return std::uint8_t(v != 0); });
  return out;
}

Mask thresholdMask(const Grid<float>& image, float lo, float hi) {
  Mask out(image.geometry);
  std::transform(image.values.begin(), image.values.end(), out.values.begin(),
                 [lo, hi](float v) { return std::uint8_t(v >= lo && v <= hi); });
  return out;
}

void paintMask(Grid<Label>& labels, const Mask& mask, Label id) {
  if (mask.values.size() != labels.values.size())
    throw BadInput("", "a mask and a label map of different sizes cannot be combined");
  for (std::size_t n = 0; n < mask.values.size(); ++n)
    if (mask.values[n]) labels.values[n] = id;
}

LabelMap labelMapOf(const Mask& mask, const LabelEntry& entry) {
  LabelMap map;
  map.labels = Grid<Label>(mask.geometry, 0);
  paintMask(map.labels, mask, entry.id);
  map.table.add(entry);
  return map;
}

Mask maskAnd(const Mask& a, const Mask& b) {
  return combine(a, b, [](bool x, bool y) { return x && y; });
}

Mask maskOr(const Mask& a, const Mask& b) {
  return combine(a, b, [](bool x, bool y) { return x || y; });
}

Mask maskAndNot(const Mask& a, const Mask& b) {
  return combine(a, b, [](bool x, bool y) { return x && !y; });
}

std::int64_t countVoxels(const Mask& mask) {
  return std::count_if(mask.values.begin(), mask.values.end(), [](std::uint8_t v) { return v != 0; });
}

double diceCoefficient(const Mask& a, const Mask& b) {
  const std::int64_t sizes = countVoxels(a) + countVoxels(b);
  if (sizes == 0) return 1.0;
  return 2.0 * double(countVoxels(maskAnd(a, b))) / double(sizes);
}

}  // namespace vesalius::segmentation
