// The poser's keys on top of VTK's trackball camera (drag to turn, wheel to zoom, middle drag to pan):
//   space        play / pause          Left, Right   step a frame back / forward (wrapping)
//   l, d, c      skin by LBS, DQS, CoR  r             view the body from the front again
//   s            save the shown pose (--save-dir)    q, Escape      quit
// VTK's own key bindings (w wireframe, e exit, p pick, ...) are off.
#pragma once

#include <vtkInteractorStyleTrackballCamera.h>

#include <string>

namespace vesalius::poser {

class PoserController;

class PoserInteractorStyle : public vtkInteractorStyleTrackballCamera {
 public:
  static PoserInteractorStyle* New();
  vtkTypeMacro(PoserInteractorStyle, vtkInteractorStyleTrackballCamera);

  void setController(PoserController* controller) { controller_ = controller; }

  void OnKeyPress() override;
  void OnChar() override {}  // every key is handled in OnKeyPress

 private:
  void handleKey(const std::string& key);

  PoserController* controller_ = nullptr;
};

}  // namespace vesalius::poser
