// The decimation of label surfaces (label_surface.h): vtkQuadricDecimation (Garland and Heckbert 1997) with
// volume preservation; where that opens the surface (a label of many thin pieces), it is tried again at
// targets 10 % … 100 % larger (the smaller ones only where twice the target stays closed), and only then
// replaced by vtkDecimatePro with the topology kept, which stops short of the target where it cannot reach
// it safely. decimate_surface.h's edge collapses reach the target and keep surfaces apart; label surfaces
// keep this decimation because the rig's body and its posed skin, and the skin registration's targets, are
// measured on its triangles (docs/methods/tetrahedral-meshes.md).
#pragma once

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

namespace vesalius::meshing::detail {

vtkSmartPointer<vtkPolyData> decimatePolyData(vtkPolyData* surface, int targetFaces);

}  // namespace vesalius::meshing::detail
