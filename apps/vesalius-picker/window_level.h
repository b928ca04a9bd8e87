// Window/level of the slice views: presets and the MRI "auto" range from percentiles. No VTK.
#pragma once

#include "vesalius/core/grid.h"

namespace vesalius::picker {

struct WindowLevel {
  double window = 400, level = 40;  // displayed range [level - window/2, level + window/2]
};

// 3D Slicer's CT presets (Hounsfield units).
inline constexpr WindowLevel kCtBone{1000, 400};
inline constexpr WindowLevel kCtSoftTissue{350, 40};

// The 1st to 99th percentile of the scan's values, from a sample of at most ~1M voxels: the range an
// MRI (arbitrary units) is best read in. A constant scan gives window 1.
WindowLevel percentileWindowLevel(const Image& scan);

// A drag of (dx, dy) pixels: right widens the window, up raises the level, both relative to the window,
// so the same drag feels the same on CT and MRI. The window stays positive.
WindowLevel dragWindowLevel(const WindowLevel& start, double dx, double dy);

}  // namespace vesalius::picker
