// One tet of the plastic elastic energy (Wang et al. 2021, §3.2, eq. 1) and its derivatives (Appendix B,
// eqs. 31-43, moved from vec(Fp) to s with vec(Fp) = Y s):
//   E(Fp, x) = |Fp| V0 ψ(F Fp⁻¹),   F Fp⁻¹ = Ds (Fp Dm)⁻¹,
// Ds = [x1 − x0, x2 − x0, x3 − x0] of the deformed corners, Dm the same of the rest (template) corners.
// Fp Dm is the rest shape of the tet after the plastic deformation, so the energy is ordinary
// hyperelasticity against that rest shape, with rest volume |Fp| V0.
#pragma once

#include "vesalius/fem/plastic_strain.h"
#include "vesalius/fem/stable_neo_hookean.h"

namespace vesalius {

using Vector12d = Eigen::Matrix<double, 12, 1>;
using Matrix12d = Eigen::Matrix<double, 12, 12>;

struct PlasticTetRest {
  Eigen::Matrix3d DmInverse;
  double volume;  // V0 > 0
};

// restCorners: 4 by 3, positively oriented. Throws BadInput if the tet is inverted, flat (volume below
// 1e-12 times its longest edge cubed) or not finite.
PlasticTetRest plasticTetRest(const Eigen::Matrix<double, 4, 3>& restCorners);

// Which blocks beyond the energy and ∂E/∂x to compute; the others are left zero.
struct PlasticTetBlocks {
  enum class Stiffness { none, exact, projected };
  Stiffness stiffness = Stiffness::none;  // projected: from the PSD-projected dP/dF, so PSD itself
  bool mixed = false;                     // ∂²E/∂x∂s
  bool plastic = false;                   // ∂E/∂s and ∂²E/∂s²
};

// x ordering is corner-major (x0, y0, z0, x1, ...).
struct PlasticTetDerivatives {
  double energy = 0;
  Vector12d gradient;                          // ∂E/∂x
  Matrix12d stiffness;                         // ∂²E/∂x²
  Eigen::Matrix<double, 12, 6> mixed;          // ∂²E/∂x∂s
  Vector6d plasticGradient;                    // ∂E/∂s
  Eigen::Matrix<double, 6, 6> plasticHessian;  // ∂²E/∂s²
};

// corners: 4 by 3 deformed positions. Fp = plasticStrainMatrix(s) must be invertible.
PlasticTetDerivatives plasticTetDerivatives(const PlasticTetRest& rest, const Eigen::Matrix<double, 4, 3>& corners,
                                            const Vector6d& s, const StableNeoHookean& material,
                                            const PlasticTetBlocks& blocks);

// det(F Fp⁻¹): positive unless the tet is inverted relative to its plastic rest shape.
double plasticTetJacobian(const PlasticTetRest& rest, const Eigen::Matrix<double, 4, 3>& corners,
                          const Vector6d& s);

}  // namespace vesalius
