// The affine map of each tet from its rest to its posed shape (Sujar et al. 2018, §3.5: "a constant transformation
// matrix can be calculated for each tetrahedron", applied on the GPU to the tissue vertices in the tet).
//
// With rest edges E = [x1-x0, x2-x0, x3-x0] and posed edges E', the map is x ↦ E' E⁻¹ (x - x0) + x0'.
// Applied to a point embedded in the tet it gives exactly what barycentric interpolation of the posed
// corners gives (core/tet_embedding.h); the maps are the form a renderer or a volume resampler wants
// (Sujar et al.'s posed volumes invert them per tet, §5).
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Geometry>

#include <vector>

namespace vesalius::posing {

// restV, posedV: #V by 3, T: #T by 4 tets. Returns #T affine maps. Throws BadInput if a rest tet is flat
// or a tet refers to a missing vertex, UsageError if restV and posedV differ in size.
std::vector<Eigen::Affine3d> tetAffineMaps(const MatrixX3d& restV, const MatrixX4i& T, const MatrixX3d& posedV);

}  // namespace vesalius::posing
