#include "vesalius/meshing/decimate_surface.h"

#include "decimate_polydata.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/io/polydata.h"

#include <vtkDecimatePro.h>
#include <vtkQuadricDecimation.h>

namespace vesalius::meshing {

vtkSmartPointer<vtkPolyData> detail::decimatePolyData(vtkPolyData* surface, int targetFaces) {
  const vtkIdType faces = surface->GetNumberOfPolys();
  if (targetFaces <= 0 || faces <= targetFaces) return surface;
  const double reduction = 1.0 - double(targetFaces) / double(faces);
  auto quadric = vtkSmartPointer<vtkQuadricDecimation>::New();
  quadric->SetInputData(surface);
  quadric->SetTargetReduction(reduction);
  quadric->VolumePreservationOn();
  quadric->Update();
  const EdgeCounts edges = countEdges(io::fromPolyData(quadric->GetOutput(), "decimated surface").F);
  if (edges.boundary == 0 && edges.nonManifold == 0) return quadric->GetOutput();
  auto pro = vtkSmartPointer<vtkDecimatePro>::New();
  pro->SetInputData(surface);
  pro->SetTargetReduction(reduction);
  pro->PreserveTopologyOn();
  pro->SplittingOff();
  pro->BoundaryVertexDeletionOff();
  pro->Update();
  return pro->GetOutput();
}

TriMesh decimateSurface(const TriMesh& surface, int targetFaces) {
  if (targetFaces <= 0 || surface.F.rows() <= targetFaces) return surface;
  return io::fromPolyData(detail::decimatePolyData(io::toPolyData(surface), targetFaces), "decimated surface");
}

}  // namespace vesalius::meshing
