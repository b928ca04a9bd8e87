// Measures of closed triangle surfaces, used to check what labelSurface makes.
#pragma once

#include "vesalius/core/mesh.h"

#include <cstdint>

namespace vesalius::meshing {

// Edges used by exactly one face (0 for a closed surface).
std::int64_t boundaryEdgeCount(const TriMesh& mesh);
// Edges used by more than two faces.
std::int64_t nonManifoldEdgeCount(const TriMesh& mesh);
// Connected components of faces sharing an edge.
int faceComponentCount(const TriMesh& mesh);
// Signed enclosed volume (mm^3 for mm coordinates) by the divergence theorem: the sum over faces of
// v0 · (v1 × v2) / 6. Positive for a closed surface oriented outward; cavities count negative.
double enclosedVolume(const TriMesh& mesh);

}  // namespace vesalius::meshing
