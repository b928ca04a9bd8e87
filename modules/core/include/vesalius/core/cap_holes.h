// A surface's holes closed by fans: each loop of boundary edges gets a vertex at its centroid and one
// triangle per edge to it. For a surface cut by a box (a reference bone kept only beyond a scan), whose
// holes lie along the cut: closed again, it has an inside that winding numbers and voxelizations can tell
// (meshing/winding_number.h). A loop far from planar gives a cap that can cross the surface near it.
#pragma once

#include "vesalius/core/mesh.h"

namespace vesalius {

// mesh: #V by 3, #F by 3, consistently oriented. Returns the mesh with one vertex appended per boundary
// loop (at the loop's vertex centroid) and, per boundary edge (a, b) of a face, the triangle (b, a, centre)
// appended; a closed mesh is returned as it is. The centre takes the vertex attributes of its loop's first
// vertex, and a cap triangle the face attributes and texture indices (FUV) of the face across its edge.
TriMesh capHoles(const TriMesh& mesh);

}  // namespace vesalius
