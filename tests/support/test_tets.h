// Tet meshes built in tests: a box of cubes, each split into six tets around its main diagonal
// (Freudenthal/Kuhn), which conform across neighbouring cubes.
#pragma once

#include "vesalius/core/mesh.h"

#include <array>
#include <utility>

namespace vesalius::test {

// A box [0, nx·h] × [0, ny·h] × [0, nz·h] of (nx·ny·nz) cubes of side h, 6 tets each, positively oriented.
inline TetMesh boxTets(int nx, int ny, int nz, double h = 1.0) {
  TetMesh m;
  const auto id = [&](int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; };
  m.V.resize((nx + 1) * (ny + 1) * (nz + 1), 3);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) m.V.row(id(i, j, k)) << i * h, j * h, k * h;
  // The six monotone lattice paths from corner (0,0,0) to (1,1,1), one tet each.
  const std::array<std::array<int, 3>, 6> orders{{{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  m.T.resize(6 * nx * ny * nz, 4);
  int t = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const auto& order : orders) {
          std::array<int, 3> c{i, j, k};
          std::array<int, 4> tet;
          tet[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[order[s]];
            tet[s + 1] = id(c[0], c[1], c[2]);
          }
          const Eigen::RowVector3d a = m.V.row(tet[1]) - m.V.row(tet[0]), b = m.V.row(tet[2]) - m.V.row(tet[0]),
                                   d = m.V.row(tet[3]) - m.V.row(tet[0]);
          if (a.dot(b.cross(d)) < 0) std::swap(tet[2], tet[3]);
          m.T.row(t++) << tet[0], tet[1], tet[2], tet[3];
        }
  return m;
}

}  // namespace vesalius::test
