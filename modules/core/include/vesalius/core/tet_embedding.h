// Points embedded in a tet mesh and carried with its deformation: tissue vertices in the posing tet mesh
// (Sujar et al. 2018, §3.4-3.5), a textured surface in a fitted template (Wang et al. 2021, §4.3).
//
// Each point is located once in the rest tet mesh (TetLocator: a bounding-volume hierarchy in place of
// Sujar et al.'s spatial hash) and keeps its tet and its barycentric coordinates there. Deformed, it is the
// same combination of that tet's deformed corners, i.e. the tet's affine map applied to the point. A point
// outside the mesh (Sujar et al. 2018 met 4.6 % such tissue vertices) takes the nearest tet and its unclamped
// barycentric coordinates in it, so it keeps its offset from the surface, deformed with that tet, instead
// of being snapped onto the surface. An affine deformation of the tet mesh therefore moves every point
// exactly, inside or outside.
//
// Carrying is per point, a weighted sum of four corners: with about 0.3 points per tet (Sujar et al.'s sizes)
// this costs less than forming each tet's affine map (posing/tet_affine_maps.h) every frame. It reads the
// corners where the points' tets are, so points in a spatially coherent order (as a mesh's vertices come)
// carry several times faster than points in random order.
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Core>

namespace vesalius {

struct TetEmbedding {
  Eigen::VectorXi tet;                                   // #P: containing (or nearest) tet of each point
  MatrixX4i corners;                                     // #P by 4: that tet's vertex indices
  Eigen::Matrix<double, Eigen::Dynamic, 4> barycentric;  // #P by 4: weights of the corners, summing to 1

  // deformedV: #V by 3 deformed tet mesh vertices. Returns #P by 3 carried points. Throws UsageError if
  // an embedded corner is not a row of deformedV.
  MatrixX3d apply(const MatrixX3d& deformedV) const;
  // The same into `carried` (resized to #P by 3; not deformedV itself), which a caller carrying many frames
  // keeps. After a throw, carried holds the points with valid corners only.
  void apply(const MatrixX3d& deformedV, MatrixX3d& carried) const;
};

// V: #V by 3 rest tet mesh vertices, T: #T by 4 tets, P: #P by 3 points in the same rest space. Throws
// BadInput if the tet mesh has no tets.
TetEmbedding embedInTets(const MatrixX3d& V, const MatrixX4i& T, const MatrixX3d& P);

}  // namespace vesalius
