// What the poser shows and how keys, slider and timer change it: the frame of the motion, the skinning
// method (LBS, DQS or CoR, Sujar et al. 2018, §3.5), playing or paused. Every change re-skins the shown frame at
// once through the session's skinners (built once, posing/rig_poser.h) and moves the points of the
// existing actors; the status line gives the method, the frame and the time that skinning and carrying
// the meshes took.
#pragma once

#include "anatomy_actors.h"
#include "poser_options.h"
#include "poser_window.h"

#include "vesalius/rigging/rig_session.h"

#include <string>
#include <vector>

namespace vesalius::poser {

class PoserController {
 public:
  // All references are kept; options.method and options.frame are where it starts (shown by showFrame).
  PoserController(const posing::RigPoser& session, const rigging::RetargetedMotion& motion, AnatomyActors& actors,
                  PoserWindow& window, const PoserOptions& options);

  void showFrame(int frame);  // wraps into 0 .. frameCount - 1
  void step(int frames) { showFrame(frame_ + frames); }
  // lbs, dqs or cor. On a rig that cannot (CoR without centres) the status line says why and the method
  // stays.
  void setMethod(const std::string& method);
  void togglePlay();  // a repeating timer at options.fps steps a frame per tick, wrapping around
  void tick() { step(1); }
  // Writes the shown meshes (their actors' points, the rest faces) to
  // <saveDir>/frame_<5 digits>_<method>/<mesh file name>.
  void saveShown() const;
  void resetCamera();

  int frame() const { return frame_; }
  const std::string& method() const { return method_; }
  bool playing() const { return timer_ >= 0; }

 private:
  void updateStatus(const std::string& note = "");

  const posing::RigPoser& session_;
  const rigging::RetargetedMotion& motion_;
  AnatomyActors& actors_;
  PoserWindow& window_;
  const PoserOptions& options_;
  int frame_ = 0;
  std::string method_;
  int timer_ = -1;
  double skinningMs_ = 0;
  MatrixX3d tets_;                  // kept between frames: the skinners write into it
  std::vector<MatrixX3d> carried_;  // the same for the meshes
};

}  // namespace vesalius::poser
