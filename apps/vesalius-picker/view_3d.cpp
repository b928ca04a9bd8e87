#include "view_3d.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkImageActor.h>
#include <vtkImageAlgorithm.h>
#include <vtkImageMapper3D.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

namespace vesalius::picker {
namespace {

constexpr int kMaxLabels = 200;  // beyond that the 3D view would be all text, and slow to draw

}  // namespace

View3D::View3D(const std::array<const SliceView*, 3>& slices, vtkRenderWindow* window,
               const std::array<double, 4>& viewport) {
  renderer_ = vtkSmartPointer<vtkRenderer>::New();
  renderer_->SetViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  renderer_->SetBackground(0.1, 0.1, 0.15);
  window->AddRenderer(renderer_);
  for (const SliceView* slice : slices) {
    auto plane = vtkSmartPointer<vtkImageActor>::New();
    plane->GetMapper()->SetInputConnection(slice->colouredSlice()->GetOutputPort());
    plane->SetUserMatrix(slice->planeToWorld());  // the same matrix object: follows the slice
    renderer_->AddActor(plane);
  }
  markers_ = std::make_unique<MarkerLayer>(renderer_, GlyphShape::ScreenSphere);
}

View3D::~View3D() = default;

bool View3D::contains(int displayX, int displayY) const {
  return renderer_->IsInViewport(displayX, displayY) != 0;
}

void View3D::showMarkers(const MarkerSet& markers, double labelOffset) {
  changed_ = true;
  std::vector<MarkerGlyph> glyphs;
  int labelled = 0;
  for (const Marker& m : markers.markers) {
    if (!hasPosition(m.status) || !m.visible) continue;
    const bool label = m.kind != MarkerKind::IcpMarker && labelled < kMaxLabels;
    labelled += label;
    glyphs.push_back({m.position, m.kind, m.status == MarkerStatus::Preview, label ? m.label : std::string()});
  }
  markers_->show(glyphs, labelOffset / 1.5);
}

void View3D::addSurface(vtkPolyData* worldSurface, const Eigen::Vector3d& colour) {
  changed_ = true;
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputData(worldSurface);
  mapper->ScalarVisibilityOff();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(colour.x(), colour.y(), colour.z());
  actor->GetProperty()->SetOpacity(0.5);
  renderer_->AddActor(actor);
}

void View3D::rotate(int dxPixels, int dyPixels) {
  changed_ = true;
  vtkCamera* camera = renderer_->GetActiveCamera();
  camera->Azimuth(-0.5 * dxPixels);
  camera->Elevation(-0.5 * dyPixels);
  camera->OrthogonalizeViewUp();
  renderer_->ResetCameraClippingRange();
}

void View3D::zoom(double factor) {
  changed_ = true;
  renderer_->GetActiveCamera()->Dolly(factor);
  renderer_->ResetCameraClippingRange();
}

void View3D::fitToScene() {
  changed_ = true;
  vtkCamera* camera = renderer_->GetActiveCamera();
  camera->SetFocalPoint(0, 0, 0);
  camera->SetPosition(0, -1, 0);  // LPS: -P is anterior
  camera->SetViewUp(0, 0, 1);
  camera->Azimuth(30);  // a little from the patient's left and above, so no slice is seen edge-on
  camera->Elevation(20);
  camera->OrthogonalizeViewUp();
  renderer_->ResetCamera();
}

}  // namespace vesalius::picker
