// A surface cut down to some of its faces.
#pragma once

#include "vesalius/core/mesh.h"

#include <vector>

namespace vesalius {

// The faces of `mesh` whose entry in `keep` (#F) is true, in their order, and only the vertices they use
// (in their order, renumbered); UV, FUV and the vertex and face attributes follow.
TriMesh keepFaces(const TriMesh& mesh, const std::vector<bool>& keep);

}  // namespace vesalius
