// What the two VTK apps (vesalius-picker, vesalius-poser) do alike around their window: end the event loop
// when the window closes, play recorded events (the GUI tests) and save the window. The display connection
// they hand the window is vesalius/viz/display_connection.h.
#pragma once

#include <string>

class vtkRenderWindow;
class vtkRenderWindowInteractor;

namespace vesalius::gui {

// Closing the window ends the event loop like the quit key (VTK 9.1's default TerminateApp() crashes
// inside Start(); docs/design.md).
void endLoopOnWindowClose(vtkRenderWindowInteractor* interactor);

// The window as last rendered, as a PNG written atomically.
void writeScreenshot(vtkRenderWindow* window, const std::string& path);

// How the GUI tests drive an app: vtkInteractorEventRecorder files to record the session to and to play
// after start, a screenshot after playing, and whether to return then instead of waiting for the user.
struct EventScript {
  std::string record, play, screenshot;
  bool exitAfterPlay = false;
};

// Runs the event loop of a window set up and rendered once. Throws BadInput if `play` cannot be opened.
void runEventLoop(vtkRenderWindow* window, vtkRenderWindowInteractor* interactor, const EventScript& script);

}  // namespace vesalius::gui
