// Embedding a surface in a template tet mesh and carrying it along with the tet mesh's deformation
// (Wang et al. 2021, §4.3: the textured liver surface embedded in the template tet mesh and "transformed with the
// shape deformation of the tet mesh").
//
// Each surface vertex is embedded in the rest tet mesh (core/tet_embedding.h) and carried to the fitted
// positions. A vertex a little outside the tet mesh keeps its offset from the boundary, deformed as its
// nearest tet is; an affine deformation of the tet mesh moves every vertex exactly.
#pragma once

#include "vesalius/core/mesh.h"

namespace vesalius::fit {

// surface: the mesh to carry, in the rest (template) space of the tet mesh. restV: #V by 3 rest positions,
// T: #T by 4 tets, fittedV: #V by 3 deformed positions (same numbering). Returns the surface with moved
// vertices; F, UV/FUV and all vertex and face attributes are kept. Throws BadInput if the tet mesh has
// no tets, UsageError if restV and fittedV differ in size.
TriMesh embedSurface(const TriMesh& surface, const MatrixX3d& restV, const MatrixX4i& T, const MatrixX3d& fittedV);

}  // namespace vesalius::fit
