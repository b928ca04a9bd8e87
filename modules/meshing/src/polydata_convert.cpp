// Copies between vtkPolyData and TriMesh (polydata_convert.h).
#include "polydata_convert.h"

#include <vtkCellArray.h>
#include <vtkIdList.h>
#include <vtkPoints.h>

#include <vector>

namespace vesalius::meshing::detail {

TriMesh toTriMesh(vtkPolyData* poly) {
  TriMesh mesh;
  mesh.V.resize(poly->GetNumberOfPoints(), 3);
  for (vtkIdType p = 0; p < poly->GetNumberOfPoints(); ++p) {
    double x[3];
    poly->GetPoint(p, x);
    mesh.V.row(p) << x[0], x[1], x[2];
  }
  std::vector<Eigen::Vector3i> faces;
  faces.reserve(std::size_t(poly->GetNumberOfPolys()));
  auto ids = vtkSmartPointer<vtkIdList>::New();
  vtkCellArray* polys = poly->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(ids);)
    if (ids->GetNumberOfIds() == 3)
      faces.emplace_back(int(ids->GetId(0)), int(ids->GetId(1)), int(ids->GetId(2)));
  mesh.F.resize(Eigen::Index(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) mesh.F.row(Eigen::Index(f)) = faces[f].transpose();
  return mesh;
}

vtkSmartPointer<vtkPolyData> toPolyData(const TriMesh& mesh) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(mesh.V.rows());
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    points->SetPoint(v, mesh.V(v, 0), mesh.V(v, 1), mesh.V(v, 2));
  auto polys = vtkSmartPointer<vtkCellArray>::New();
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const vtkIdType tri[3] = {mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)};
    polys->InsertNextCell(3, tri);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(polys);
  return poly;
}

}  // namespace vesalius::meshing::detail
