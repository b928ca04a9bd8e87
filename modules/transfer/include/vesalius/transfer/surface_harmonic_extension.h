// Values known on some vertices of a triangle surface, extended to the others as a harmonic function of
// the surface's edge graph: each unknown vertex the mean of its neighbours (the uniform-weight graph
// Laplacian, Dirichlet at the known vertices). Smooth, and within the known values' range (the maximum
// principle), so a displacement or a thickness given on part of a skin is continued without a step or an
// overshoot. Used by the partial skin registration's continuation (partial_skin_registration.h) and the
// fat of a completed reference (patient/reference_completion.h).
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Core>

#include <vector>

namespace vesalius::transfer {

// values: #V by k, read on the rows where known[v] != 0; F: #F by 3 over those #V vertices. Returns #V by
// k, equal to values on the known rows. An edge-connected piece with no known vertex gets 0. Throws
// BadInput if the sizes disagree or F indexes outside the vertices.
Eigen::MatrixXd extendHarmonically(const Eigen::MatrixXd& values, const std::vector<char>& known, const MatrixX3i& F);

}  // namespace vesalius::transfer
