// Small 26-connected pieces of a mask cleared (small_pieces.h).
#include "vesalius/core/small_pieces.h"

#include <array>
#include <vector>

namespace vesalius {
namespace {

// The 26 neighbours of a voxel, by their linear indices; a voxel on the grid's border has fewer.
class Neighbours {
 public:
  explicit Neighbours(const GridGeometry& g) : g_(g) {
    int n = 0;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (dx || dy || dz) {
            step_[std::size_t(n)] = {dx, dy, dz};
            offset_[std::size_t(n++)] = dx + std::int64_t(g.size.x()) * (dy + std::int64_t(g.size.y()) * dz);
          }
  }

  template <class Visit>
  void forEach(const Eigen::Vector3i& v, Visit&& visit) const {
    const std::int64_t at = g_.linearIndex(v.x(), v.y(), v.z());
    const bool inner = (v.array() > 0).all() && (v.array() + 1 < g_.size.array()).all();
    for (std::size_t n = 0; n < offset_.size(); ++n) {
      const Eigen::Vector3i w = v + step_[n];
      if (inner || g_.contains(w.x(), w.y(), w.z())) visit(w, at + offset_[n]);
    }
  }

 private:
  const GridGeometry& g_;
  std::array<std::int64_t, 26> offset_{};
  std::array<Eigen::Vector3i, 26> step_{};
};

// Voxels of a piece already counted, until the end: the mask itself marks what has been seen, so each step
// reads one array instead of two.
constexpr std::uint8_t kCounted = 2;

// Sets the 26-connected piece of voxels valued `from` that holds `start` to `to`; returns its voxel count.
std::int64_t flood(Grid<std::uint8_t>& mask, const Neighbours& neighbours, const Eigen::Vector3i& start,
                   std::uint8_t from, std::uint8_t to, std::vector<Eigen::Vector3i>& stack) {
  std::int64_t voxels = 0;
  stack.assign(1, start);
  mask.at(start.x(), start.y(), start.z()) = to;
  while (!stack.empty()) {
    const Eigen::Vector3i v = stack.back();
    stack.pop_back();
    ++voxels;
    neighbours.forEach(v, [&](const Eigen::Vector3i& w, std::int64_t at) {
      if (mask.values[std::size_t(at)] == from) {
        mask.values[std::size_t(at)] = to;
        stack.push_back(w);
      }
    });
  }
  return voxels;
}

}  // namespace

std::int64_t dropSmallPieces(Grid<std::uint8_t>& mask, std::int64_t minVoxels) {
  for (std::uint8_t& v : mask.values) v = v ? 1 : 0;
  if (minVoxels <= 1) return 0;
  const GridGeometry& g = mask.geometry;
  const Neighbours neighbours(g);
  std::vector<Eigen::Vector3i> stack;
  std::int64_t cleared = 0;
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i) {
        if (mask.at(i, j, k) != 1) continue;
        // Count the piece; a small one is flooded again from its start to clear it, so no piece is listed.
        const Eigen::Vector3i start(i, j, k);
        const std::int64_t voxels = flood(mask, neighbours, start, 1, kCounted, stack);
        if (voxels < minVoxels) cleared += flood(mask, neighbours, start, kCounted, 0, stack);
      }
  for (std::uint8_t& v : mask.values)
    if (v == kCounted) v = 1;
  return cleared;
}

}  // namespace vesalius
