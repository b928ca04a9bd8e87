// Decimation of a closed triangle surface to about a target face count: quadric error metrics
// (Garland and Heckbert, SIGGRAPH 1997; vtkQuadricDecimation) with volume preservation, for the better
// triangle shapes. Where that opens the surface (a mesh of many thin pieces, such as a CT's bone class), it
// is tried again at targets 10 % … 100 % larger (where a collapse tears depends on the target; the
// smaller ones only where twice the target holds), and only then replaced by vtkDecimatePro with the
// topology kept, which stops short of the target where it cannot reach it safely. Templates with fine
// surfaces need this before TetGen, which keeps every input triangle (a 30k-triangle muscle gives 150k
// tets whatever the target).
#pragma once

#include "vesalius/core/mesh.h"

namespace vesalius::meshing {

// surface: closed, #V by 3 and #F by 3. Returns it unchanged when it has no more than targetFaces
// triangles (or targetFaces <= 0). Face attributes are not carried.
TriMesh decimateSurface(const TriMesh& surface, int targetFaces);

}  // namespace vesalius::meshing
