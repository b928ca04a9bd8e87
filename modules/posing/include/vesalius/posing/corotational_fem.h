// The physically based reference pose of Sujar et al. 2018, §5, Fig. 9: a static co-rotational linear FEM solve of
// the tet mesh with the bone vertices as boundary conditions ("the boundary conditions ... are given by the
// positions of the vertices labelled as bones"; "the internal forces [are computed] in a non-rotated
// configuration. Then, the internal forces are rotated again into the final configuration [45]").
//
// Linear, isotropic, homogeneous P1 elements with stiffness K_t (12 by 12, small strain) and per-tet
// rotations R_t, the rotation of the polar decomposition of the deformation gradient F_t = D_s D_m⁻¹
// (a reflection, from an inverted tet, is turned into the nearest rotation). With the R_t held fixed the
// elastic forces f_t = R_t K_t (R_tᵀ x_t − X_t) are linear in x; equilibrium of the free vertices,
//   Σ_t R_t K_t R_tᵀ x = Σ_t R_t K_t X   with the bone vertices given,
// is one sparse SPD solve. The rotations are then updated from the new x and the solve repeated until no
// vertex moves more than the tolerance (Sujar et al.'s "solution is refined iteratively"). The pattern of the
// matrix never changes, so its symbolic factorisation is done once.
//
// Homogeneous material: Young's modulus scales K and cancels; only the Poisson ratio matters, near 0.5
// to keep volume (Sujar et al. 2018 keeps it below 0.5 for numerical stability).
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

namespace vesalius::posing {

struct CorotationalFemOptions {
  double poissonRatio = 0.45;  // in (-1, 0.5); closer to 0.5 keeps volume better but conditions K worse
  double tolerance = 1e-6;     // stop when no vertex moves more than this × the rest bounding-box diagonal
  int maxIterations = 100;
};

struct CorotationalFemResult {
  MatrixX3d V;         // #V by 3 posed positions
  int iterations = 0;  // linear solves done
  double residual = 0; // largest vertex move of the last solve, mm (below tolerance × diagonal if converged)
  bool converged = false;
};

// V: #V by 3 rest positions, T: #T by 4 positively oriented tets, boneOfVertex: #V, -1 for tissue and j >= 0
// for bone j, transforms: #B bone transforms from rest to posed (#B > largest bone index). Starts from
// linear blend skinning with the bone weights of computeBoneWeights. Throws BadInput if the sizes disagree,
// no vertex is a bone, a bone has no transform, a tet refers to a missing vertex or is flat or inverted,
// or an option is out of range; NumericalFailure if the stiffness of the free vertices is singular.
CorotationalFemResult corotationalFem(const MatrixX3d& V, const MatrixX4i& T, const Eigen::VectorXi& boneOfVertex,
                                      const std::vector<Eigen::Isometry3d>& transforms,
                                      const CorotationalFemOptions& options = {});

}  // namespace vesalius::posing
