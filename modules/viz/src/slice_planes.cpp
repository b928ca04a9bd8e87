// World-aligned slice planes of a grid (slice_planes.h).
#include "slice_planes.h"

#include <algorithm>
#include <cmath>

namespace vesalius::viz::detail {
namespace {

struct WorldBox {
  Eigen::Vector3d lo, hi;
};

// World bounding box of the grid's voxels (their outer faces, not their centres).
WorldBox worldBox(const GridGeometry& g) {
  WorldBox box{Eigen::Vector3d::Constant(HUGE_VAL), Eigen::Vector3d::Constant(-HUGE_VAL)};
  for (int corner = 0; corner < 8; ++corner) {
    Eigen::Vector3d index;
    for (int a = 0; a < 3; ++a) index[a] = (corner >> a & 1) ? g.size[a] - 0.5 : -0.5;
    const Eigen::Vector3d world = g.indexToWorld(index);
    box.lo = box.lo.cwiseMin(world);
    box.hi = box.hi.cwiseMax(world);
  }
  return box;
}

// A panel spanning world axis `across` (left to right, increasing) and `vertical` (top to bottom,
// increasing if `downIncreases`), through `centre` along the remaining axis.
SlicePlane panel(const WorldBox& box, const Eigen::Vector3d& centre, double pixelMm, int across, int vertical,
                 bool downIncreases) {
  SlicePlane plane;
  plane.corner = centre;
  plane.right = Eigen::Vector3d::Unit(across) * pixelMm;
  plane.down = Eigen::Vector3d::Unit(vertical) * (downIncreases ? pixelMm : -pixelMm);
  plane.corner[across] = box.lo[across] + 0.5 * pixelMm;
  plane.corner[vertical] =
      downIncreases ? box.lo[vertical] + 0.5 * pixelMm : box.hi[vertical] - 0.5 * pixelMm;
  plane.width = std::max(1, int(std::ceil((box.hi[across] - box.lo[across]) / pixelMm - 1e-6)));
  plane.height = std::max(1, int(std::ceil((box.hi[vertical] - box.lo[vertical]) / pixelMm - 1e-6)));
  return plane;
}

}  // namespace

std::array<SlicePlane, 3> orthogonalPlanes(const GridGeometry& geometry, const Eigen::Vector3d& centre,
                                           int panelPixels) {
  const WorldBox box = worldBox(geometry);
  const double pixelMm = (box.hi - box.lo).maxCoeff() / std::max(panelPixels, 1);
  // LPS: x grows to the patient's left, y to posterior, z to superior.
  SlicePlane axial = panel(box, centre, pixelMm, 0, 1, true);
  axial.title = "axial";
  axial.edges = {"R", "L", "A", "P"};
  SlicePlane coronal = panel(box, centre, pixelMm, 0, 2, false);
  coronal.title = "coronal";
  coronal.edges = {"R", "L", "S", "I"};
  SlicePlane sagittal = panel(box, centre, pixelMm, 1, 2, false);
  sagittal.title = "sagittal";
  sagittal.edges = {"A", "P", "S", "I"};
  return {axial, coronal, sagittal};
}

}  // namespace vesalius::viz::detail
