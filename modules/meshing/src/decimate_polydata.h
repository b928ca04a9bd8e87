// The VTK side of decimate_surface.h, for callers that already hold vtkPolyData.
#pragma once

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

namespace vesalius::meshing::detail {

vtkSmartPointer<vtkPolyData> decimatePolyData(vtkPolyData* surface, int targetFaces);

}  // namespace vesalius::meshing::detail
