#include "anatomy_actors.h"

#include "tissue_colour.h"

#include "vesalius/core/error.h"
#include "vesalius/io/polydata.h"

#include <vtkDataArray.h>
#include <vtkPoints.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>

namespace vesalius::poser {

AnatomyActors::AnatomyActors(const std::vector<TriMesh>& meshes, const std::vector<std::string>& names,
                             vtkRenderer* renderer, const AnatomyActorsOptions& options) {
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    TriMesh faces;  // points and faces only: attributes would be copied again every frame for nothing
    faces.V = meshes[m].V;
    faces.F = meshes[m].F;
    surfaces_.push_back(io::toPolyData(faces));
    // Smooth shading; the normals follow the points, which it passes through unsplit and unchanged.
    auto normals = vtkSmartPointer<vtkPolyDataNormals>::New();
    normals->SetInputData(surfaces_.back());
    normals->SplittingOff();
    normals->ConsistencyOff();
    auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
    mapper->SetInputConnection(normals->GetOutputPort());
    mapper->ScalarVisibilityOff();
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    const bool isSkin = names[m] == options.skinName;
    const Eigen::Vector3d colour = isSkin ? options.skinColour : tissueColour(names[m]);
    actor->GetProperty()->SetColor(colour.x(), colour.y(), colour.z());
    if (isSkin) {
      actor->GetProperty()->SetOpacity(options.skinOpacity);
      actor->GetProperty()->SetSpecular(0);  // highlights on the skin would hide the tissues below
    }
    renderer->AddActor(actor);
    actors_.push_back(actor);
  }
}

void AnatomyActors::setPoints(const std::vector<MatrixX3d>& carried) {
  if (carried.size() != surfaces_.size()) throw UsageError("setPoints: one point matrix per mesh");
  for (std::size_t m = 0; m < surfaces_.size(); ++m) {
    vtkDataArray* points = surfaces_[m]->GetPoints()->GetData();
    if (points->GetNumberOfTuples() != carried[m].rows()) throw UsageError("setPoints: point count changed");
    for (Eigen::Index p = 0; p < carried[m].rows(); ++p)
      points->SetTuple3(p, carried[m](p, 0), carried[m](p, 1), carried[m](p, 2));
    surfaces_[m]->GetPoints()->Modified();
  }
}

MatrixX3d AnatomyActors::shownPoints(int m) const {
  vtkMapper* mapper = actors_[m]->GetMapper();
  mapper->Update();
  vtkPoints* points = vtkPolyData::SafeDownCast(mapper->GetInput())->GetPoints();
  MatrixX3d P(points->GetNumberOfPoints(), 3);
  for (Eigen::Index p = 0; p < P.rows(); ++p) {
    double xyz[3];
    points->GetPoint(p, xyz);
    P.row(p) << xyz[0], xyz[1], xyz[2];
  }
  return P;
}

}  // namespace vesalius::poser
