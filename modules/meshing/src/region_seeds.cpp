// Region seeds by inward rays (see region_seeds.h).
#include "region_seeds.h"

#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/triangle_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace vesalius::meshing {
namespace {

using Vec3 = Eigen::Vector3d;

// Connected part of each triangle (triangles joined through shared vertices), by union-find.
std::vector<int> triangleParts(Eigen::Index vertexCount, const MatrixX3i& F, int& count) {
  std::vector<int> parent(static_cast<std::size_t>(vertexCount));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 1; k < 3; ++k) parent[find(F(f, k))] = find(F(f, 0));
  std::vector<int> id(parent.size(), -1), part(std::size_t(F.rows()));
  count = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    int& root = id[find(F(f, 0))];
    if (root < 0) root = count++;
    part[f] = root;
  }
  return part;
}

Vec3 corner(const TriMesh& m, Eigen::Index f, int k) { return m.V.row(m.F(f, k)).transpose(); }

// Distance along the ray o + t d (t > 0) to triangle f, or infinity (Möller and Trumbore 1997).
double rayHit(const TriMesh& m, Eigen::Index f, const Vec3& o, const Vec3& d) {
  const Vec3 a = corner(m, f, 0), e1 = corner(m, f, 1) - a, e2 = corner(m, f, 2) - a;
  const Vec3 p = d.cross(e2);
  const double det = e1.dot(p);
  if (det == 0.0) return std::numeric_limits<double>::infinity();
  const Vec3 s = o - a;
  const double u = s.dot(p) / det;
  const Vec3 q = s.cross(e1);
  const double v = d.dot(q) / det, t = e2.dot(q) / det;
  if (u < 0 || v < 0 || u + v > 1 || t <= 0) return std::numeric_limits<double>::infinity();
  return t;
}

// The best inward-ray midpoint over the largest triangles of one part. "Inward" is against the triangle's
// normal, towards the material (side(f) = -1), or with it (+1): into the cavity an inner shell bounds,
// or into the label a partition's triangle faces.
template <class Side>
RegionSeed seedOfPart(const TriMesh& all, const TriangleTree& tree, std::vector<int> triangles, Side side) {
  auto area = [&](int f) { return (corner(all, f, 1) - corner(all, f, 0)).cross(corner(all, f, 2) - corner(all, f, 0)).norm(); };
  const std::size_t tries = std::min<std::size_t>(8, triangles.size());
  std::partial_sort(triangles.begin(), triangles.begin() + long(tries), triangles.end(),
                    [&](int f, int g) { return area(f) > area(g); });
  RegionSeed best;
  for (std::size_t i = 0; i < tries; ++i) {
    const int f = triangles[i];
    const Vec3 o = (corner(all, f, 0) + corner(all, f, 1) + corner(all, f, 2)) / 3.0;
    const Vec3 d = side(f) * (corner(all, f, 1) - corner(all, f, 0)).cross(corner(all, f, 2) - corner(all, f, 0)).normalized();
    double hit = std::numeric_limits<double>::infinity();
    for (Eigen::Index g = 0; g < all.F.rows(); ++g)
      if (g != f) hit = std::min(hit, rayHit(all, g, o, d));
    if (!std::isfinite(hit)) continue;
    const Vec3 point = o + 0.5 * hit * d;
    const double clearance = std::sqrt(tree.closest(point).squaredDistance);
    if (clearance > best.clearance) best = {point, 0, clearance};
  }
  return best;
}

// Whether p is inside the triangles `faces` (closed), by the parity of crossings along a fixed oblique ray.
bool inside(const TriMesh& all, const std::vector<int>& faces, const Vec3& p) {
  const Vec3 d = Vec3(0.5773, 0.5774, 0.5775).normalized();  // off the axes, which voxel surfaces align with
  int crossings = 0;
  for (int f : faces) crossings += std::isfinite(rayHit(all, f, p, d));
  return crossings % 2 == 1;
}

