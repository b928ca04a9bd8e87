// Embedding a surface in a template tet mesh and carrying it along with the tet mesh's deformation
// (seed 002 §4.3: the textured liver surface embedded in the template tet mesh and "transformed with the
// shape deformation of the tet mesh").
//
// Each surface vertex is located in the rest tet mesh (TetLocator::locateOrNearest) and moved with the
// barycentric weights of its tet to the fitted positions. A vertex outside the tet mesh (a surface a
// little larger than the mesh's boundary) takes the affine map of its nearest tet, i.e. its unclamped
// barycentric weights in that tet, so it keeps its offset from the boundary instead of being snapped onto
// it; the offset then deforms as that tet does, so where a fit distorts the boundary tets it is stretched
// with them. Inside a tet the map is the tet's affine map too, so an affine deformation of the tet mesh
// moves every vertex exactly.
#pragma once

#include "vesalius/core/mesh.h"

namespace vesalius::fit {

// surface: the mesh to carry, in the rest (template) space of the tet mesh. restV: #V by 3 rest positions,
// T: #T by 4 tets, fittedV: #V by 3 deformed positions (same numbering). Returns the surface with moved
// vertices; F, UV/FUV and all vertex and face attributes are kept. Throws BadInput if the tet mesh has
// no tets, UsageError if restV and fittedV differ in size.
TriMesh embedSurface(const TriMesh& surface, const MatrixX3d& restV, const MatrixX4i& T, const MatrixX3d& fittedV);

}  // namespace vesalius::fit
