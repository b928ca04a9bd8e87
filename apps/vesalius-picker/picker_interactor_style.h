// Hands the interactor's mouse and key events to the PickerController, replacing VTK's default
// bindings (no 'q' to quit, no 'w' wireframe, no camera moves the controller did not ask for).
#pragma once

#include <vtkInteractorStyle.h>

namespace vesalius::picker {

class PickerController;

class PickerInteractorStyle : public vtkInteractorStyle {
 public:
  static PickerInteractorStyle* New();
  vtkTypeMacro(PickerInteractorStyle, vtkInteractorStyle);

  void setController(PickerController* controller) { controller_ = controller; }

  void OnLeftButtonDown() override;
  void OnLeftButtonUp() override;
  void OnRightButtonDown() override;
  void OnRightButtonUp() override;
  void OnMiddleButtonDown() override;
  void OnMiddleButtonUp() override;
  void OnMouseMove() override;
  void OnMouseWheelForward() override;
  void OnMouseWheelBackward() override;
  void OnKeyPress() override;
  void OnChar() override {}  // every key is handled in OnKeyPress

 private:
  PickerController* controller_ = nullptr;
};

}  // namespace vesalius::picker
