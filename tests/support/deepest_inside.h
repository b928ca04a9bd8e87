// How deep two closed surfaces reach into each other, measured apart from the methods under test: each
// surface's vertices inside the other by winding number, their distance to its closest triangle.
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/meshing/winding_number.h"

#include <algorithm>
#include <cmath>

namespace vesalius::test {

// The deepest vertex of either mesh inside the other (0: apart), mm.
inline double deepestEitherWay(const TriMesh& a, const TriMesh& b) {
  double deepest = 0;
  for (const meshing::PointInside& in : meshing::pointsInside(a.V, a.F, b.V))
    deepest = std::max(deepest, std::sqrt(in.closest.squaredDistance));
  for (const meshing::PointInside& in : meshing::pointsInside(b.V, b.F, a.V))
    deepest = std::max(deepest, std::sqrt(in.closest.squaredDistance));
  return deepest;
}

}  // namespace vesalius::test
