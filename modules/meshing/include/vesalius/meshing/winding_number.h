// Generalized winding numbers of triangle soups: about 1 inside, 0 outside, 1/2 on the surface, and still
// meaningful where the surface has holes, flaps, duplicated or crossing triangles (Jacobson, Kavan,
// Sorkine-Hornung, "Robust inside-outside segmentation using generalized winding numbers", SIGGRAPH 2013,
// eq. 1 and §3.1: the solid angle of each triangle by van Oosterom and Strackee, summed over 4π).
//
// Fast evaluation (Barill, Dickson, Schmidt, Levin, Jacobson, "Fast winding numbers for soups and clouds",
// SIGGRAPH 2018, §3.2-3.3): the triangles are held in a bounding-volume hierarchy; a node whose triangles
// lie within radius r of their area-weighted centre p̃ counts, for a query q farther than beta·r from p̃, as
// one dipole, the first-order term of eq. 8: N · (p̃ - q) / (4π |p̃ - q|³), N being the sum of the
// triangles' area-weighted normals. Nearer nodes are opened; leaves are summed exactly. Barill et al. use
// beta = 2 with a second-order expansion; with the first-order one here beta = 2 erred by up to 0.044 on a
// sphere, beta = 3 by 0.015 (tests/meshing/closed_surface_test.cpp, docs/methods/closed-surfaces.md).
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/core/triangle_tree.h"

#include <vector>

namespace vesalius::meshing {

struct WindingNumberOptions {
  // A node is approximated by its dipole when the query is farther than beta times its radius; larger is
  // more accurate and slower; 0 sums every triangle exactly.
  double beta = 3.0;
};

// The winding number of the triangles (V #V by 3, F #F by 3, any orientation consistent with "outside
// is counter-clockwise") at each row of P (#P by 3); in parallel (TBB). Throws BadInput if F indexes
// outside V, UsageError if beta is negative.
Eigen::VectorXd windingNumbers(const MatrixX3d& V, const MatrixX3i& F, const MatrixX3d& P,
                               const WindingNumberOptions& options = {});

// A row of P inside a closed surface and the closest point on that surface (its distance is the row's
// depth).
struct PointInside {
  Eigen::Index row = 0;
  ClosestPoint closest;
};

// The rows of P (#P by 3) inside the closed surface (V, F): winding number at least 1/2. How deep one
// tissue reaches into another (transfer/anatomy_rules.h) and where a tissue is moved out of one.
std::vector<PointInside> pointsInside(const MatrixX3d& V, const MatrixX3i& F, const MatrixX3d& P);

}  // namespace vesalius::meshing
