// Moving a closed surface along its normals until it encloses a given volume (internal to meshing).
#pragma once

#include "vesalius/core/mesh.h"

namespace vesalius::meshing::detail {

// Offsets every vertex of the outward-oriented closed surface `mesh` along its area-weighted normal by
// one uniform distance d = (targetVolume - volume) / area, twice (the second step corrects the change of
// area). Leaves the mesh untouched and returns false if |d| would exceed maxOffsetMm: the shape is then
// too thin for an offset to be harmless.
bool restoreVolume(TriMesh& mesh, double targetVolume, double maxOffsetMm);

}  // namespace vesalius::meshing::detail
