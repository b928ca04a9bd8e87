// Editing label maps: extract, merge and relabel labels, and crop a map to the bounds of a mask.
//
// Label tables follow the voxels: an extracted label keeps its entry, merged labels give way to the
// entry they are merged into, a relabelled entry takes its new id. Crops keep world geometry exact: the
// cropped grid's voxel (0,0,0) is the original's voxel `lo`, so its origin is
// origin + direction · diag(spacing) · lo and every kept voxel stays where it was in LPS mm.
#pragma once

#include "vesalius/core/label_map.h"
#include "vesalius/segmentation/label_ops.h"

#include <map>
#include <string>
#include <vector>

namespace vesalius::segmentation {

// The ids of labels given by id or by name (case-insensitive), as a user types them ("5", "liver"),
// through LabelTable::resolve; throws UsageError naming the first one that matches nothing.
std::vector<Label> resolveLabels(const LabelTable& table, const std::vector<std::string>& idsOrNames);

// The map with only the labels `ids` kept (every other voxel 0) and their table entries.
LabelMap extractLabels(const LabelMap& map, const std::vector<Label>& ids);
// The same with labels given by id or name.
LabelMap extractLabels(const LabelMap& map, const std::vector<std::string>& idsOrNames);

// Every voxel labelled one of `ids` becomes `into.id`; the table loses the entries of `ids` and gets
// `into` (which may reuse one of `ids`). Throws UsageError if into.id is 0.
LabelMap mergeLabels(const LabelMap& map, const std::vector<Label>& ids, const LabelEntry& into);

// Maps each id in `idMap` to its new id (0 deletes the label); ids not in the map are kept. Throws
// UsageError if two labels would end up with the same non-zero id (join labels with mergeLabels).
LabelMap relabel(const LabelMap& map, const std::map<Label, Label>& idMap);

// A box of voxel indices, lo inclusive and hi exclusive per axis.
struct VoxelBox {
  Eigen::Vector3i lo = Eigen::Vector3i::Zero(), hi = Eigen::Vector3i::Zero();
  Eigen::Vector3i size() const { return hi - lo; }
};

// The bounding box of the voxels of `mask`, grown by marginMm on every side (ceil(marginMm / spacing)
// voxels along each axis) and clipped to the grid. Throws BadInput if the mask is empty, UsageError if
// marginMm is negative or not finite.
VoxelBox maskBounds(const Mask& mask, double marginMm = 0.0);

// The geometry of the sub-grid `box` of `geometry` (see the header comment); UsageError if the box is
// empty or leaves the grid.
GridGeometry cropGeometry(const GridGeometry& geometry, const VoxelBox& box);

// The voxels of `grid` inside `box`, with cropGeometry.
template <class T>
Grid<T> cropGrid(const Grid<T>& grid, const VoxelBox& box) {
  Grid<T> out(cropGeometry(grid.geometry, box));
  const Eigen::Vector3i& s = out.geometry.size;
  for (int k = 0; k < s.z(); ++k)
    for (int j = 0; j < s.y(); ++j)
      for (int i = 0; i < s.x(); ++i) out.at(i, j, k) = grid.at(box.lo.x() + i, box.lo.y() + j, box.lo.z() + k);
  return out;
}

// The label map cropped to `box`; the table keeps the entries of the labels still present.
LabelMap cropLabelMap(const LabelMap& map, const VoxelBox& box);

}  // namespace vesalius::segmentation
