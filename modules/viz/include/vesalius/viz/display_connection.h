// One connection to the X display, for everything here that opens a VTK render window.
#pragma once

#include <string>

namespace vesalius::viz {

// VTK aborts the process when it cannot open the X display; this throws UsageError with one line naming
// `user` (the program or the picture that needs the display) instead. Keep it alive longer than the render
// window and hand `display` to the window (vtkRenderWindow::SetDisplayId), so that VTK opens no second
// connection that could fail after this one succeeded.
class DisplayConnection {
 public:
  explicit DisplayConnection(const std::string& user);
  ~DisplayConnection();
  DisplayConnection(const DisplayConnection&) = delete;
  DisplayConnection& operator=(const DisplayConnection&) = delete;

  void* display;  // Xlib's Display*, as vtkRenderWindow::SetDisplayId takes it; Xlib's macros stay out of here
};

}  // namespace vesalius::viz
