// Plastic strain of one tet as a symmetric 3x3 Fp parameterized by s in R^6 (Wang et al. 2021, §3.2, eq. 2):
//   Fp = [[s1 s2 s3] [s2 s4 s5] [s3 s5 s6]].
// A symmetric Fp loses nothing: Fp and its polar factor S give the same energy because ψ is isotropic.
#pragma once

#include <Eigen/Core>

namespace vesalius {

using Vector6d = Eigen::Matrix<double, 6, 1>;

Eigen::Matrix3d plasticStrainMatrix(const Vector6d& s);

// s of the symmetric part of the matrix ((M + Mᵀ) / 2).
Vector6d plasticStrainParameters(const Eigen::Matrix3d& symmetric);

// s of Fp = I: no plastic deformation.
Vector6d identityPlasticStrain();

// Y of Wang et al. 2021, Appendix B: vec(Fp) = Y s, vec column-major. Transfers derivatives in vec(Fp) to s.
Eigen::Matrix<double, 9, 6> plasticStrainJacobian();

// Fp with its eigenvalues below `floor` raised to `floor` (Wang et al. 2021, §3.4, uses 0.01), so Fp stays positive
// definite after an optimizer step; s is returned unchanged when no eigenvalue is below `floor`.
Vector6d clampPlasticStrain(const Vector6d& s, double floor);

}  // namespace vesalius
