// Hole filling by flood fill of the background from the volume edge (label_ops.h).
#include "vesalius/core/error.h"
#include "vesalius/segmentation/label_ops.h"

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace vesalius::segmentation {
namespace {

using Voxel = std::array<int, 3>;

// Flood fill of background within the box [lo, hi) through face neighbours along `axes`.
class BackgroundFlood {
 public:
  BackgroundFlood(const Mask& mask, const Voxel& lo, const Voxel& hi, const std::vector<int>& axes,
                  std::vector<std::uint8_t>& reached)
      : mask_(mask), lo_(lo), hi_(hi), axes_(axes), reached_(reached) {}

  // Marks the background region(s) containing `seeds` as reached; returns the voxels newly reached.
  std::vector<Voxel> grow(const std::vector<Voxel>& seeds) {
    std::vector<Voxel> region, stack;
    auto visit = [&](const Voxel& v) {
      const std::int64_t n = mask_.geometry.linearIndex(v[0], v[1], v[2]);
      if (mask_.values[n] || reached_[n]) return;
      reached_[n] = 1;
      stack.push_back(v);
      region.push_back(v);
    };
    for (const Voxel& s : seeds) visit(s);
    while (!stack.empty()) {
      const Voxel v = stack.back();
      stack.pop_back();
      for (int a : axes_)
        for (int step : {-1, 1}) {
          Voxel w = v;
          w[a] += step;
          if (w[a] >= lo_[a] && w[a] < hi_[a]) visit(w);
        }
    }
    return region;
  }

  bool reached(const Voxel& v) const { return reached_[mask_.geometry.linearIndex(v[0], v[1], v[2])]; }

 private:
  const Mask& mask_;
  Voxel lo_, hi_;
  std::vector<int> axes_;
  std::vector<std::uint8_t>& reached_;
};

template <class Visit>
void forEachVoxel(const Voxel& lo, const Voxel& hi, Visit visit) {
  for (int k = lo[2]; k < hi[2]; ++k)
    for (int j = lo[1]; j < hi[1]; ++j)
      for (int i = lo[0]; i < hi[0]; ++i) visit(Voxel{i, j, k});
}

// Sets to 1 each background region of the box [lo, hi) that does not reach the box border (along
// `axes`) and has at most maxHoleVoxels voxels. `reached` has one zeroed entry per voxel of `mask`;
// boxes filled one after another must not overlap.
void fillBox(Mask& mask, const Voxel& lo, const Voxel& hi, const std::vector<int>& axes, double maxHoleVoxels,
             std::vector<std::uint8_t>& reached) {
  BackgroundFlood flood(mask, lo, hi, axes, reached);
  std::vector<Voxel> border;
  forEachVoxel(lo, hi, [&](const Voxel& v) {
    bool onBorder = false;
    for (int a : axes) onBorder = onBorder || v[a] == lo[a] || v[a] == hi[a] - 1;
    if (onBorder) border.push_back(v);
  });
  flood.grow(border);
  std::vector<Voxel> holes;
  forEachVoxel(lo, hi, [&](const Voxel& v) {
    if (mask.at(v[0], v[1], v[2]) || flood.reached(v)) return;
    std::vector<Voxel> hole = flood.grow({v});
    if (double(hole.size()) <= maxHoleVoxels) holes.insert(holes.end(), hole.begin(), hole.end());
  });
  for (const Voxel& v : holes) mask.at(v[0], v[1], v[2]) = 1;
}

}  // namespace

Mask fillHoles3d(const Mask& mask) {
  Mask out = mask;
  const Eigen::Vector3i& s = mask.geometry.size;
  std::vector<std::uint8_t> reached(out.values.size(), 0);
  fillBox(out, {0, 0, 0}, {s[0], s[1], s[2]}, {0, 1, 2}, HUGE_VAL, reached);
  return out;
}

Mask fillHolesSliceWise(const Mask& mask, int axis, double maxHoleAreaMm2) {
  if (axis < 0 || axis > 2) throw UsageError("slice axis must be 0, 1 or 2, not " + std::to_string(axis));
  Mask out = mask;
  const Eigen::Vector3i& s = mask.geometry.size;
  std::vector<int> inPlane;
  for (int a = 0; a < 3; ++a)
    if (a != axis) inPlane.push_back(a);
  const double pixelMm2 = mask.geometry.spacing[inPlane[0]] * mask.geometry.spacing[inPlane[1]];
  std::vector<std::uint8_t> reached(out.values.size(), 0);
  for (int slice = 0; slice < s[axis]; ++slice) {
    Voxel lo{0, 0, 0}, hi{s[0], s[1], s[2]};
    lo[axis] = slice;
    hi[axis] = slice + 1;
    fillBox(out, lo, hi, inPlane, maxHoleAreaMm2 / pixelMm2, reached);
  }
  return out;
}

int axialAxis(const GridGeometry& geometry) {
  int best = 0;
  for (int a = 1; a < 3; ++a)
    if (std::abs(geometry.direction(2, a)) > std::abs(geometry.direction(2, best))) best = a;
  return best;
}

Mask fillBodyHoles(const Mask& body) { return fillHoles3d(fillHolesSliceWise(body, axialAxis(body.geometry))); }

}  // namespace vesalius::segmentation
