// Pixel access and simple drawing on RgbImage (rgb_image.h).
#include "vesalius/viz/rgb_image.h"

#include <algorithm>
#include <cmath>

namespace vesalius::viz {

RgbImage::RgbImage(int w, int h, const Rgb& fill) : width(w), height(h), pixels(std::size_t(w) * h * 3) {
  for (std::size_t p = 0; p < pixels.size(); p += 3) std::copy(fill.begin(), fill.end(), pixels.begin() + p);
}

Rgb RgbImage::get(int x, int y) const {
  const std::size_t p = (std::size_t(y) * width + x) * 3;
  return {pixels[p], pixels[p + 1], pixels[p + 2]};
}

void RgbImage::set(int x, int y, const Rgb& c) {
  if (!contains(x, y)) return;
  std::copy(c.begin(), c.end(), pixels.begin() + (std::size_t(y) * width + x) * 3);
}

void RgbImage::blend(int x, int y, const Rgb& c, double alpha) {
  if (!contains(x, y)) return;
  const Rgb old = get(x, y);
  Rgb mixed;
  for (int ch = 0; ch < 3; ++ch)
    mixed[ch] = std::uint8_t(std::lround((1.0 - alpha) * old[ch] + alpha * c[ch]));
  set(x, y, mixed);
}

void RgbImage::fillRect(int x, int y, int w, int h, const Rgb& c) {
  for (int yy = std::max(y, 0); yy < std::min(y + h, height); ++yy)
    for (int xx = std::max(x, 0); xx < std::min(x + w, width); ++xx) set(xx, yy, c);
}

void RgbImage::paste(const RgbImage& src, int x, int y) {
  for (int yy = 0; yy < src.height; ++yy)
    for (int xx = 0; xx < src.width; ++xx) set(x + xx, y + yy, src.get(xx, yy));
}

}  // namespace vesalius::viz
