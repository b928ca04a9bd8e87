#include "picker_render_window.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLState.h>
#include <vtkXOpenGLRenderWindow.h>
#include <vtk_glew.h>

namespace vesalius::picker {
namespace {

class PickerRenderWindow : public vtkXOpenGLRenderWindow {
 public:
  static PickerRenderWindow* New();
  vtkTypeMacro(PickerRenderWindow, vtkXOpenGLRenderWindow);

 protected:
  PickerRenderWindow() = default;
  void BlitDisplayFramebuffersToHardware() override;
};

vtkStandardNewMacro(PickerRenderWindow);

void PickerRenderWindow::BlitDisplayFramebuffersToHardware() {
  vtkOpenGLState* state = this->GetState();
  state->PushFramebufferBindings();
  state->vtkglViewport(0, 0, this->Size[0], this->Size[1]);
  state->vtkglScissor(0, 0, this->Size[0], this->Size[1]);
  state->vtkglBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  state->vtkglDrawBuffer(this->DoubleBuffer ? GL_BACK_LEFT : GL_FRONT_LEFT);
  this->DisplayFramebuffer->Bind(GL_READ_FRAMEBUFFER);
  this->DisplayFramebuffer->ActivateReadBuffer(0);
  state->vtkglBlitFramebuffer(0, 0, this->Size[0], this->Size[1], 0, 0, this->Size[0], this->Size[1],
                              GL_COLOR_BUFFER_BIT, GL_NEAREST);
  state->PopFramebufferBindings();
}

}  // namespace

vtkSmartPointer<vtkRenderWindow> newPickerRenderWindow() { return vtkSmartPointer<PickerRenderWindow>::New(); }

}  // namespace vesalius::picker
