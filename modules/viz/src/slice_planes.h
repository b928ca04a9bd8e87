// The three world-aligned slice planes of a slice overlay and their sampling (internal to viz).
#pragma once

#include "vesalius/core/label_map.h"

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace vesalius::viz::detail {

// Pixel (x, y) of a panel shows the world point corner + x * right + y * down (pixel centres).
struct SlicePlane {
  std::string title;
  std::array<std::string, 4> edges;  // anatomical side shown at the left, right, top, bottom edge
  Eigen::Vector3d corner, right, down;
  int width = 0, height = 0;
};

// Axial, coronal and sagittal planes through world point `centre` (slice_overlay.h gives the display
// convention), each covering the grid's world bounding box, with square pixels sized so that the longest
// panel side is `panelPixels`.
std::array<SlicePlane, 3> orthogonalPlanes(const GridGeometry& geometry, const Eigen::Vector3d& centre,
                                           int panelPixels);

// Per pixel of `plane`, row by row: the scan by trilinear interpolation and the label of the nearest
// voxel; `inside` is 0 where the pixel falls outside the grid (scan and label are then 0).
struct PlaneSamples {
  std::vector<float> scan;
  std::vector<Label> labels;
  std::vector<std::uint8_t> inside;
};
PlaneSamples samplePlane(const Image& scan, const Grid<Label>& labels, const SlicePlane& plane);

}  // namespace vesalius::viz::detail
