// Mean value coordinates of points inside a closed triangle mesh (Ju, Schaefer and Warren, "Mean value
// coordinates for closed triangular meshes", SIGGRAPH 2005, §3.3 and its Figure 4): values given at the
// mesh's vertices are interpolated smoothly into its inside. They reproduce linear functions exactly, so a
// cage moved by an affine map moves every inner point by that map; a point on the mesh gets the
// barycentric interpolation of its triangle.
//
// Used to carry points that only a surface defines (MakeHuman's joint helpers inside its body) along when
// the surface changes shape.
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Core>

namespace vesalius {

// cage: closed, consistently oriented; values: #V(cage) by k; points: #P by 3, in the cage's space.
// Returns #P by k: each point's mean-value interpolation of `values`. A point on a vertex gets its value.
// Throws BadInput if the cage has no triangles or `values` has not a row per cage vertex.
Eigen::MatrixXd meanValueInterpolate(const TriMesh& cage, const Eigen::MatrixXd& values, const MatrixX3d& points);

}  // namespace vesalius
