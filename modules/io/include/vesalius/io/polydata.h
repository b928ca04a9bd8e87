// Copies between VTK polydata and TriMesh, for the modules that run VTK filters on meshes (meshing, viz).
// Point and cell arrays become vertex and face attributes and back, as in .vtp files (docs/formats.md).
#pragma once

#include "vesalius/core/mesh.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <string>

namespace vesalius::io {

// Polygons are fan-triangulated; vertices and lines are ignored. Throws BadInput naming `source` on
// triangle strips or a polygon of fewer than three vertices.
TriMesh fromPolyData(vtkPolyData* data, const std::string& source);

vtkSmartPointer<vtkPolyData> toPolyData(const TriMesh& mesh);

}  // namespace vesalius::io
