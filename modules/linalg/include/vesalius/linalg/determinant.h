// First and second derivatives of det(F) for a 3x3 F, used by stable neo-Hookean (J = det F) and by the
// plastic volume V = |Fp| V0 (Wang et al. 2021, Appendix B, eqs. 34 and 42). vec is column-major throughout fem.
#pragma once

#include <Eigen/Core>

namespace vesalius {

// d det(F) / dF = cof(F) = [f1 x f2, f2 x f0, f0 x f1] for the columns f0, f1, f2 of F.
Eigen::Matrix3d determinantGradient(const Eigen::Matrix3d& F);

// d² det(F) / d vec(F)²: 3x3 blocks (column i of F, column j of F) are cross-product matrices of the third
// column, with signs; linear in F.
Eigen::Matrix<double, 9, 9> determinantHessian(const Eigen::Matrix3d& F);

}  // namespace vesalius
