// The 3D view: the three slice planes as they lie in the world, marker spheres and overlay surfaces.
#pragma once

#include "marker_layer.h"
#include "slice_view.h"

#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include <Eigen/Core>

#include <array>
#include <memory>
#include <utility>

class vtkPolyData;
class vtkRenderWindow;

namespace vesalius::picker {

class View3D {
 public:
  View3D(const std::array<const SliceView*, 3>& slices, vtkRenderWindow* window,
         const std::array<double, 4>& viewport);
  ~View3D();

  vtkRenderer* renderer() const { return renderer_; }
  bool contains(int displayX, int displayY) const;
  // Whether its camera, markers or surfaces changed since the last call (not the slices it shows).
  bool takeChanged() { return std::exchange(changed_, false); }

  // All placed markers as spheres (previews dimmer); labels, `labelOffset` mm to the right, for the first 200 landmarks
  // and attachments (ICP markers come by the hundred and would hide the anatomy).
  void showMarkers(const MarkerSet& markers, double labelOffset);
  void addSurface(vtkPolyData* worldSurface, const Eigen::Vector3d& colour);
  void rotate(int dxPixels, int dyPixels);
  void zoom(double factor);
  void fitToScene();  // seen from the front (anterior), a little from the left and above, superior up

 private:
  vtkSmartPointer<vtkRenderer> renderer_;
  std::unique_ptr<MarkerLayer> markers_;
  bool changed_ = true;
};

}  // namespace vesalius::picker
