// A closed surface of another topology than the given one: voxelized (its inside at `voxelMm`) and
// surfaced anew (about `faces` triangles). Registration tests use it as a target whose vertex i is not the
// source's, so only its shape can guide them. Shared by tests/transfer/skin_registration_test.cpp and
// tests/apps/cli_transfer_test.cpp.
#pragma once

#include "vesalius/core/label_map.h"
#include "vesalius/core/mesh.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/meshing/mesh_volume.h"

#include <algorithm>

namespace vesalius::test {

inline TriMesh remeshedSurface(const TriMesh& surface, double voxelMm, int faces) {
  meshing::CoveringGridOptions grid;
  grid.voxelSizeMm = voxelMm;
  grid.maxSize = Eigen::Vector3i(1000, 1000, 1000);
  const Grid<std::uint8_t> inside = meshing::meshInsideMask(surface, meshing::coveringGrid({&surface}, grid));
  LabelMap labels;
  labels.labels = Grid<Label>(inside.geometry);
  std::copy(inside.values.begin(), inside.values.end(), labels.labels.values.begin());
  meshing::SurfaceOptions options;
  options.targetFaces = faces;
  options.avoidSelfIntersections = false;  // a registration target need not be fit for TetGen
  return meshing::labelSurface(labels, 1, options);
}

}  // namespace vesalius::test
