// Points spread evenly over a label's boundary within its scan: the stand-ins for a radiologist's ICP
// markers that `vesalius markers sample` writes (Wang et al. 2021, §3.1, §4.1.1: points on the organ's boundary),
// and the points `vesalius markers suggest` places a template on.
//
// The boundary is the surface `vesalius surface` makes of the label (labelSurfaces, default options) less
// the cap that closes a label cut by the edge of the scan (withinScan): that cap is the scan's edge, not
// the organ's, and no radiologist would put a marker on it. The points are spreadSurfacePoints' farthest-
// point sampling on it.
#pragma once

#include "vesalius/core/label_map.h"
#include "vesalius/core/mesh.h"
#include "vesalius/core/progress.h"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace vesalius::meshing {

struct LabelBoundaryPointsOptions {
  int count = 100;         // points to spread
  std::uint64_t seed = 1;  // the same seed gives the same points on every platform
};

struct LabelBoundaryPoints {
  bool hasVoxels = false;    // false: the label has no voxel, and nothing else is set
  MatrixX3d points;          // #count by 3, LPS mm, in the order chosen; 0 rows if no boundary lies within the scan
  double area = 0;           // mm², of the boundary within the scan
  double scanEdgeArea = 0;   // mm², of the cap where the scan's edge cuts the label
  std::vector<std::pair<std::string, double>> stageSeconds;  // "surface", then "spread markers" if spread
};

// map: the label map, in LPS mm; id: the label. progress (may be null) shows the surfacing. Throws what
// spreadSurfacePoints throws for a bad count (UsageError).
LabelBoundaryPoints labelBoundaryPoints(const LabelMap& map, Label id, const LabelBoundaryPointsOptions& options = {},
                                        Progress* progress = nullptr);

}  // namespace vesalius::meshing
