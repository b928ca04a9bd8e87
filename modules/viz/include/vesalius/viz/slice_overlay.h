// Axial, coronal and sagittal slices of a scan with its labels as translucent colours, and a legend.
//
// Each slice is a plane of LPS world space through one point (not an index plane), sampled with square
// pixels: the scan by trilinear interpolation, the labels by nearest voxel. So oblique scans show
// anatomically upright and the three views share one scale. Display convention is radiological:
//   axial    patient right on the image left, anterior up      (screen x = +L, screen y = +P)
//   coronal  patient right on the image left, superior up      (screen x = +L, screen y = -S)
//   sagittal anterior on the image left, superior up           (screen x = +P, screen y = -S)
// The scan is mapped to grey through a window and level (CT soft tissue: W 400, L 40 HU); labels of the
// table are blended with their colours at `opacity`, their outlines at `outlineOpacity`. Labels present
// in the map but not in the table use defaultLabelColor. The legend lists the labels present in the map.
#pragma once

#include "vesalius/core/atomic_file.h"
#include "vesalius/core/label_map.h"
#include "vesalius/viz/rgb_image.h"

#include <Eigen/Core>

#include <optional>
#include <string>

namespace vesalius::viz {

struct OverlayOptions {
  double window = 400.0;  // in scan units (HU for CT)
  double level = 40.0;
  std::optional<Eigen::Vector3i> voxel;  // slices pass through this voxel's centre; default the grid centre
  double opacity = 0.35;
  double outlineOpacity = 0.8;
  int panelPixels = 400;  // the longest side of the largest panel, in pixels
  WriteOptions write;
};

// The picture in memory. `labels` must have the scan's geometry (BadInput otherwise); UsageError for a
// non-positive window, an opacity outside [0, 1] or a voxel outside the grid.
RgbImage renderSliceOverlay(const Image& scan, const LabelMap& labels, const OverlayOptions& options = {});

// renderSliceOverlay written as PNG (writePng).
void writeSliceOverlayPng(const Image& scan, const LabelMap& labels, const std::string& pngPath,
                          const OverlayOptions& options = {});

}  // namespace vesalius::viz
