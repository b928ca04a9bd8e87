// The surface of a label inside its bounding box (internal to meshing).
#pragma once

#include "vesalius/core/label_boxes.h"
#include "vesalius/core/label_map.h"
#include "vesalius/core/mesh.h"
#include "vesalius/meshing/label_surface.h"

namespace vesalius::meshing::detail {

// The surface of label `id`, whose voxels all lie in `box` (box.voxels > 0); see labelSurface.
// Throws UsageError on bad options.
TriMesh labelSurfaceInBox(const LabelMap& labels, Label id, const LabelBox& box, const SurfaceOptions& options);

}  // namespace vesalius::meshing::detail