// The surface whose region a cavity point lies in: the smallest other surface holding it; -1 if none.
int enclosingSurface(const TriMesh& all, const std::vector<std::vector<int>>& facesOf, int self, const Vec3& p) {
  int best = -1;
  double smallest = std::numeric_limits<double>::infinity();
  for (int s = 0; s < int(facesOf.size()); ++s) {
    if (s == self || !inside(all, facesOf[std::size_t(s)], p)) continue;
    const double volume = enclosedVolume(all.V, all.F(facesOf[std::size_t(s)], Eigen::all));
    if (volume < smallest) best = s, smallest = volume;
  }
  return best;
}

}  // namespace

std::vector<RegionSeed> regionSeeds(const TriMesh& all, const std::vector<int>& owner) {
  int count = 0;
  const std::vector<int> part = triangleParts(all.V.rows(), all.F, count);
  std::vector<std::vector<int>> triangles(static_cast<std::size_t>(count));
  for (Eigen::Index f = 0; f < all.F.rows(); ++f) triangles[part[f]].push_back(int(f));
  const TriangleTree tree(all.V, all.F);
  std::vector<std::vector<int>> facesOf;
  for (Eigen::Index f = 0; f < all.F.rows(); ++f) {
    if (owner[f] >= int(facesOf.size())) facesOf.resize(std::size_t(owner[f]) + 1);
    facesOf[std::size_t(owner[f])].push_back(int(f));
  }
  std::vector<RegionSeed> seeds;
  for (int p = 0; p < count; ++p) {
    const int surface = owner[triangles[p].front()];
    if (enclosedVolume(all.V, all.F(triangles[p], Eigen::all)) >= 0.0) {
      RegionSeed seed = seedOfPart(all, tree, triangles[p], [](int) { return -1.0; });
      seed.region = surface;
      if (seed.clearance <= 0.0)
        throw NumericalFailure("tetrahedralize: no point found inside a part of surface " +
                               std::to_string(seed.region) + " (is it flat?)");
      seeds.push_back(seed);
      continue;
    }
    // An inner shell (a hollow in a bone): its material lies outside it, in the cell its outer shell's
    // seed already names; a ray against its normals would leave the surface and could land in another
    // cell (a crumb of a hand turned inside out seeded the forearm). Its cavity belongs to the surface
    // around the shell's surface (the body), if any; otherwise it stays empty.
    RegionSeed cavity = seedOfPart(all, tree, triangles[p], [](int) { return 1.0; });
    cavity.region = cavity.clearance > 0.0 ? enclosingSurface(all, facesOf, surface, cavity.point) : -1;
    if (cavity.region >= 0) seeds.push_back(cavity);
  }
  return seeds;
}

std::vector<RegionSeed> partitionSeeds(const TriMesh& all, const Eigen::MatrixX2i& sides, const std::vector<int>& labels) {
  const TriangleTree tree(all.V, all.F);
  std::vector<RegionSeed> seeds;
  for (std::size_t region = 0; region < labels.size(); ++region) {
    const int label = labels[region];
    std::vector<int> faces;
    for (Eigen::Index f = 0; f < all.F.rows(); ++f)
      if (sides(f, 0) == label || sides(f, 1) == label) faces.push_back(int(f));
    int count = 0;
    const std::vector<int> part = triangleParts(all.V.rows(), all.F(faces, Eigen::all), count);
    std::vector<std::vector<int>> triangles(static_cast<std::size_t>(count));
    for (std::size_t i = 0; i < faces.size(); ++i) triangles[std::size_t(part[i])].push_back(faces[i]);
    for (const std::vector<int>& t : triangles) {
      RegionSeed seed = seedOfPart(all, tree, t, [&](int f) { return sides(f, 0) == label ? -1.0 : 1.0; });
      if (seed.clearance <= 0.0)
        throw NumericalFailure("tetrahedralize: no point found inside a part of label " + std::to_string(label));
      seed.region = int(region);
      seeds.push_back(seed);
    }
  }
  return seeds;
}

}  // namespace vesalius::meshing
