#include "picker_interactor_style.h"

#include "picker_controller.h"

#include <vtkObjectFactory.h>
#include <vtkRenderWindowInteractor.h>

namespace vesalius::picker {
namespace {

MouseEvent mouseEvent(vtkRenderWindowInteractor* interactor) {
  const int* position = interactor->GetEventPosition();
  return {position[0], position[1], interactor->GetShiftKey() != 0, interactor->GetControlKey() != 0};
}

}  // namespace

vtkStandardNewMacro(PickerInteractorStyle);

void PickerInteractorStyle::OnLeftButtonDown() { controller_->leftButtonDown(mouseEvent(Interactor)); }
void PickerInteractorStyle::OnLeftButtonUp() { controller_->leftButtonUp(mouseEvent(Interactor)); }
void PickerInteractorStyle::OnRightButtonDown() { controller_->rightButtonDown(mouseEvent(Interactor)); }
void PickerInteractorStyle::OnRightButtonUp() { controller_->buttonUp(); }
void PickerInteractorStyle::OnMiddleButtonDown() { controller_->middleButtonDown(mouseEvent(Interactor)); }
void PickerInteractorStyle::OnMiddleButtonUp() { controller_->buttonUp(); }
void PickerInteractorStyle::OnMouseMove() { controller_->mouseMove(mouseEvent(Interactor)); }
void PickerInteractorStyle::OnMouseWheelForward() { controller_->wheel(mouseEvent(Interactor), 1); }
void PickerInteractorStyle::OnMouseWheelBackward() { controller_->wheel(mouseEvent(Interactor), -1); }

void PickerInteractorStyle::OnKeyPress() {
  const char* keySym = Interactor->GetKeySym();
  controller_->keyPress(keySym ? keySym : "", mouseEvent(Interactor));
}

}  // namespace vesalius::picker
