// Midpoint subdivision: every triangle split into four at its edges' midpoints. The new triangles lie on
// the old ones, so the surface's shape is unchanged while its vertices multiply by about four per level:
// a coarse mesh made fine enough to take another shape (patient/bone_onto_label.h).
#pragma once

#include "vesalius/core/mesh.h"

namespace vesalius::meshing {

// V #V by 3, F #F by 3 (any orientation, kept). An edge shared by several triangles is split once, so a
// closed surface stays closed. Vertex and face attributes and texture coordinates are dropped.
TriMesh subdivideMidpoints(const TriMesh& mesh, int levels = 1);

// The levels of subdivision that bring the mean edge length of `mesh` to at most maxEdge (0 if it is).
int midpointLevelsFor(const TriMesh& mesh, double maxEdge);

}  // namespace vesalius::meshing
