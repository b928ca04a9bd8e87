// The legend of a slice overlay (internal to viz).
#pragma once

#include "vesalius/core/label_map.h"
#include "vesalius/viz/rgb_image.h"

namespace vesalius::viz::detail {

// A colour swatch, the name and the volume in ml of every label present in `labels`, in id order, laid out
// in rows no wider than `maxWidth` pixels. Labels missing from the table are named "label_<id>" and get
// defaultLabelColor.
RgbImage renderLegend(const LabelMap& labels, int maxWidth);

// The colour a label is drawn with: the table's, else defaultLabelColor.
Rgb labelColor(const LabelTable& table, Label id);

}  // namespace vesalius::viz::detail
