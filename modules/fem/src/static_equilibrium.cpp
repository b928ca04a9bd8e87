#include "vesalius/fem/static_equilibrium.h"

#include "vesalius/core/error.h"
#include "vesalius/linalg/sparse_cholesky.h"

#include <Eigen/LU>

#include <cmath>
#include <optional>
#include <string>

namespace vesalius {
namespace {

constexpr double kInitialDamping = 1e-8, kMinDamping = 1e-9, kMaxDamping = 1e8;
constexpr double kArmijo = 1e-4;
constexpr int kHalvings = 12;
// Energy changes this small relative to the energy are round-off: near convergence the Newton decrease
// falls below them and Armijo would refuse good steps.
constexpr double kEnergyRoundOff = 1e-13;

struct Objective {
  const PlasticFem& fem;
  const Eigen::VectorXd& s;
  const PointSprings& springs;
  Eigen::SparseMatrix<double> springHessian;

  double energy(const Eigen::VectorXd& x) const {
    return fem.energy(x, s) + pointSpringEnergy(springs, fem.tets(), x);
  }
  Eigen::VectorXd gradient(const Eigen::VectorXd& x) const {
    return fem.gradient(x, s) + pointSpringGradient(springs, fem.tets(), x);
  }
};

void checkStart(const PlasticFem& fem, const Eigen::VectorXd& s, const Eigen::VectorXd& x0) {
  fem.elasticJacobians(x0, s);  // checks the sizes
  for (int t = 0; t < fem.tetCount(); ++t)
    if (!(plasticStrainMatrix(s.segment<6>(6 * t)).determinant() > 0))
      throw BadInput("", "static equilibrium: the plastic strain of tet " + std::to_string(t) + " has det <= 0");
}

struct Step {
  Eigen::VectorXd x;
  double energy, length;  // length: the line-search factor taken
};

// Backtracking from the full step d; nothing if every tried step fails Armijo. Steps may invert tets: the
// stable neo-Hookean energy is defined and rises there, so Newton passes through a nearly flat tet
// instead of being trapped in front of it, as a barrier on J = 0 would leave it.
std::optional<Step> lineSearch(const Objective& f, const Eigen::VectorXd& x, double energy,
                               const Eigen::VectorXd& g, const Eigen::VectorXd& d) {
  const double slope = g.dot(d);
  if (!(slope < 0)) return std::nullopt;
  for (double a = 1; a >= std::ldexp(1.0, -kHalvings); a /= 2) {
    Eigen::VectorXd trial = x + a * d;
    const double e = f.energy(trial);
    if (e <= energy + kArmijo * a * slope + kEnergyRoundOff * std::abs(energy))
      return Step{std::move(trial), e, a};
  }
  return std::nullopt;
}

// Damped Newton steps. The projected stiffness descends from anywhere, but where elements keep residual
// stress (inconsistent plastic strains, bending) it is not the Hessian, and convergence turns linear. So
// after a full projected step the exact stiffness is used for as long as K + damping stays positive
// definite (Cholesky succeeds) and the line search accepts its steps. Both have one pattern: one analysis.
class NewtonSteps {
 public:
  explicit NewtonSteps(const Objective& f) : f_(f) {}

  Step next(const Eigen::VectorXd& x, double energy, const Eigen::VectorXd& g) {
    if (exact_) {
      if (auto step = along(f_.fem.stiffness(x, f_.s, false) + f_.springHessian, x, energy, g)) return *step;
      exact_ = false;
    }
    const Eigen::SparseMatrix<double> K = f_.fem.stiffness(x, f_.s, true) + f_.springHessian;
    for (; damping_ <= kMaxDamping; damping_ *= 10)
      if (auto step = along(K, x, energy, g)) return *step;
    throw NumericalFailure("static equilibrium: no descent step at the largest damping (gradient norm " +
                           std::to_string(g.norm()) + ")");
  }

 private:
  // Factors K + ν d I and searches along its Newton direction; nothing if either fails.
  std::optional<Step> along(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& x, double energy,
                            const Eigen::VectorXd& g) {
    Eigen::SparseMatrix<double> identity(K.rows(), K.cols());
    identity.setIdentity();
    try {
      cholesky_.factor(K + (damping_ * K.diagonal().mean()) * identity);
    } catch (const NumericalFailure&) {
      return std::nullopt;
    }
    auto step = lineSearch(f_, x, energy, g, -cholesky_.solve(g));
    if (step && step->length == 1) {
      damping_ = std::max(damping_ / 10, kMinDamping);
      exact_ = true;
    }
    return step;
  }

  const Objective& f_;
  SparseCholesky cholesky_;
  double damping_ = kInitialDamping;
  bool exact_ = false;
};

}  // namespace

double equilibriumForceScale(const PlasticFem& fem) {
  return fem.material().mu * std::pow(fem.restVolumes().sum(), 2.0 / 3.0);
}

EquilibriumResult solveStaticEquilibrium(const PlasticFem& fem, const Eigen::VectorXd& s,
                                         const PointSprings& springs, const Eigen::VectorXd& x0,
                                         const EquilibriumOptions& options) {
  checkStart(fem, s, x0);
  const Objective f{fem, s, springs, pointSpringHessian(springs, fem.tets(), fem.vertexCount())};
  const double scale = equilibriumForceScale(fem);
  EquilibriumResult result{x0, 0, 0, false};
  double energy = f.energy(x0);
  Eigen::VectorXd g = f.gradient(x0);
  NewtonSteps steps(f);
  for (;; ++result.iterations) {
    result.residual = g.norm() / scale;
    if (!std::isfinite(energy) || !std::isfinite(result.residual))
      throw NumericalFailure("static equilibrium: energy or force is not finite");
    result.converged = result.residual <= options.tolerance;
    if (result.converged || result.iterations == options.maxIterations) return result;
    Step step = steps.next(result.x, energy, g);
    result.x = std::move(step.x);
    energy = step.energy;
    g = f.gradient(result.x);
  }
}

}  // namespace vesalius
