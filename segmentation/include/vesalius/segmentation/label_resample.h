// Coarser label maps under a size cap, for meshing a whole body (Sujar et al. 2018, §3.2: the voxel size is chosen
// so that the body image stays under 250x700x120 voxels).
#pragma once

#include "vesalius/core/label_map.h"

namespace vesalius::segmentation {

// `geometry` with the spacing of each index axis grown just enough that the axis has at most
// maxSizeLps(d) voxels, d being the LPS axis (0 L, 1 P, 2 S) the index axis points most along. The grid
// covers the same box (its outer voxel faces stay where they are); direction
// is kept. Axes already under their cap are unchanged. UsageError if a cap is below 1.
GridGeometry cappedGeometry(const GridGeometry& geometry, const Eigen::Vector3i& maxSizeLps);

// The labels of `map` on the grid `target` by nearest neighbour (0 outside `map`), with map's table.
LabelMap resampleLabels(const LabelMap& map, const GridGeometry& target);

}  // namespace vesalius::segmentation
