#include "vesalius/viz/histogram_panel.h"

#include "vesalius/core/error.h"
#include "vesalius/core/histogram.h"
#include "vesalius/viz/text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace vesalius::viz {

namespace {

std::string withUnit(double value, const std::string& unit) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", value);
  return std::string(text) + " " + unit;
}

}  // namespace

RgbImage histogramPanel(const Eigen::VectorXd& values, const HistogramPanelOptions& o) {
  if (values.size() == 0) throw UsageError("histogram panel: no values");
  if (!values.allFinite()) throw UsageError("histogram panel: every value must be finite");
  if (o.maxBars < 1) throw UsageError("histogram panel: at least one bar");
  if (o.width < 1 || o.height < 1) throw UsageError("histogram panel: the panel must be at least 1 pixel");
  constexpr int kPad = 14, kTitle = 16, kSmall = 13;
  RgbImage panel(o.width, o.height, o.background);
  std::vector<long> counts = histogramCounts(values, o.binWidth);
  const std::size_t maxBars = std::size_t(o.maxBars);
  const bool capped = counts.size() > maxBars;
  if (capped) {
    for (std::size_t b = maxBars; b < counts.size(); ++b) counts[maxBars - 1] += counts[b];
    counts.resize(maxBars);
  }
  const int line = measureText("Ag", kSmall).height + 4;
  drawText(panel, kPad, kPad, o.title, o.text, kTitle);
  drawText(panel, kPad, kPad + line + 6,
           std::to_string(values.size()) + " " + o.items + ", mean " + withUnit(values.mean(), o.unit) + ", max " +
               withUnit(values.maxCoeff(), o.unit),
           o.text, kSmall);
  const long highest = *std::max_element(counts.begin(), counts.end());
  const int left = kPad + measureText(std::to_string(highest), kSmall).width + 6, right = o.width - kPad;
  const int top = kPad + 3 * line + 12, bottom = std::max(top + 20, o.height - kPad - 2 * line);
  const double barWidth = double(right - left) / double(counts.size());
  for (std::size_t b = 0; b < counts.size(); ++b) {
    const int x0 = left + int(std::lround(double(b) * barWidth)),
              x1 = left + int(std::lround(double(b + 1) * barWidth));
    const int h = int(std::lround(double(bottom - top) * double(counts[b]) / double(highest)));
    panel.fillRect(x0, bottom - h, std::max(1, x1 - x0 - 1), h, o.bar);
  }
  panel.fillRect(left, bottom, right - left, 1, o.axis);
  panel.fillRect(left - 1, top, 1, bottom - top + 1, o.axis);
  drawText(panel, kPad, top, std::to_string(highest), o.text, kSmall);
  drawText(panel, kPad, bottom - line + 4, "0", o.text, kSmall);
  const std::string end = (capped ? ">" : "") + withUnit(double(counts.size()) * o.binWidth, o.unit);
  drawText(panel, left, bottom + 4, "0", o.text, kSmall);
  drawText(panel, right - measureText(end, kSmall).width, bottom + 4, end, o.text, kSmall);
  drawText(panel, left, bottom + 4 + line, o.items + " per " + withUnit(o.binWidth, o.unit) + " bin", o.axis, kSmall);
  return panel;
}

}  // namespace vesalius::viz
