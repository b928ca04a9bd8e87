#include "vtk_window_support.h"

#include "vesalius/core/atomic_file.h"
#include "vesalius/core/error.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkInteractorEventRecorder.h>
#include <vtkPNGWriter.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkSmartPointer.h>
#include <vtkWindowToImageFilter.h>

#include <filesystem>

namespace vesalius::gui {

void endLoopOnWindowClose(vtkRenderWindowInteractor* interactor) {
  auto endLoop = vtkSmartPointer<vtkCallbackCommand>::New();
  endLoop->SetCallback([](vtkObject* caller, unsigned long, void*, void*) {
    static_cast<vtkRenderWindowInteractor*>(caller)->SetDone(true);
  });
  interactor->AddObserver(vtkCommand::ExitEvent, endLoop);
}

void writeScreenshot(vtkRenderWindow* window, const std::string& path) {
  auto capture = vtkSmartPointer<vtkWindowToImageFilter>::New();
  capture->SetInput(window);
  capture->ReadFrontBufferOff();
  capture->ShouldRerenderOff();  // what the last render left, views skipped since included
  capture->Update();
  writeAtomically(path, WriteOptions{true}, [&](const std::string& temporaryPath) {
    auto png = vtkSmartPointer<vtkPNGWriter>::New();
    png->SetInputConnection(capture->GetOutputPort());
    png->SetFileName(temporaryPath.c_str());
    png->Write();
    std::error_code ec;
    if (png->GetErrorCode() != 0 || std::filesystem::file_size(temporaryPath, ec) == 0 || ec)
      throw BadInput(path, "cannot write the screenshot");
  });
}

void runEventLoop(vtkRenderWindow* window, vtkRenderWindowInteractor* interactor, const EventScript& script) {
  auto recorder = vtkSmartPointer<vtkInteractorEventRecorder>::New();
  if (!script.record.empty()) {
    recorder->SetInteractor(interactor);
    recorder->SetFileName(script.record.c_str());
    recorder->On();
    recorder->Record();
  }
  if (!script.play.empty()) {
    if (!std::filesystem::is_regular_file(script.play)) throw BadInput(script.play, "cannot open the events file");
    auto player = vtkSmartPointer<vtkInteractorEventRecorder>::New();
    player->SetInteractor(interactor);
    player->SetFileName(script.play.c_str());
    player->Play();
    player->SetInteractor(nullptr);
  }
  if (!script.screenshot.empty()) writeScreenshot(window, script.screenshot);
  if (script.play.empty() || !script.exitAfterPlay) interactor->Start();
  if (!script.record.empty()) recorder->Stop();
}

}  // namespace vesalius::gui
