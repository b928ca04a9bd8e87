#include "vesalius/fem/plastic_tet.h"

#include "vesalius/core/error.h"
#include "vesalius/linalg/determinant.h"

#include <Eigen/LU>

#include <algorithm>
#include <string>

namespace vesalius {
namespace {

using Matrix9d = Eigen::Matrix<double, 9, 9>;
using Vector9d = Eigen::Matrix<double, 9, 1>;
using Matrix9x12 = Eigen::Matrix<double, 9, 12>;
using Matrix12x9 = Eigen::Matrix<double, 12, 9>;
using Corners = Eigen::Matrix<double, 4, 3>;

Eigen::Matrix3d edgeMatrix(const Corners& c) {
  Eigen::Matrix3d D;
  for (int i = 0; i < 3; ++i) D.col(i) = (c.row(i + 1) - c.row(0)).transpose();
  return D;
}

Vector9d vec(const Eigen::Matrix3d& m) { return Eigen::Map<const Vector9d>(m.data()); }

// ∂/∂x of a function whose derivative in Ds is W: columns of W on corners 1-3, minus their sum on corner 0.
Vector12d scatter(const Eigen::Matrix3d& W) {
  Vector12d g;
  g.segment<3>(0) = -W.rowwise().sum();
  for (int c = 1; c < 4; ++c) g.segment<3>(3 * c) = W.col(c - 1);
  return g;
}

// G = ∂vec(Fe)/∂x for Fe = Ds M (the constant ∂F/∂x of eq. 33, times Fp⁻¹).
Matrix9x12 shapeJacobian(const Eigen::Matrix3d& M) {
  Matrix9x12 G = Matrix9x12::Zero();
  for (int j = 0; j < 3; ++j)
    for (int k = 0; k < 3; ++k) {
      G(k + 3 * j, k) = -M.col(j).sum();
      for (int c = 1; c < 4; ++c) G(k + 3 * j, 3 * c + k) = M(c - 1, j);
    }
  return G;
}

// What every block needs: A = Fp⁻¹, M = (Fp Dm)⁻¹, Fe = F Fp⁻¹, V = |Fp| V0, ψ and P at Fe.
struct TetState {
  Eigen::Matrix3d Fp, A, M, Fe, P;
  double V0, V, psi;
};

TetState tetState(const PlasticTetRest& rest, const Corners& corners, const Vector6d& s,
                  const StableNeoHookean& material) {
  TetState t;
  t.Fp = plasticStrainMatrix(s);
  t.A = t.Fp.inverse();
  t.M = rest.DmInverse * t.A;
  t.Fe = edgeMatrix(corners) * t.M;
  t.V0 = rest.volume;
  t.V = rest.volume * t.Fp.determinant();
  t.psi = material.energy(t.Fe);
  t.P = material.stress(t.Fe);
  return t;
}

// ∂vec(Fe)/∂vec(Fp) = −(Aᵀ ⊗ Fe), from ∂Fp⁻¹ = −Fp⁻¹ ∂Fp Fp⁻¹ (eq. 33).
Matrix9d plasticJacobian(const TetState& t) {
  Matrix9d D;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      for (int c = 0; c < 3; ++c)
        for (int d = 0; d < 3; ++d) D(a + 3 * b, c + 3 * d) = -t.A(d, b) * t.Fe(a, c);
  return D;
}

// ∂²E/∂x∂vec(Fp), eqs. 36-38. The last term differentiates M = Dm⁻¹ Fp⁻¹ inside ∂Fe/∂x.
Matrix12x9 mixedInFp(const TetState& t, const Matrix9x12& G, const Matrix9d& H, const Matrix9d& D) {
  const Eigen::Matrix3d dV = t.V0 * determinantGradient(t.Fp);
  Matrix12x9 K = scatter(t.P * t.M.transpose()) * vec(dV).transpose() + t.V * G.transpose() * H * D;
  for (int c = 0; c < 3; ++c)
    for (int d = 0; d < 3; ++d) {
      const Eigen::Matrix3d dM = -t.M.col(c) * t.A.row(d);  // ∂M/∂Fp(c, d)
      K.col(c + 3 * d) += t.V * scatter(t.P * dM.transpose());
    }
  return K;
}

// ∂²E/∂vec(Fp)², eqs. 39-43. P : ∂²Fe/∂Fp_i∂Fp_j for i = (a, b), j = (c, d) is
// A(b, c) Q(a, d) + A(d, a) Q(c, b) with Q = Feᵀ P Aᵀ.
Matrix9d hessianInFp(const TetState& t, const Matrix9d& H, const Matrix9d& D) {
  const Vector9d dV = t.V0 * vec(determinantGradient(t.Fp));
  const Vector9d dPsi = D.transpose() * vec(t.P);
  const Eigen::Matrix3d Q = t.Fe.transpose() * t.P * t.A.transpose();
  Matrix9d second;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      for (int c = 0; c < 3; ++c)
        for (int d = 0; d < 3; ++d) second(a + 3 * b, c + 3 * d) = t.A(b, c) * Q(a, d) + t.A(d, a) * Q(c, b);
  return t.psi * t.V0 * determinantHessian(t.Fp) + dV * dPsi.transpose() + dPsi * dV.transpose() +
         t.V * (D.transpose() * H * D + second);
}

}  // namespace

PlasticTetRest plasticTetRest(const Corners& restCorners) {
  const Eigen::Matrix3d Dm = edgeMatrix(restCorners);
  double longest = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) longest = std::max(longest, (restCorners.row(i) - restCorners.row(j)).norm());
  const double volume = Dm.determinant() / 6;
  if (!restCorners.allFinite() || !(volume > 1e-12 * longest * longest * longest))
    throw BadInput("", "rest tet is inverted or flat (signed volume " + std::to_string(volume) + ")");
  return {Dm.inverse(), volume};
}

