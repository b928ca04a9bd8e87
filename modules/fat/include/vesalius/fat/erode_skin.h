// Volume erosion: the skin surface moved inward by the subcutaneous fat thickness (Dicko et al. 2013, §5 and
// Fig. 2.b: "For each vertex of the target, we compute the local depth using the texture coordinates
// and we move the vertex by this distance following the forest of shortest paths.").
//
// Method, per vertex x with thickness t (mm):
//  1. Direction. With a FatForest: every skin voxel within pathRadiusMm of x whose tree holds fat points
//     from x toward its tree's deepest voxel, the end of its longest forest path; d is the mean of these
//     unit vectors weighted by the trees' depths. Without a forest, with no such tree near, or where d is
//     more than acos(minPathCosine) off the inward normal (trees that grew along the skin), d is the
//     inward normal: area-weighted vertex normals averaged with their 1-ring normalSmoothingIterations
//     times. Path directions are averaged with their 1-ring directionSmoothingIterations times.
//  2. Room. r(x): how deep a ball fits inside the surface below x along the inward normal n, by relaxed
//     ball shrinking (after Ma, Bai, Zhang, "3D medial axis point approximation using nearest neighbors
//     and the normal field", Visual Computer 2012, Alg. 1): the largest s for which the ball of radius
//     κs, κ = 0.9, centred at x + s·n holds no surface point except on x's own triangles. Starting
//     from s = t / maxFractionOfInnerRadius (a deeper ball allows the whole move anyway), each nearest
//     point q inside the ball cuts s to where q leaves it. In a tube or sphere of radius ρ,
//     r = 2ρ / (1 + κ) = 1.05ρ; r also shrinks where the surface is sharply convex (a fingertip, a thin
//     rim) or another sheet lies close below (eyelids, lips). Deviation: the exact method (κ = 1, a ball
//     tangent at x) collapses wherever a vertex normal is a degree or two off the mesh (measured over
//     the vertices of a sphere of radius 100 and 10,242 vertices: down to 48 mm); κ < 1 and leaving
//     out x's own triangles tolerate normals up to acos κ = 25.8° off.
//  3. Limiter. The move is min(t, maxFractionOfInnerRadius · r). Each needed reduction t − move spreads
//     to the neighbours (limitSmoothingIterations rounds of ρ ← max(ρ_needed, mean of the 1-ring's ρ))
//     so a limited region tapers instead of stepping; where nothing is limited the move is t exactly.
//  4. Repair. Triangle pairs that cross after the move and did not before (core/self_intersections.h):
//     the moves of their vertices are halved and the reductions spread again, at most maxRepairRounds
//     times; in the last quarter of the rounds the offending vertices stay where they were. What still
//     crosses is counted in the result, never hidden.
// The faces are not touched: topology (and closedness) is that of the input.
//
// Deviations: the paper moves "following the forest"; here a vertex moves in a straight line toward the
// ends of the paths near it, by the thickness (a path itself is a 26-neighbour staircase, up to 12.8 %
// longer than the straight line, fat_forest.h). One path's end on the grid is off to the side by up to
// a voxel or two: toward the single deepest tree the directions were 7.0° off radial on average under a
// spherical shell of 1.2 mm voxels, the weighted mean 3.5° (tests/fat/erode_skin_test.cpp). The paper
// has no limiter; without it a uniform 5 mm crosses 3,547 triangle pairs of the MakeHuman thin body and
// flips 1,774 triangles (fingers, toes, eyelids). The room could be measured by a ray cast to the
// opposite side; core has no ray query, and a ray along a fingertip's axis reports ample room where the
// ball does not.
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/fat/fat_forest.h"

#include <Eigen/Core>

#include <string>

namespace vesalius::fat {

struct ErodeSkinOptions {
  double pathRadiusMm = 0;              // skin voxels this near a vertex offer their trees; 0: two voxel
                                        // diagonals (the vertex radius plus the forest's gathering radius)
  double minPathCosine = 0.25;          // path directions at more than ~75° from the inward normal are not used
  int normalSmoothingIterations = 3;    // 1-ring averaging of the area-weighted vertex normals
  int directionSmoothingIterations = 2; // 1-ring averaging of the path directions
  double maxFractionOfInnerRadius = 0.5;  // a move is at most this fraction of r(x); +infinity: no limit
  int limitSmoothingIterations = 4;     // spreading of the reductions
  int maxRepairRounds = 12;
  std::string source;                   // names the thickness's origin in BadInput messages
};

struct ErodedSkin {
  MatrixX3d V;                  // #V by 3, the eroded positions
  MatrixX3d direction;          // #V by 3, unit inward directions (zero for a vertex in no triangle)
  Eigen::VectorXd displacement; // #V, mm moved
  Eigen::VectorXd innerRadius;  // #V, r(x) in mm, computed up to t / maxFractionOfInnerRadius (0 if t = 0)
  enum Direction : int { kNone = 0, kPath = 1, kNormal = 2 };
  Eigen::VectorXi directionSource;  // #V
  Eigen::Index movedAlongPaths = 0, movedAlongNormals = 0;  // vertices moved (> 0 mm) each way
  Eigen::Index limited = 0;    // vertices whose thickness exceeded the fraction of r(x)
  Eigen::Index reduced = 0;    // vertices that moved less than their thickness (limited, spread, repaired)
  Eigen::Index repaired = 0;   // vertices whose move the repair cut
  int repairRounds = 0;
  double maxDisplacement = 0, meanDisplacement = 0;  // mm, over all vertices
  long selfIntersectionsBefore = 0;  // crossing triangle pairs of the input
  long selfIntersectionsAfter = 0;   // of the output, all of them
  long newSelfIntersections = 0;     // of the output, pairs that did not cross in the input
};

// V: #V by 3 (LPS mm), F: #F by 3, counter-clockwise seen from outside (an inside-out mesh, of negative
// enclosed volume, is turned around); thickness: #V, mm, finite and >= 0. forest: optional, in the same
// world space. Throws BadInput (naming options.source) for a thickness of the wrong length, NaN or
// negative; UsageError for negative options or a fraction outside (0, 1] (but +infinity); BadInput if F indexes
// outside V. Parallel over vertices (TBB); the result does not depend on the number of threads.
ErodedSkin erodeSkin(const MatrixX3d& V, const MatrixX3i& F, const Eigen::VectorXd& thickness,
                     const FatForest* forest = nullptr, const ErodeSkinOptions& options = {});

}  // namespace vesalius::fat
