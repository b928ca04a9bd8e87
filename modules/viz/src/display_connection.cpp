#include "vesalius/viz/display_connection.h"

#include "vesalius/core/error.h"

#include <X11/Xlib.h>

#include <cstdlib>

namespace vesalius::viz {

DisplayConnection::DisplayConnection(const std::string& user) : display(XOpenDisplay(nullptr)) {
  if (!display) {
    const char* name = std::getenv("DISPLAY");
    throw UsageError(std::string("cannot open the X display '") + (name ? name : "") + "'; " + user +
                     " needs one (without a screen, run it under xvfb-run)");
  }
}

DisplayConnection::~DisplayConnection() { XCloseDisplay(static_cast<Display*>(display)); }

}  // namespace vesalius::viz