PlasticTetDerivatives plasticTetDerivatives(const PlasticTetRest& rest, const Corners& corners, const Vector6d& s,
                                            const StableNeoHookean& material, const PlasticTetBlocks& blocks) {
  using Stiffness = PlasticTetBlocks::Stiffness;
  const TetState t = tetState(rest, corners, s, material);
  PlasticTetDerivatives out;
  out.energy = t.V * t.psi;
  out.gradient = t.V * scatter(t.P * t.M.transpose());  // eq. 31
  out.stiffness.setZero();
  out.mixed.setZero();
  out.plasticGradient.setZero();
  out.plasticHessian.setZero();
  const bool needExact = blocks.stiffness == Stiffness::exact || blocks.mixed || blocks.plastic;
  if (!needExact && blocks.stiffness == Stiffness::none) return out;
  const Matrix9x12 G = shapeJacobian(t.M);
  const Matrix9d H = needExact ? material.stressDerivative(t.Fe) : Matrix9d::Zero();
  if (blocks.stiffness == Stiffness::exact) out.stiffness = t.V * G.transpose() * H * G;  // eq. 35
  if (blocks.stiffness == Stiffness::projected)
    out.stiffness = t.V * G.transpose() * material.projectedStressDerivative(t.Fe) * G;
  if (!blocks.mixed && !blocks.plastic) return out;
  const Matrix9d D = plasticJacobian(t);
  const Eigen::Matrix<double, 9, 6> Y = plasticStrainJacobian();
  if (blocks.mixed) out.mixed = mixedInFp(t, G, H, D) * Y;
  if (blocks.plastic) {
    const Vector9d dE = t.psi * t.V0 * vec(determinantGradient(t.Fp)) + t.V * D.transpose() * vec(t.P);  // eq. 32
    out.plasticGradient = Y.transpose() * dE;
    out.plasticHessian = Y.transpose() * hessianInFp(t, H, D) * Y;
  }
  return out;
}

double plasticTetJacobian(const PlasticTetRest& rest, const Corners& corners, const Vector6d& s) {
  return (edgeMatrix(corners) * rest.DmInverse).determinant() / plasticStrainMatrix(s).determinant();
}

}  // namespace vesalius
