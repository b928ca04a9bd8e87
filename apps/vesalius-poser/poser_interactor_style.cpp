#include "poser_interactor_style.h"

#include "poser_controller.h"

#include <vtkObjectFactory.h>
#include <vtkRenderWindowInteractor.h>

#include <exception>
#include <iostream>
#include <string>

namespace vesalius::poser {

vtkStandardNewMacro(PoserInteractorStyle);

void PoserInteractorStyle::OnKeyPress() {
  const char* symbol = Interactor->GetKeySym();
  const std::string key = symbol ? symbol : "";
  try {
    handleKey(key);
  } catch (const std::exception& e) {  // a save that fails must not take the session down with it
    std::cerr << "vesalius-poser: " << e.what() << '\n';
  }
}

void PoserInteractorStyle::handleKey(const std::string& key) {
  if (key == "space") controller_->togglePlay();
  else if (key == "Left") controller_->step(-1);
  else if (key == "Right") controller_->step(1);
  else if (key == "l") controller_->setMethod("lbs");
  else if (key == "d") controller_->setMethod("dqs");
  else if (key == "c") controller_->setMethod("cor");
  else if (key == "r") controller_->resetCamera();
  else if (key == "s") controller_->saveShown();
  // TerminateApp() inside Start() crashes VTK 9.1 (docs/design.md); ending the loop does not.
  else if (key == "q" || key == "Escape") Interactor->SetDone(true);
}

}  // namespace vesalius::poser
