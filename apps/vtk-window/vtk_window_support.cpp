#include "vtk_window_support.h"

#include "vesalius/core/atomic_file.h"
#include "vesalius/core/error.h"
#include "vesalius/viz/rgb_image.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkInteractorEventRecorder.h>
#include <vtkImageData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkSmartPointer.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cstdint>
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
  capture->SetInputBufferTypeToRGB();
  capture->ReadFrontBufferOff();
  capture->ShouldRerenderOff();  // what the last render left, views skipped since included
  capture->Update();
  // Written as the other pictures are (viz::writePng), which reports a full disk in one line.
  vtkImageData* image = capture->GetOutput();
  const int* size = image->GetDimensions();
  viz::RgbImage picture;
  picture.width = size[0];
  picture.height = size[1];
  picture.pixels.resize(std::size_t(size[0]) * std::size_t(size[1]) * 3);
  const auto* rows = static_cast<const std::uint8_t*>(image->GetScalarPointer());
  const std::size_t rowBytes = std::size_t(size[0]) * 3;
  for (int y = 0; y < size[1]; ++y)  // VTK's row 0 is the bottom one
    std::copy_n(rows + rowBytes * std::size_t(size[1] - 1 - y), rowBytes,
                picture.pixels.begin() + std::ptrdiff_t(rowBytes * std::size_t(y)));
  viz::writePng(path, picture, WriteOptions{true});
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
