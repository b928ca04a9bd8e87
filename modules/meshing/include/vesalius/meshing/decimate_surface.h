// Decimation of a triangle surface to a target face count by edge collapses: Garland and Heckbert's
// quadric error metric ("Surface simplification using quadric error metrics", SIGGRAPH 1997) with each
// collapse placed where it keeps the volume its fans enclose (Lindstrom and Turk, "Fast and memory
// efficient polygonal simplification", IEEE Visualization 1998), and only collapses that satisfy the link
// condition (Dey, Edelsbrunner, Guha, Nekhayev, "Topology preserving edge contraction", 1999), so a closed
// 2-manifold stays closed and 2-manifold with its handles. A collapse is also refused where it would turn a
// triangle over, leave one thinner than a shape quality (2√3·area / Σ edge²) of 0.05 and half of what it
// was, or make a triangle meet another (self_intersections.h), so a surface free of crossings stays free of
// them. Vertices on open or non-manifold edges stay where they are.
//
// A piece can get no fewer than a tetrahedron's four triangles, so a piece whose share of the target (in
// proportion to its area) is under four is below the decimation's resolution and is left out (the largest
// piece always stays): a label's crumbs, each a few triangles, would otherwise be slivers that TetGen fills
// with tets. A closed surface then reaches the target exactly (within the one triangle of parity) unless its
// handles need more triangles. Templates
// with fine surfaces need this before TetGen, which keeps every input triangle (a 30k-triangle muscle gives
// 150k tets whatever the target).
#pragma once

#include "vesalius/core/mesh.h"

#include <vector>

namespace vesalius::meshing {

// surface: #V by 3 and #F by 3. Returns it unchanged when it has no more than targetFaces triangles (or
// targetFaces <= 0). Face and vertex attributes are not carried. Throws BadInput if a triangle names a
// missing vertex.
TriMesh decimateSurface(const TriMesh& surface, int targetFaces);

// Surfaces that share no vertex (each #V by 3, #F by 3), each decimated to its own target as decimateSurface
// does, together: no collapse makes a triangle of one meet a triangle of any, so surfaces that were apart
// (nested regions for TetGen) stay apart. A target <= 0 keeps its surface as it is (an obstacle to the
// others). Throws UsageError unless there is one target per surface.
std::vector<TriMesh> decimateSurfacesApart(const std::vector<const TriMesh*>& surfaces,
                                           const std::vector<int>& targetFaces);

}  // namespace vesalius::meshing
