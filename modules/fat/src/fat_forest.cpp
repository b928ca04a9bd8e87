#include "vesalius/fat/fat_forest.h"

#include "vesalius/core/error.h"

#include <array>
#include <chrono>
#include <cmath>
#include <limits>

#include <Eigen/LU>
#include <tbb/parallel_for.h>

namespace vesalius::fat {

namespace {

enum Kind : std::uint8_t { kOther = 0, kFat = 1, kSkin = 2, kSettled = 3 };  // kSettled: fat, popped

struct Neighbour {
  int di, dj, dk;
  std::int64_t delta;  // change of the linear index
  float length;        // mm between the two centres
};

// The 26 neighbour steps with their physical lengths |direction · diag(spacing) · Δ|.
std::array<Neighbour, 26> neighbourSteps(const GridGeometry& g) {
  const Eigen::Matrix3d M = g.direction * g.spacing.asDiagonal();
  std::array<Neighbour, 26> steps{};
  int n = 0;
  for (int dk = -1; dk <= 1; ++dk)
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        if (di == 0 && dj == 0 && dk == 0) continue;
        const double length = (M * Eigen::Vector3d(di, dj, dk)).norm();
        steps[n++] = {di, dj, dk, di + std::int64_t(g.size.x()) * (dj + std::int64_t(g.size.y()) * dk),
                      float(length)};
      }
  return steps;
}

void checkInputs(const Mask& skin, const Mask& fat, const FatForestOptions& options, const std::string& source) {
  const GridGeometry& a = skin.geometry;
  const GridGeometry& b = fat.geometry;
  if (a.size != b.size || !a.origin.isApprox(b.origin, 1e-6) || !a.spacing.isApprox(b.spacing, 1e-6) ||
      !a.direction.isApprox(b.direction, 1e-6))
    throw BadInput(source, "skin and fat masks are on different grids");
  if (std::int64_t(skin.values.size()) != a.voxelCount() || std::int64_t(fat.values.size()) != b.voxelCount())
    throw BadInput(source, "mask size does not match its grid");
  if (a.voxelCount() >= std::numeric_limits<std::int32_t>::max())
    throw BadInput(source, "grid too large for the fat forest (2^31 voxels or more)");
  if (!(options.maxDistanceMm >= 0)) throw UsageError("fat forest: maxDistanceMm must be >= 0");
  if (std::isnan(options.gatherRadiusMm)) throw UsageError("fat forest: gatherRadiusMm is NaN");
}

// thickness(s) = the largest tree thickness of the skin voxels within `radius` of s (fat_forest.h).
Grid<float> gatherAlongSkin(const Grid<float>& tree, const std::vector<std::uint8_t>& kind, double radius) {
  if (radius == 0) return tree;
  const GridGeometry& g = tree.geometry;
  const Eigen::Matrix3d M = g.direction * g.spacing.asDiagonal();
  const Eigen::Matrix3d Minv = M.inverse();
  struct Offset { int di, dj, dk; };
  std::vector<Offset> ball;
  Eigen::Vector3i reach;
  for (int a = 0; a < 3; ++a) reach[a] = int(std::floor(radius * Minv.row(a).norm() + 1e-9));
  for (int dk = -reach.z(); dk <= reach.z(); ++dk)
    for (int dj = -reach.y(); dj <= reach.y(); ++dj)
      for (int di = -reach.x(); di <= reach.x(); ++di)
        if ((M * Eigen::Vector3d(di, dj, dk)).norm() <= radius * (1 + 1e-9)) ball.push_back({di, dj, dk});
  Grid<float> out(g, 0.0f);
  tbb::parallel_for(0, g.size.z(), [&](int k) {
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i) {
        const std::int64_t v = g.linearIndex(i, j, k);
        if (kind[v] != kSkin) continue;
        float t = 0;
        for (const Offset& o : ball) {
          if (!g.contains(i + o.di, j + o.dj, k + o.dk)) continue;
          const std::int64_t w = g.linearIndex(i + o.di, j + o.dj, k + o.dk);
          if (kind[w] == kSkin) t = std::max(t, tree.values[w]);
        }
        out.values[v] = t;
      }
  });
  return out;
}

// Multi-source Dijkstra over the 26-neighbourhood, writing distance, root and parent of every fat voxel it
// reaches (fat_forest.h). `kind` marks skin and fat; fat voxels become kSettled when popped.
//
// The queue is Dial's bucket queue: bucket b holds voxels with distance in [bW, (b+1)W). With W no longer
// than the shortest step, relaxing a voxel of bucket b only fills later buckets, so voxels of one bucket
// cannot improve each other and popping them in any order is exact Dijkstra, with O(1) pushes and pops.
// Stale entries (a voxel improved after it was pushed) are skipped as settled.
class Grower {
 public:
  Grower(const GridGeometry& g, std::vector<std::uint8_t>& kind, std::vector<float>& distance,
         std::vector<std::int32_t>& root, std::vector<std::int32_t>& parent, float maxDistance)
      : g_(g), kind_(kind), distance_(distance), root_(root), parent_(parent), maxDistance_(maxDistance),
        steps_(neighbourSteps(g)), M_(g.direction * g.spacing.asDiagonal()) {
    float shortest = std::numeric_limits<float>::infinity();
    for (const Neighbour& s : steps_) shortest = std::min(shortest, s.length);
    W_ = shortest * 0.999f;  // round-off margin
    // Sums of the same steps in another order differ by round-off only; the tie tolerance stays far
    // below the bucket margin (shortest − W) so a tie never lands in the bucket being popped.
    tie_ = shortest * 1e-4f;
  }

