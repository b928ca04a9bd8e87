#include "vesalius/fit/constraint_jacobian.h"

#include "vesalius/core/error.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <utility>

namespace vesalius::fit {
namespace {

using Eigen::Index;

constexpr Index kColumnBlock = 4096;

// Wᵀ y and W x over column blocks of Wᵀ in parallel: with few right-hand sides these are memory-bound
// products that Eigen runs on one thread. The reduction is deterministic so results are reproducible.
Eigen::MatrixXd multiply(const Eigen::MatrixXd& Wt, const Eigen::MatrixXd& y) {
  return tbb::parallel_deterministic_reduce(
      tbb::blocked_range<Index>(0, Wt.cols(), kColumnBlock),
      Eigen::MatrixXd(Eigen::MatrixXd::Zero(Wt.rows(), y.cols())),
      [&](const tbb::blocked_range<Index>& r, Eigen::MatrixXd sum) {
        sum.noalias() += Wt.middleCols(r.begin(), r.size()) * y.middleRows(r.begin(), r.size());
        return sum;
      },
      [](Eigen::MatrixXd a, const Eigen::MatrixXd& b) {
        a += b;
        return a;
      });
}

Eigen::MatrixXd multiplyTransposed(const Eigen::MatrixXd& Wt, const Eigen::Ref<const Eigen::MatrixXd>& x) {
  Eigen::MatrixXd out(Wt.cols(), x.cols());
  tbb::parallel_for(tbb::blocked_range<Index>(0, Wt.cols(), kColumnBlock), [&](const tbb::blocked_range<Index>& r) {
    out.middleRows(r.begin(), r.size()).noalias() = Wt.middleCols(r.begin(), r.size()).transpose() * x;
  });
  return out;
}

Eigen::SparseMatrix<double> minusIdentity(Index n) {
  Eigen::SparseMatrix<double> I(n, n);
  I.setIdentity();
  return -I;
}

}  // namespace

ConstraintJacobian::ConstraintJacobian(Eigen::MatrixXd Wt, Eigen::SparseMatrix<double> G)
    : Wt_(std::move(Wt)), G_(std::move(G)) {
  if (Wt_.cols() != G_.rows()) throw BadInput("", "constraint Jacobian: Wᵀ and G do not have matching sizes");
}

// A formed Z as the factors Wᵀ = Z and G = −I, so that one code path serves both.
ConstraintJacobian::ConstraintJacobian(const Eigen::MatrixXd& Z) : Wt_(Z), G_(minusIdentity(Z.cols())) {}

Eigen::MatrixXd ConstraintJacobian::operator*(const Eigen::Ref<const Eigen::MatrixXd>& y) const {
  if (y.rows() != cols()) throw BadInput("", "constraint Jacobian: Z y with y of the wrong number of rows");
  return -multiply(Wt_, Eigen::MatrixXd(G_ * y));
}

Eigen::MatrixXd ConstraintJacobian::transposeTimes(const Eigen::Ref<const Eigen::MatrixXd>& x) const {
  if (x.rows() != rows()) throw BadInput("", "constraint Jacobian: Zᵀ x with x of the wrong number of rows");
  return -(G_.transpose() * multiplyTransposed(Wt_, x));
}

void ConstraintJacobian::column(Index j, Eigen::Ref<Eigen::VectorXd> out) const {
  out.setZero();
  for (Eigen::SparseMatrix<double>::InnerIterator it(G_, j); it; ++it) out.noalias() -= it.value() * Wt_.col(it.row());
}

double ConstraintJacobian::squaredNorm() const {
  return tbb::parallel_deterministic_reduce(
      tbb::blocked_range<Index>(0, cols(), 1024), 0.0,
      [&](const tbb::blocked_range<Index>& r, double sum) {
        Eigen::VectorXd z(rows());
        for (Index j = r.begin(); j < r.end(); ++j) {
          column(j, z);
          sum += z.squaredNorm();
        }
        return sum;
      },
      [](double a, double b) { return a + b; });
}

}  // namespace vesalius::fit
