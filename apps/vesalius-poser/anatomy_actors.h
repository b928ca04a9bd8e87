// The meshes of a posed anatomy as VTK actors: the skin translucent over the internal tissues (bones,
// muscles, organs) drawn opaque in their colours (tissue_colour.h), as the viewer of issue 6 shows them.
// Posing a frame only replaces the points of the existing actors; faces, colours and actors stay.
#pragma once

#include "vesalius/core/mesh.h"

#include <vtkActor.h>
#include <vtkPolyData.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include <string>
#include <vector>

namespace vesalius::poser {

struct AnatomyActorsOptions {
  std::string skinName = "skin";  // the mesh stem drawn translucent
  double skinOpacity = 0.3;
  Eigen::Vector3d skinColour{0.90, 0.75, 0.63};
};

class AnatomyActors {
 public:
  // meshes: at rest; names: their stems, in the same order. Adds one actor per mesh to `renderer`.
  AnatomyActors(const std::vector<TriMesh>& meshes, const std::vector<std::string>& names, vtkRenderer* renderer,
                const AnatomyActorsOptions& options = {});

  // carried: per mesh, its #P by 3 posed vertices (as many as at rest).
  void setPoints(const std::vector<MatrixX3d>& carried);

  // The #P by 3 points mesh m is drawn with now (read back from its actor's mapper input).
  MatrixX3d shownPoints(int m) const;
  vtkActor* actor(int m) const { return actors_[m]; }
  int size() const { return int(actors_.size()); }

 private:
  std::vector<vtkSmartPointer<vtkPolyData>> surfaces_;
  std::vector<vtkSmartPointer<vtkActor>> actors_;
};

}  // namespace vesalius::poser
