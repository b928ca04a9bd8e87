// Mapping tissue points into the tet mesh and carrying them with its deformation (seed 001 §3.4-3.5).
//
// Each point is located once in the rest tet mesh (TetLocator: a bounding-volume hierarchy in place of the
// seed's spatial hash) and keeps its tet and its barycentric coordinates there. Posed, it is the same
// combination of that tet's posed corners, i.e. the tet's affine map applied to the point (tet_affine_maps.h)
// as in the seed. A point outside the mesh (the seed met 4.6 % such tissue vertices) takes the nearest tet
// and its unclamped barycentric coordinates in it, so it keeps its offset from the surface, deformed with
// that tet, instead of being snapped onto the surface.
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Core>

namespace vesalius::posing {

struct TetEmbedding {
  Eigen::VectorXi tet;                             // #P: containing (or nearest) tet of each point
  MatrixX4i corners;                               // #P by 4: that tet's vertex indices
  Eigen::Matrix<double, Eigen::Dynamic, 4> barycentric;  // #P by 4: weights of the corners, summing to 1
};

// V: #V by 3 rest tet mesh vertices, T: #T by 4 tets, P: #P by 3 points in the same rest space. Throws
// BadInput if the tet mesh has no tets.
TetEmbedding embedInTets(const MatrixX3d& V, const MatrixX4i& T, const MatrixX3d& P);

// posedV: #V by 3 posed tet mesh vertices. Returns #P by 3 posed points. Throws UsageError if an
// embedded corner is not a row of posedV.
MatrixX3d apply(const TetEmbedding& embedding, const MatrixX3d& posedV);

}  // namespace vesalius::posing
