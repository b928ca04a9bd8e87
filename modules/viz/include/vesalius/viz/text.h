// Text drawn into RgbImage with FreeType through vtkFreeTypeTools; needs no window and no X server.
#pragma once

#include "vesalius/viz/rgb_image.h"

#include <string>

namespace vesalius::viz {

struct TextExtent {
  int width = 0, height = 0;  // pixels
};

// Size of `text` in VTK's built-in Arial at `pixelSize` (font size in pixels, at 72 dpi).
TextExtent measureText(const std::string& text, int pixelSize);

// Draws `text` with its top-left corner at (x, y), anti-aliased over what is there, clipped to `image`.
void drawText(RgbImage& image, int x, int y, const std::string& text, const Rgb& color, int pixelSize);

}  // namespace vesalius::viz
