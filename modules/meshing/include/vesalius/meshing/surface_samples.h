// Points spread evenly over a surface: stand-ins for the ICP markers a radiologist picks on an organ's
// boundary (Wang et al. 2021, §3.1: "clear representative points on the organ boundary"; §4.1.1: ~50-100 per
// muscle, "as many reliable points as possible"), for tests and benchmarks of the organ fitter.
//
// Method: `candidates` points are drawn uniformly by area (a triangle with probability proportional to
// its area, then a uniform point in it: barycentric (1 - √u, √u (1 - v), √u v), Osada et al., "Shape
// distributions", ACM TOG 2002, §4.2), and `count` of them are chosen by farthest-point sampling
// (Gonzalez 1985, "Clustering to minimize the maximum intercluster distance"; Eldar et al. 1997): the
// first candidate, then repeatedly the candidate farthest (Euclidean) from those chosen so far, ties to the
// lowest index. Every chosen point is thus at least as far from the others as any unchosen candidate is
// from the chosen set, which is what keeps them evenly spread. Cost: O(count · candidates).
//
// Deterministic: the random numbers are std::mt19937_64 (whose output the C++ standard fixes) seeded with
// `seed`, turned into doubles as (draw >> 11) · 2^-53 in [0, 1); no std:: distribution is used (their
// output is implementation-defined), so a seed gives the same points with every standard library.
// The points lie on the triangles up to round-off (1e-12 relative).
#pragma once

#include "vesalius/core/grid.h"
#include "vesalius/core/mesh.h"

#include <cstdint>

namespace vesalius::meshing {

struct SpreadOptions {
  // Area-uniform candidates the points are chosen from; 0: 32 per point (at least 1000). More candidates
  // spread the points a little more evenly: on a sphere with 200 points the smallest spacing is on
  // average 0.71 sqrt(area / count) with 8 per point, 0.76 with 32, 0.78 with 128 (never below 0.62 in
  // theory, see the test; a hexagonal packing would give 1.07).
  int candidates = 0;
};

// `count` points spread evenly over the triangles of `surface` (V: #V by 3, F: #F by 3; it need not be
// closed; unreferenced vertices are ignored). Returns #count by 3, in the order chosen: every prefix of
// the rows is itself spread evenly. Throws UsageError if count <= 0 or count exceeds the candidates, and
// BadInput if the surface has no triangles, no area, or non-finite coordinates.
MatrixX3d spreadSurfacePoints(const TriMesh& surface, int count, std::uint64_t seed,
                              const SpreadOptions& options = {});

// The part of a label surface (labelSurface, in the same world space as `scan`) that is the label's
// boundary inside the scan: the faces whose three vertices all lie within the box of `scan`'s voxel
// centres (continuous index in [0, size - 1] along each axis, to 1e-9 voxel). A label cut by the edge of
// the scan is closed by labelSurface half a voxel beyond the last voxel centres; that cap is the scan's
// edge, not the organ's, and no radiologist would put a marker on it. V and vertex attributes are kept as
// they are; F and the face attributes keep the faces that remain, in order.
TriMesh withinScan(const TriMesh& surface, const GridGeometry& scan);

}  // namespace vesalius::meshing
