#include "poser_controller.h"

#include "vesalius/core/error.h"
#include "vesalius/io/mesh_io.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

namespace vesalius::poser {

namespace fs = std::filesystem;

PoserController::PoserController(const posing::RigPoser& session, const rigging::RetargetedMotion& motion,
                                 AnatomyActors& actors, PoserWindow& window, const PoserOptions& options)
    : session_(session), motion_(motion), actors_(actors), window_(window), options_(options),
      frame_(options.frame), method_(options.method) {
  auto onTimer = vtkSmartPointer<vtkCallbackCommand>::New();
  onTimer->SetClientData(this);
  onTimer->SetCallback([](vtkObject*, unsigned long, void* self, void* timerId) {
    auto* controller = static_cast<PoserController*>(self);
    if (timerId && *static_cast<int*>(timerId) == controller->timer_) controller->tick();
  });
  window_.interactor()->AddObserver(vtkCommand::TimerEvent, onTimer);
}

void PoserController::showFrame(int frame) {
  const int count = motion_.frameCount();
  frame_ = ((frame % count) + count) % count;
  const auto start = std::chrono::steady_clock::now();
  const std::vector<Eigen::Isometry3d> world = motion_.pose(frame_);
  session_.skinTets(world, method_, tets_);
  session_.carry(tets_, world, carried_);
  skinningMs_ = 1000 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  actors_.setPoints(carried_);
  window_.setSliderFrame(frame_);
  updateStatus();
  window_.render();
}

void PoserController::setMethod(const std::string& method) {
  const std::string previous = method_;
  method_ = method;
  try {
    showFrame(frame_);
  } catch (const Error& e) {
    method_ = previous;
    showFrame(frame_);
    updateStatus(e.what());
    window_.render();
  }
}

void PoserController::togglePlay() {
  vtkRenderWindowInteractor* interactor = window_.interactor();
  if (playing()) {
    interactor->DestroyTimer(timer_);
    timer_ = -1;
  } else {
    timer_ = interactor->CreateRepeatingTimer(unsigned(std::max(1.0, std::round(1000 / options_.fps))));
  }
  updateStatus();
  window_.render();
}

void PoserController::saveShown() const {
  if (options_.saveDir.empty()) {
    std::cerr << "vesalius-poser: s saves the shown pose only with --save-dir\n";
    return;
  }
  char name[48];
  std::snprintf(name, sizeof name, "frame_%05d_%s", frame_, method_.c_str());
  const fs::path dir = fs::path(options_.saveDir) / name;
  fs::create_directories(dir);
  for (int m = 0; m < actors_.size(); ++m) {
    TriMesh shown = session_.meshes()[m];
    shown.V = actors_.shownPoints(m);
    io::writeTriMesh((dir / fs::path(session_.rig().meshes[m]).filename()).string(), shown,
                     io::MeshWriteOptions{WriteOptions{true}});
  }
  std::cout << "wrote " << dir.string() << '\n';
}

void PoserController::resetCamera() {
  window_.viewFromFront();
  window_.render();
}

void PoserController::updateStatus(const std::string& note) {
  std::string upper = method_;
  std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return std::toupper(c); });
  char text[160];
  std::snprintf(text, sizeof text, "%s   frame %d / %d   skinning %.1f ms%s", upper.c_str(), frame_,
                motion_.frameCount() - 1, skinningMs_, playing() ? "   playing" : "");
  window_.setStatus(note.empty() ? text : std::string(text) + "\n" + note);
}

}  // namespace vesalius::poser
