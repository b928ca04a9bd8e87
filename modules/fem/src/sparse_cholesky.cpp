// SparseCholesky on Eigen's CHOLMOD wrapper. The analysis is kept while the sparsity pattern (outer
// index and inner index arrays) stays the same, so Newton iterations and Gauss-Newton iterations pay
// only the numeric factorization.
#include "vesalius/fem/sparse_cholesky.h"

#include "vesalius/core/error.h"

#include <Eigen/CholmodSupport>

#include <dlfcn.h>

#include <algorithm>
#include <vector>

namespace vesalius {

namespace {

// CHOLMOD's supernodal factorization and solves call BLAS (OpenBLAS on Debian) and run parts in OpenMP
// regions. Both libraries start their own threads, whose idle workers spin (sched_yield) against TBB's on
// the same cores: a 22k-tet fit spent most of its time in the kernel. TBB already keeps the cores busy,
// so CHOLMOD and its BLAS run on the calling thread. The OpenMP setting is per thread, so every call sets
// it. Looked up at run time: any BLAS and an OpenMP-free CHOLMOD need none of it.
void keepCholmodOnThisThread() {
  using SetThreads = void (*)(int);
  static const bool blasSet = [] {
    if (auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) set(1);
    return true;
  }();
  (void)blasSet;
  static const SetThreads openMp = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "omp_set_num_threads"));
  if (openMp) openMp(1);
}

}  // namespace

struct SparseCholesky::Impl {
  // CHOLMOD prints nothing: its failures become the NumericalFailure below, and Newton solvers try
  // matrices that may not be positive definite on purpose. (print = 0 alone does not silence the
  // supernodal factorization's "not positive definite"; try_catch does, and keeps the status.)
  Impl() {
    llt.cholmod().print = 0;
    llt.cholmod().try_catch = 1;
  }
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
  std::vector<int> outer, inner;  // pattern of the analysed matrix
  bool analysed = false;
  Eigen::Index n = 0;
};

SparseCholesky::SparseCholesky() : impl_(std::make_unique<Impl>()) {}
SparseCholesky::~SparseCholesky() = default;
SparseCholesky::SparseCholesky(SparseCholesky&&) noexcept = default;
SparseCholesky& SparseCholesky::operator=(SparseCholesky&&) noexcept = default;

void SparseCholesky::factor(const Eigen::SparseMatrix<double>& A) {
  if (A.rows() == 0 || A.rows() != A.cols())
    throw NumericalFailure("sparse Cholesky: the matrix is empty or not square");
  keepCholmodOnThisThread();
  Eigen::SparseMatrix<double> M = A;
  M.makeCompressed();
  const std::vector<int> outer(M.outerIndexPtr(), M.outerIndexPtr() + M.outerSize() + 1);
  const std::vector<int> inner(M.innerIndexPtr(), M.innerIndexPtr() + M.nonZeros());
  if (!impl_->analysed || outer != impl_->outer || inner != impl_->inner) {
    impl_->llt.analyzePattern(M);
    impl_->outer = outer;
    impl_->inner = inner;
    impl_->analysed = true;
  }
  impl_->llt.factorize(M);
  if (impl_->llt.info() != Eigen::Success) {
    impl_->analysed = false;
    throw NumericalFailure("sparse Cholesky: the matrix is not positive definite");
  }
  impl_->n = M.rows();
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& B) const {
  if (impl_->n == 0) throw NumericalFailure("sparse Cholesky: solve before factor");
  if (B.rows() != impl_->n) throw NumericalFailure("sparse Cholesky: right-hand side has the wrong size");
  if (B.cols() == 0) return Eigen::MatrixXd(B.rows(), 0);
  keepCholmodOnThisThread();
  Eigen::MatrixXd X = impl_->llt.solve(B);
  if (impl_->llt.info() != Eigen::Success) throw NumericalFailure("sparse Cholesky: solve failed");
  return X;
}

Eigen::VectorXd SparseCholesky::solve(const Eigen::VectorXd& b) const {
  return solve(Eigen::MatrixXd(b)).col(0);
}

Eigen::Index SparseCholesky::size() const { return impl_->n; }

}  // namespace vesalius
