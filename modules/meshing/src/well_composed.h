// Making a multi-label voxel map well-composed for each non-zero label (internal to meshing; see
// shared_label_surfaces.h, step 1).
#pragma once

#include "vesalius/core/grid.h"
#include "vesalius/core/label_map.h"

namespace vesalius::meshing::detail {

// Repairs `labels` in place until no non-zero label meets itself across a voxel edge or corner only, and
// no 2x2x2 block leaves a label all but two opposite voxels. Voxels on the grid's outer layer must be 0
// and stay 0. Returns the number of voxels relabelled; throws NumericalFailure if repairs do not settle.
long makeWellComposed(Grid<Label>& labels);

}  // namespace vesalius::meshing::detail
