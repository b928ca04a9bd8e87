// Copies between vtkPolyData and TriMesh (internal to meshing).
#pragma once

#include "vesalius/core/mesh.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

namespace vesalius::meshing::detail {

// Triangles of `poly` (other cells are ignored) and all its points.
TriMesh toTriMesh(vtkPolyData* poly);
vtkSmartPointer<vtkPolyData> toPolyData(const TriMesh& mesh);

}  // namespace vesalius::meshing::detail
