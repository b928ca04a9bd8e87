// The poser's window: one 3D view with a frame slider across the bottom (vtkSliderWidget) and a status
// line at the top left (method, frame, skinning time). What the slider and keys do is the controller's.
#pragma once

#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkSliderWidget.h>
#include <vtkSmartPointer.h>
#include <vtkTextActor.h>

#include <functional>
#include <string>

namespace vesalius::poser {

class PoserWindow {
 public:
  // frameCount >= 1: the slider runs over frames 0 .. frameCount - 1.
  PoserWindow(int width, int height, int frameCount);

  vtkRenderer* renderer() const { return renderer_; }
  vtkRenderWindow* renderWindow() const { return window_; }
  vtkRenderWindowInteractor* interactor() const { return interactor_; }

  // Calls `moved` with the slider's frame (rounded) while it is dragged. Call after the interactor has a
  // style; the widget then takes its mouse events first.
  void enableSlider(std::function<void(int)> moved);
  void setSliderFrame(int frame);
  void setStatus(const std::string& text);
  // Looks at the shown actors from the front (anterior, LPS -y) with superior (+z) up.
  void viewFromFront();
  void render() { window_->Render(); }
  // The window as last rendered, as PNG (atomically).

 private:
  vtkSmartPointer<vtkRenderWindow> window_;
  vtkSmartPointer<vtkRenderer> renderer_;
  vtkSmartPointer<vtkRenderWindowInteractor> interactor_;
  vtkSmartPointer<vtkSliderWidget> slider_;
  vtkSmartPointer<vtkTextActor> status_;
  std::function<void(int)> moved_;
};

}  // namespace vesalius::poser
