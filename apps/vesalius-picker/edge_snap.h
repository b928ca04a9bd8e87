// Snap (issue 5): a click on a boundary moves to the strongest edge within a few millimetres, so ICP
// markers sit on the organ's edge rather than where the hand landed. No VTK.
#pragma once

#include "vesalius/core/grid.h"

#include <Eigen/Core>

namespace vesalius::picker {

// The point of largest intensity change on the line through `world` along the scan's gradient there,
// within `radius` mm of `world`. The gradient is taken by central differences over radius / 2 (so that a
// click a little off the edge still sees it) and projected onto the plane with normal `planeNormal`
// (the slice's), so the snapped point stays on the slice. Returns `world` where the scan is flat or
// `world` is outside it.
Eigen::Vector3d snapToEdge(const Image& scan, const Eigen::Vector3d& world, const Eigen::Vector3d& planeNormal,
                           double radius);

}  // namespace vesalius::picker
