// What the two VTK apps (vesalius-picker, vesalius-poser) do alike around their window: check the X display,
// end the event loop when the window closes, play recorded events (the GUI tests) and save the window.
#pragma once

#include <X11/Xlib.h>

#include <string>

class vtkRenderWindow;
class vtkRenderWindowInteractor;

namespace vesalius::gui {

// VTK aborts when it cannot open the X display; this throws UsageError with one line naming `program`
// instead. Keep it alive and hand `display` to the render window (SetDisplayId): VTK opening a second
// connection failed now and then under a loaded Xvfb.
class DisplayConnection {
 public:
  explicit DisplayConnection(const std::string& program);
  ~DisplayConnection();
  DisplayConnection(const DisplayConnection&) = delete;
  DisplayConnection& operator=(const DisplayConnection&) = delete;

  Display* display;
};

// Closing the window ends the event loop like the quit key (VTK 9.1's default TerminateApp() crashes
// inside Start(), BUILD-NOTES.md).
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
