// Which tets hold each vertex, and the rings of tets around a set of vertices: the neighbourhoods that
// local repairs of a tet mesh work on (interpenetration removal, untangling after skinning, dihedral
// smoothing).
#pragma once

#include "vesalius/core/mesh.h"

#include <vector>

namespace vesalius {

// The tets holding each vertex, in compressed rows: those of vertex v are tets[start[v] .. start[v + 1]),
// ascending.
struct VertexTets {
  std::vector<int> start;  // #V + 1
  std::vector<int> tets;   // 4#T
  const int* begin(int v) const { return tets.data() + start[std::size_t(v)]; }
  const int* end(int v) const { return tets.data() + start[std::size_t(v) + 1]; }
  std::vector<int> of(int v) const { return {begin(v), end(v)}; }
};

// T: #T by 4, every index in [0, vertexCount). Throws BadInput otherwise.
VertexTets vertexTets(const MatrixX4i& T, Eigen::Index vertexCount);

// The vertices within `rings` rings of `seeds`: ring 0 is the seeds, ring r + 1 every vertex of a tet that
// holds a vertex of ring r. Each vertex once, ring by ring. `tetsOf` is vertexTets(T, ...).
std::vector<int> vertexRings(const MatrixX4i& T, const VertexTets& tetsOf, const std::vector<int>& seeds, int rings);

}  // namespace vesalius
