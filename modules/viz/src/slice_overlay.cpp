// Slice overlay pictures (slice_overlay.h): three panels side by side, titles, edge letters, legend.
#include "vesalius/viz/slice_overlay.h"

#include "legend.h"
#include "overlay_style.h"
#include "slice_planes.h"
#include "vesalius/core/error.h"
#include "vesalius/viz/text.h"

#include <algorithm>
#include <cmath>

namespace vesalius::viz {
namespace {

using namespace detail;

std::uint8_t grey(float value, const OverlayOptions& o) {
  const double t = (value - (o.level - 0.5 * o.window)) / o.window;
  return std::uint8_t(std::lround(255.0 * std::clamp(t, 0.0, 1.0)));
}

// A label pixel is on the outline if a 4-neighbour inside the grid has another label.
bool onOutline(const detail::PlaneSamples& s, const detail::SlicePlane& plane, int x, int y) {
  const Label own = s.labels[std::size_t(y) * plane.width + x];
  const int dx[4] = {-1, 1, 0, 0}, dy[4] = {0, 0, -1, 1};
  for (int n = 0; n < 4; ++n) {
    const int nx = x + dx[n], ny = y + dy[n];
    if (nx < 0 || ny < 0 || nx >= plane.width || ny >= plane.height) continue;
    const std::size_t q = std::size_t(ny) * plane.width + nx;
    if (s.inside[q] && s.labels[q] != own) return true;
  }
  return false;
}

RgbImage renderPanel(const Image& scan, const LabelMap& labels, const detail::SlicePlane& plane,
                     const OverlayOptions& o) {
  const detail::PlaneSamples s = detail::samplePlane(scan, labels.labels, plane);
  RgbImage panel(plane.width, plane.height, {0, 0, 0});
  for (int y = 0; y < plane.height; ++y)
    for (int x = 0; x < plane.width; ++x) {
      const std::size_t p = std::size_t(y) * plane.width + x;
      if (!s.inside[p]) continue;
      const std::uint8_t g = grey(s.scan[p], o);
      panel.set(x, y, {g, g, g});
      if (s.labels[p] == 0) continue;
      const double alpha = onOutline(s, plane, x, y) ? o.outlineOpacity : o.opacity;
      panel.blend(x, y, labelColor(labels.table, s.labels[p]), alpha);
    }
  const auto& e = plane.edges;
  const TextExtent letter = measureText("M", kEdgeSize);
  drawText(panel, 3, (plane.height - letter.height) / 2, e[0], kEdgeText, kEdgeSize);
  drawText(panel, plane.width - measureText(e[1], kEdgeSize).width - 3, (plane.height - letter.height) / 2,
           e[1], kEdgeText, kEdgeSize);
  drawText(panel, (plane.width - measureText(e[2], kEdgeSize).width) / 2, 3, e[2], kEdgeText, kEdgeSize);
  drawText(panel, (plane.width - measureText(e[3], kEdgeSize).width) / 2, plane.height - letter.height - 3,
           e[3], kEdgeText, kEdgeSize);
  return panel;
}

void validate(const Image& scan, const LabelMap& labels, const OverlayOptions& o) {
  if (labels.labels.geometry.size != scan.geometry.size || labels.labels.values.size() != scan.values.size())
    throw BadInput("", "label map and scan have different grids");
  if (!(o.window > 0) || !(o.opacity >= 0 && o.opacity <= 1) ||
      !(o.outlineOpacity >= 0 && o.outlineOpacity <= 1) || o.panelPixels < 16)
    throw UsageError("overlay needs window > 0, opacities in [0, 1] and at least 16 panel pixels");
  if (o.voxel && !scan.geometry.contains(o.voxel->x(), o.voxel->y(), o.voxel->z()))
    throw UsageError("overlay slice voxel lies outside the scan");
}

}  // namespace

RgbImage renderSliceOverlay(const Image& scan, const LabelMap& labels, const OverlayOptions& options) {
  validate(scan, labels, options);
  const Eigen::Vector3d centreIndex =
      options.voxel ? Eigen::Vector3d(options.voxel->cast<double>())
                    : Eigen::Vector3d((scan.geometry.size.cast<double>().array() - 1.0) / 2.0);
  const auto planes =
      detail::orthogonalPlanes(scan.geometry, scan.geometry.indexToWorld(centreIndex), options.panelPixels);
  std::vector<RgbImage> panels;
  int width = 2 * kMargin + 2 * kGap, height = 0;
  for (const auto& plane : planes) {
    panels.push_back(renderPanel(scan, labels, plane, options));
    width += plane.width;
    height = std::max(height, plane.height);
  }
  const int titleHeight = measureText("Ag", kTitleSize).height + 6;
  const RgbImage legend = renderLegend(labels, width - 2 * kMargin);
  RgbImage canvas(width, kMargin + titleHeight + height + kGap + legend.height + kMargin, kBackground);
  int x = kMargin;
  for (std::size_t n = 0; n < panels.size(); ++n) {
    drawText(canvas, x, kMargin, planes[n].title, kText, kTitleSize);
    canvas.paste(panels[n], x, kMargin + titleHeight);
    x += panels[n].width + kGap;
  }
  canvas.paste(legend, kMargin, kMargin + titleHeight + height + kGap);
  return canvas;
}

void writeSliceOverlayPng(const Image& scan, const LabelMap& labels, const std::string& pngPath,
                          const OverlayOptions& options) {
  writePng(pngPath, renderSliceOverlay(scan, labels, options), options.write);
}

}  // namespace vesalius::viz
