// Self-intersections of a triangle surface: pairs of triangles that cross or touch where a valid closed
// 2-manifold never does. TetGen aborts on such input, and `vesalius info` reports them.
//
// Method: candidate pairs come from the triangles' BoxTree (boxes that overlap); each candidate is decided
// by orientation tests. Two triangles meet exactly when an edge of one meets the other (the ends of the
// segment where they meet lie on their edges; coplanar triangles are compared in the plane), so a pair
// costs at most six segment-triangle tests (Möller, "A fast triangle-triangle intersection test",
// J. Graphics Tools 1997, gives the same answer in fewer operations; this form handles shared vertices
// simply). Triangles that share mesh vertices are compared away from what they share:
//   - one shared vertex: they intersect if the edge opposite the shared vertex of either meets the other
//     triangle (anything else they have in common would have to leave the shared corner through one);
//   - one shared edge: they intersect only if they fold onto each other (coplanar within round-off,
//     third vertices on the same side of the edge), as after a flipped triangle;
//   - three shared vertices (a duplicated triangle): always reported.
// Contact counts as intersection (closed triangles). Arithmetic is plain double precision, so contacts
// closer than round-off may be missed or reported; crossings that matter to meshing are not.
#pragma once

#include "vesalius/core/mesh.h"

#include <array>
#include <utility>
#include <vector>

namespace vesalius {

// V: #V by 3, F: #F by 3. Returns the intersecting pairs (i < j, indices into F), sorted.
// Throws BadInput if F indexes outside V.
std::vector<std::pair<int, int>> selfIntersections(const MatrixX3d& V, const MatrixX3i& F);

// The intersecting pairs with at least one triangle in `candidates` (indices into F), sorted: after a few
// vertices moved on a surface that was clean, only the triangles around them need testing.
// Throws UsageError if a candidate is not a row of F.
std::vector<std::pair<int, int>> selfIntersections(const MatrixX3d& V, const MatrixX3i& F,
                                                   const std::vector<int>& candidates);

// Whether triangles a and b of one mesh (vertex indices a, b; corner positions pa, pb) meet beyond what they
// share, by the rules above: the test selfIntersections makes of each pair.
bool meshTrianglesMeet(std::array<int, 3> a, std::array<Eigen::Vector3d, 3> pa, std::array<int, 3> b,
                       std::array<Eigen::Vector3d, 3> pb);

// Whether the closed triangles (a0, a1, a2) and (b0, b1, b2) meet, ignoring connectivity.
bool trianglesIntersect(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& a2,
                        const Eigen::Vector3d& b0, const Eigen::Vector3d& b1, const Eigen::Vector3d& b2);

}  // namespace vesalius
