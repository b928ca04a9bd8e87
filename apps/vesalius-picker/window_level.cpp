#include "window_level.h"

#include <algorithm>
#include <vector>

namespace vesalius::picker {

WindowLevel percentileWindowLevel(const Image& scan) {
  const std::size_t count = scan.values.size();
  const std::size_t stride = std::max<std::size_t>(1, count / 1000000);
  std::vector<float> sample;
  sample.reserve(count / stride + 1);
  for (std::size_t i = 0; i < count; i += stride) sample.push_back(scan.values[i]);
  if (sample.empty()) return {1, 0};
  const auto at = [&](double fraction) {
    auto nth = sample.begin() + std::ptrdiff_t(fraction * double(sample.size() - 1));
    std::nth_element(sample.begin(), nth, sample.end());
    return double(*nth);
  };
  const double low = at(0.01), high = at(0.99);
  return {std::max(high - low, 1.0), (low + high) / 2};
}

WindowLevel dragWindowLevel(const WindowLevel& start, double dx, double dy) {
  const double perPixel = start.window / 200.0;
  return {std::max(start.window + dx * perPixel, 1e-3), start.level + dy * perPixel};
}

}  // namespace vesalius::picker
