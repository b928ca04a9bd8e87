// Sizes and colours shared by the parts of a slice overlay picture (internal to viz).
#pragma once

#include "vesalius/viz/rgb_image.h"

namespace vesalius::viz::detail {

inline constexpr int kMargin = 12, kGap = 12;                            // pixels
inline constexpr int kTitleSize = 16, kEdgeSize = 13, kLegendSize = 15;  // font sizes in pixels
inline constexpr Rgb kBackground{{24, 24, 28}}, kText{{235, 235, 235}}, kEdgeText{{250, 210, 90}};

}  // namespace vesalius::viz::detail