  // Grows the forest from every skin voxel; returns the number of queue entries popped.
  std::int64_t run() {
    // Skin voxels are sources at distance 0, settled in index order without going through bucket 0.
    for (std::int64_t v = 0; v < std::int64_t(kind_.size()); ++v)
      if (kind_[v] == kSkin) relax(v);
    std::int64_t pops = 0;
    for (std::size_t b = 0; b < buckets_.size(); ++b) {
      for (std::size_t e = 0; e < buckets_[b].size(); ++e) {  // by index: relax() may grow buckets_
        const std::int32_t v = buckets_[b][e];
        ++pops;
        if (kind_[v] != kFat) continue;  // settled from an earlier entry
        kind_[v] = kSettled;
        relax(v);
      }
      std::vector<std::int32_t>().swap(buckets_[b]);
    }
    return pops;
  }

 private:
  void push(float d, std::int64_t w) {
    const std::size_t b = std::size_t(d / W_);
    if (b >= buckets_.size()) buckets_.resize(b + 1);
    buckets_[b].push_back(std::int32_t(w));
  }

  // Squared world distance between two voxel centres.
  double straight2(std::int64_t a, std::int64_t b) const {
    const std::int64_t nx = g_.size.x(), ny = g_.size.y();
    const Eigen::Vector3d d(double(a % nx - b % nx), double((a / nx) % ny - (b / nx) % ny),
                            double(a / (nx * ny) - b / (nx * ny)));
    return (M_ * d).squaredNorm();
  }

  // Settles voxel v: offers each unsettled fat neighbour the path through v. Among paths of equal length
  // (frequent on a grid: many staircases tie) the one whose root is nearer in a straight line wins, so
  // trees grow as columns under their skin voxel rather than as wedges decided by the order of
  // relaxation. Interior voxels skip bounds checks.
  void relax(std::int64_t v) {
    const int nx = g_.size.x(), ny = g_.size.y(), nz = g_.size.z();
    const int i = int(v % nx), j = int((v / nx) % ny), k = int(v / (std::int64_t(nx) * ny));
    const bool interior = i > 0 && j > 0 && k > 0 && i < nx - 1 && j < ny - 1 && k < nz - 1;
    const float d = distance_[v];
    for (const Neighbour& s : steps_) {
      if (!interior && !g_.contains(i + s.di, j + s.dj, k + s.dk)) continue;
      const std::int64_t w = v + s.delta;
      if (kind_[w] != kFat) continue;
      const float candidate = d + s.length;
      if (candidate > maxDistance_ || candidate > distance_[w] + tie_) continue;
      if (candidate >= distance_[w] - tie_ &&
          (root_[w] == root_[v] || straight2(w, root_[v]) >= straight2(w, root_[w])))
        continue;  // a tie that does not bring a nearer root
      // On a tie the distance keeps the smaller value: distances stay exact shortest-path lengths, and a
      // path walked through the parents may differ from it by round-off only.
      distance_[w] = std::min(candidate, distance_[w]);
      parent_[w] = std::int32_t(v);
      root_[w] = root_[v];
      push(distance_[w], w);
    }
  }

  const GridGeometry& g_;
  std::vector<std::uint8_t>& kind_;
  std::vector<float>& distance_;
  std::vector<std::int32_t>& root_;
  std::vector<std::int32_t>& parent_;
  const float maxDistance_;
  const std::array<Neighbour, 26> steps_;
  const Eigen::Matrix3d M_;
  float W_ = 1, tie_ = 0;
  std::vector<std::vector<std::int32_t>> buckets_;
};

}  // namespace

FatForest::FatForest(const Mask& skin, const Mask& fat, const FatForestOptions& options, const std::string& source) {
  checkInputs(skin, fat, options, source);
  const auto start = std::chrono::steady_clock::now();
  geometry_ = skin.geometry;
  const GridGeometry& g = geometry_;
  const std::int64_t n = g.voxelCount();
  distance_.assign(n, std::numeric_limits<float>::infinity());
  root_.assign(n, -1);
  parent_.assign(n, -1);
  std::vector<std::uint8_t> kind(n, kOther);
  for (std::int64_t v = 0; v < n; ++v) {
    if (skin.values[v]) {
      kind[v] = kSkin, distance_[v] = 0, root_[v] = std::int32_t(v);
      ++stats_.skinVoxels;
    } else if (fat.values[v]) {
      kind[v] = kFat;
      ++stats_.fatVoxels;
    }
  }
  if (stats_.skinVoxels == 0) throw BadInput(source, "the skin mask is empty");

  stats_.queuePops = Grower(g, kind, distance_, root_, parent_, float(options.maxDistanceMm)).run();

  treeThickness_ = Grid<float>(g, 0.0f);
  for (std::int64_t v = 0; v < n; ++v) {
    if (kind[v] != kSettled) continue;
    ++stats_.reachedFatVoxels;
    float& t = treeThickness_.values[root_[v]];
    if (t == 0) ++stats_.skinVoxelsWithFat;
    t = std::max(t, distance_[v]);
  }
  const double diagonal = (g.direction * g.spacing).norm();
  thickness_ = gatherAlongSkin(treeThickness_, kind, options.gatherRadiusMm < 0 ? diagonal : options.gatherRadiusMm);
  stats_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::vector<std::int32_t> FatForest::pathToRoot(std::int64_t voxel) const {
  std::vector<std::int32_t> path;
  if (voxel < 0 || voxel >= std::int64_t(root_.size()) || root_[voxel] < 0) return path;
  for (std::int32_t v = std::int32_t(voxel); v >= 0; v = parent_[v]) path.push_back(v);
  return path;
}

}  // namespace vesalius::fat
