// The signed distance to a closed body surface on which rules R5 and R6 (seed 000 §3: tissue inside the
// skin) are measured, shared by `transfer` (its report and its bone maps) and `reference full-body` (its
// bones moved inside the skin), so that both count "inside" alike.
#pragma once

#include "vesalius/core/grid.h"
#include "vesalius/core/mesh.h"

namespace vesalius::cli {

// Exact within this distance of the surface, clamped to ±it beyond (mm).
constexpr double kDistanceBandMm = 6.0;

// Signed distance (mm, negative inside) to `body` (closed, #V by 3 mm LPS) on a 2 mm grid covering it.
// Throws BadInput as meshing::meshSignedDistance does.
Grid<float> bodySignedDistance(const TriMesh& body);

}  // namespace vesalius::cli
