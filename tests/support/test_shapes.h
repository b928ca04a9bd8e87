// Closed surfaces built in tests: a tetrahedron and an octahedron-based sphere.
#pragma once

#include "vesalius/core/mesh.h"

#include <algorithm>
#include <array>
#include <map>
#include <vector>

namespace vesalius::test {

// The tetrahedron with corners at the origin and `size` along each axis; outward.
inline TriMesh tetrahedron(double size) {
  TriMesh m;
  m.V.resize(4, 3);
  m.V << 0, 0, 0, size, 0, 0, 0, size, 0, 0, 0, size;
  m.F.resize(4, 3);
  m.F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  return m;
}

// Sphere of `radius` around `centre`: an octahedron whose triangles are split in four `levels` times,
// vertices pushed onto the sphere; outward, 8 * 4^levels triangles.
inline TriMesh sphere(int levels, double radius = 1.0, const Eigen::Vector3d& centre = Eigen::Vector3d::Zero()) {
  std::vector<Eigen::Vector3d> v{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  std::vector<std::array<int, 3>> f{{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                    {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto middle = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back(((v[a] + v[b]) / 2).normalized());
      return mid[key] = int(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& t : f) {
      const int ab = middle(t[0], t[1]), bc = middle(t[1], t[2]), ca = middle(t[2], t[0]);
      next.insert(next.end(), {{t[0], ab, ca}, {ab, t[1], bc}, {ca, bc, t[2]}, {ab, bc, ca}});
    }
    f = next;
  }
  TriMesh m;
  m.V.resize(Eigen::Index(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i) m.V.row(Eigen::Index(i)) = (centre + radius * v[i]).transpose();
  m.F.resize(Eigen::Index(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i) m.F.row(Eigen::Index(i)) << f[i][0], f[i][1], f[i][2];
  return m;
}

}  // namespace vesalius::test
