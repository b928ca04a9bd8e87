// Static equilibrium of the plastically deformed body under point springs, for fixed plastic strains s:
//   f_e(Fp(s), x) + f_a(x) = 0   (Wang et al. 2021, §3.3, eq. 4; eq. 7 with f_net),
// i.e. a stationary point of E_total(x) = E(s, x) + E_a(x), found by minimizing E_total.
//
// Newton's method with a backtracking (Armijo) line search on E_total. Tets may invert on the way (Smith
// et al.'s energy is built for it); the caller decides whether an inverted equilibrium is acceptable.
// The Newton matrix is the PSD-projected stiffness plus the spring Hessian, which descends from anywhere; after a full step it switches to the exact stiffness for as long as
// that stays positive definite and its steps are accepted, which restores quadratic convergence where
// elements keep residual stress (inconsistent plastic strains). Both carry Levenberg-Marquardt damping
// ν·d·I (d = mean diagonal; ν ÷10 after a full step, ×10 when no step is found, from 1e-9 to 1e8), which
// changes the steps, never the equilibrium, and makes the matrix definite when the springs do not remove
// the 6 rigid motions (un-attached objects, Wang et al. 2021, §3.6): the elastic force has no net force or torque, so
// rigid motions are not excited. One SparseCholesky analysis serves all iterations.
#pragma once

#include "vesalius/fem/plastic_fem.h"
#include "vesalius/fem/point_springs.h"

namespace vesalius {

struct EquilibriumOptions {
  int maxIterations = 50;  // Newton steps
  // Converged when ||∇E_total|| ≤ tolerance · equilibriumForceScale(fem).
  double tolerance = 1e-6;
};

struct EquilibriumResult {
  Eigen::VectorXd x;       // 3#V equilibrium positions (the last iterate if not converged)
  int iterations = 0;      // Newton steps taken
  double residual = 0;     // ||∇E_total(x)|| / equilibriumForceScale(fem)
  bool converged = false;  // false only when maxIterations ran out while still descending
};

// μ (Σ V0)^(2/3): the force of stress μ over an object-sized cross-section, (unit of μ) · mm².
double equilibriumForceScale(const PlasticFem& fem);

// s: 6#T plastic strains, used as given; every Fp must have det > 0 (else BadInput). x0: 3#V start
// positions, inverted tets allowed. springs may be empty.
// Throws NumericalFailure when no descent step is found even at the largest damping, or on non-finite
// values.
EquilibriumResult solveStaticEquilibrium(const PlasticFem& fem, const Eigen::VectorXd& s,
                                         const PointSprings& springs, const Eigen::VectorXd& x0,
                                         const EquilibriumOptions& options = {});

}  // namespace vesalius
