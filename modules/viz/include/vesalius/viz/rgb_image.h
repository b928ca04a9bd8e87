// An 8-bit RGB picture in memory, rows top to bottom, and its PNG file.
#pragma once

#include "vesalius/core/atomic_file.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace vesalius::viz {

using Rgb = std::array<std::uint8_t, 3>;

struct RgbImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  // width * height * 3, row y = 0 at the top

  RgbImage() = default;
  RgbImage(int w, int h, const Rgb& fill);
  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
  Rgb get(int x, int y) const;
  void set(int x, int y, const Rgb& c);
  // Mixes `c` over the pixel with weight `alpha` in [0, 1]; ignores pixels outside the picture.
  void blend(int x, int y, const Rgb& c, double alpha);
  void fillRect(int x, int y, int w, int h, const Rgb& c);
  // Copies `src` with its top-left corner at (x, y), clipped to this picture.
  void paste(const RgbImage& src, int x, int y);
};

// Writes `image` as PNG (vtkPNGWriter) atomically and without clobbering (core/atomic_file.h).
// Throws BadInput naming the path if the file cannot be written, UsageError for an empty image.
void writePng(const std::string& path, const RgbImage& image, const WriteOptions& options = {});

}  // namespace vesalius::viz
