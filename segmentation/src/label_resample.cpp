// Label maps under a size cap (label_resample.h).
#include "vesalius/segmentation/label_resample.h"

#include "vesalius/core/error.h"

#include <cmath>

namespace vesalius::segmentation {

GridGeometry cappedGeometry(const GridGeometry& geometry, const Eigen::Vector3i& maxSizeLps) {
  if ((maxSizeLps.array() < 1).any()) throw UsageError("a grid size cap must be at least 1 voxel per axis");
  GridGeometry out = geometry;
  for (int a = 0; a < 3; ++a) {
    Eigen::Index lps = 0;
    geometry.direction.col(a).cwiseAbs().maxCoeff(&lps);
    const int cap = maxSizeLps(lps);
    if (geometry.size(a) <= cap) continue;
    const double extent = geometry.size(a) * geometry.spacing(a);
    out.spacing(a) = extent / cap;
    out.size(a) = cap;
  }
  // Same outer faces: the first voxel's centre moves by half the change of spacing, along each axis.
  out.origin = geometry.origin + geometry.direction * (0.5 * (out.spacing - geometry.spacing));
  return out;
}

LabelMap resampleLabels(const LabelMap& map, const GridGeometry& target) {
  target.validate("resampled label map");
  LabelMap out{Grid<Label>(target, 0), map.table};
  const Eigen::Vector3i& from = map.labels.geometry.size;
  for (int k = 0; k < target.size.z(); ++k)
    for (int j = 0; j < target.size.y(); ++j)
      for (int i = 0; i < target.size.x(); ++i) {
        const Eigen::Vector3d index =
            map.labels.geometry.worldToIndex(target.indexToWorld(Eigen::Vector3d(i, j, k)));
        const Eigen::Vector3i nearest = index.array().round().cast<int>();
        if ((nearest.array() >= 0).all() && (nearest.array() < from.array()).all())
          out.labels.at(i, j, k) = map.labels.at(nearest.x(), nearest.y(), nearest.z());
      }
  return out;
}

}  // namespace vesalius::segmentation
