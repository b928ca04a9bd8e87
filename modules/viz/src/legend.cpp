// The legend of a slice overlay (legend.h).
#include "legend.h"

#include "overlay_style.h"
#include "vesalius/viz/text.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace vesalius::viz::detail {
namespace {

struct LegendItem {
  Rgb color;
  std::string text;
  int width;
};

std::string volumeText(std::int64_t voxels, const GridGeometry& g) {
  const double ml = double(voxels) * g.spacing.prod() / 1000.0;
  char text[32];
  if (ml >= 1000.0)
    std::snprintf(text, sizeof text, "%.1f L", ml / 1000.0);
  else
    std::snprintf(text, sizeof text, "%.0f ml", ml);
  return text;
}

std::vector<LegendItem> legendItems(const LabelMap& labels, int swatch) {
  std::vector<std::int64_t> counts(std::size_t(1) << 16, 0);
  for (Label v : labels.labels.values) ++counts[v];
  std::vector<LegendItem> items;
  for (std::size_t id = 1; id < counts.size(); ++id) {
    if (counts[id] == 0) continue;
    const LabelEntry* entry = labels.table.find(Label(id));
    const std::string name = entry ? entry->name : "label_" + std::to_string(id);
    const std::string text = name + "  " + volumeText(counts[id], labels.labels.geometry);
    items.push_back({labelColor(labels.table, Label(id)), text,
                     swatch + 6 + measureText(text, kLegendSize).width + 2 * kGap});
  }
  return items;
}

}  // namespace

Rgb labelColor(const LabelTable& table, Label id) {
  const LabelEntry* entry = table.find(id);
  return entry ? entry->color : defaultLabelColor(id);
}

RgbImage renderLegend(const LabelMap& labels, int maxWidth) {
  const int rowHeight = measureText("Ag", kLegendSize).height + 8, swatch = rowHeight - 8;
  const std::vector<LegendItem> items = legendItems(labels, swatch);
  int rows = items.empty() ? 0 : 1, x = 0;
  for (const LegendItem& item : items) {
    if (x > 0 && x + item.width > maxWidth) ++rows, x = 0;
    x += item.width;
  }
  RgbImage legend(std::max(maxWidth, 1), std::max(rows * rowHeight, 1), kBackground);
  int row = 0;
  x = 0;
  for (const LegendItem& item : items) {
    if (x > 0 && x + item.width > maxWidth) ++row, x = 0;
    const int y = row * rowHeight;
    legend.fillRect(x, y + 4, swatch, swatch, item.color);
    drawText(legend, x + swatch + 6, y + 4, item.text, kText, kLegendSize);
    x += item.width;
  }
  return legend;
}

}  // namespace vesalius::viz::detail
