// Label maps built in tests: every voxel labelled by a function of its world position (LPS mm).
#pragma once

#include "vesalius/core/label_map.h"

namespace vesalius::test {

// The map on `geometry` whose voxel with centre p (world, mm) holds labelAt(p); the table is empty.
template <class LabelAt>
LabelMap paintedLabelMap(const GridGeometry& geometry, LabelAt labelAt) {
  LabelMap map;
  map.labels = Grid<Label>(geometry, 0);
  for (int k = 0; k < geometry.size.z(); ++k)
    for (int j = 0; j < geometry.size.y(); ++j)
      for (int i = 0; i < geometry.size.x(); ++i)
        map.labels.at(i, j, k) = Label(labelAt(geometry.indexToWorld(Eigen::Vector3d(i, j, k))));
  return map;
}

}  // namespace vesalius::test
