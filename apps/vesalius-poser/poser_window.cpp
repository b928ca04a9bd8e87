#include "poser_window.h"

#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkProperty2D.h>
#include <vtkSliderRepresentation2D.h>
#include <vtkTextProperty.h>

#include <cmath>

namespace vesalius::poser {

PoserWindow::PoserWindow(int width, int height, int frameCount)
    : window_(vtkSmartPointer<vtkRenderWindow>::New()),
      renderer_(vtkSmartPointer<vtkRenderer>::New()),
      interactor_(vtkSmartPointer<vtkRenderWindowInteractor>::New()),
      slider_(vtkSmartPointer<vtkSliderWidget>::New()),
      status_(vtkSmartPointer<vtkTextActor>::New()) {
  window_->SetSize(width, height);
  window_->SetWindowName("vesalius-poser");
  window_->AddRenderer(renderer_);
  renderer_->SetBackground(0.09, 0.09, 0.11);
  interactor_->SetRenderWindow(window_);

  auto track = vtkSmartPointer<vtkSliderRepresentation2D>::New();
  track->SetMinimumValue(0);
  track->SetMaximumValue(std::max(frameCount - 1, 1));  // VTK needs max > min; one frame shows at 0
  track->SetValue(0);
  track->SetLabelFormat("%.0f");
  track->GetPoint1Coordinate()->SetCoordinateSystemToNormalizedDisplay();
  track->GetPoint1Coordinate()->SetValue(0.05, 0.06);
  track->GetPoint2Coordinate()->SetCoordinateSystemToNormalizedDisplay();
  track->GetPoint2Coordinate()->SetValue(0.95, 0.06);
  track->SetSliderLength(0.015);
  track->SetTubeWidth(0.006);
  track->GetSliderProperty()->SetColor(0.95, 0.75, 0.3);
  track->GetTubeProperty()->SetColor(0.6, 0.6, 0.6);
  slider_->SetRepresentation(track);
  slider_->SetAnimationModeToJump();

  status_->GetTextProperty()->SetFontSize(16);
  status_->GetTextProperty()->SetColor(0.95, 0.95, 0.95);
  status_->GetPositionCoordinate()->SetCoordinateSystemToNormalizedDisplay();
  status_->GetPositionCoordinate()->SetValue(0.02, 0.95);
  renderer_->AddViewProp(status_);
}

void PoserWindow::enableSlider(std::function<void(int)> moved) {
  moved_ = std::move(moved);
  auto observer = vtkSmartPointer<vtkCallbackCommand>::New();
  observer->SetClientData(this);
  observer->SetCallback([](vtkObject* caller, unsigned long, void* self, void*) {
    auto* widget = static_cast<vtkSliderWidget*>(caller);
    const double value = static_cast<vtkSliderRepresentation*>(widget->GetRepresentation())->GetValue();
    static_cast<PoserWindow*>(self)->moved_(int(std::lround(value)));
  });
  slider_->AddObserver(vtkCommand::InteractionEvent, observer);
  slider_->SetInteractor(interactor_);
  slider_->EnabledOn();
}

void PoserWindow::setSliderFrame(int frame) {
  static_cast<vtkSliderRepresentation*>(slider_->GetRepresentation())->SetValue(frame);
}

void PoserWindow::setStatus(const std::string& text) { status_->SetInput(text.c_str()); }

void PoserWindow::viewFromFront() {
  vtkCamera* camera = renderer_->GetActiveCamera();
  camera->SetFocalPoint(0, 0, 0);
  camera->SetPosition(0, -1, 0);
  camera->SetViewUp(0, 0, 1);
  renderer_->ResetCamera();
}

}  // namespace vesalius::poser
