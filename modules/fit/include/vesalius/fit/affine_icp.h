// Affine ICP of a surface to scattered target points (Besl and McKay, "A method for registration of 3-D
// shapes", PAMI 14(2), 1992, with an affine instead of a rigid update): each target pairs with its closest
// point on the surface, the affine map of those surface points onto the targets is solved by linear least
// squares, and the surface moves by it. Refines a similarity placement (initial_placement.h) where a
// template organ differs from a patient's by more than a scale (a liver's lobes wider or flatter).
#pragma once

#include "vesalius/core/mesh.h"

namespace vesalius::fit {

struct AffineIcpOptions {
  int iterations = 30;
  int minTargets = 20;  // below this the surface is returned as it is: an affine map of a few points can shear
};

// surface: V #V by 3, F #F by 3, mm; targets: #P by 3 points the surface should pass through. Returns the
// surface with its vertices moved by the accumulated affine map (F and attributes kept). A rank-deficient
// step (targets on a plane) ends the iterations.
TriMesh refineAffineIcp(TriMesh surface, const MatrixX3d& targets, const AffineIcpOptions& options = {});

}  // namespace vesalius::fit
