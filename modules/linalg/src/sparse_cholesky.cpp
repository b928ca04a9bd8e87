// SparseCholesky on Eigen's CHOLMOD wrapper. The analysis is kept while the sparsity pattern (outer
// index and inner index arrays) stays the same, so Newton iterations and Gauss-Newton iterations pay
// only the numeric factorization.
#include "vesalius/linalg/sparse_cholesky.h"

#include "vesalius/core/error.h"

#include <Eigen/CholmodSupport>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <dlfcn.h>

#include <algorithm>
#include <atomic>
#include <vector>

namespace vesalius {

namespace {

// CHOLMOD's supernodal factorization and solves call BLAS (OpenBLAS on Debian) and run parts in OpenMP
// regions. Both libraries start their own threads, whose idle workers spin (sched_yield) and sleep (futex)
// against TBB's on the same cores: a 22k-tet fit spent most of its time in the kernel. TBB already keeps
// the cores busy, so CHOLMOD and its BLAS run on the calling thread. CHOLMOD 3 asks for num_threads(4) in
// its regions, which overrides omp_set_num_threads(1): a team of 4 was woken for every large supernode
// (785k context switches in the 39k-tet fit of bench_fit, whose CPU time was 28 % kernel).
// No active OpenMP level (max-active-levels 0) runs every region on the thread that meets it. The
// setting is per thread, so every call sets it. Looked up at run time: any BLAS and an OpenMP-free
// CHOLMOD need none of it.
void keepCholmodOnThisThread() {
  using SetThreads = void (*)(int);
  static const bool blasSet = [] {
    if (auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) set(1);
    return true;
  }();
  (void)blasSet;
  static const SetThreads openMp = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"));
  if (openMp) openMp(0);
}

// Columns per solve call. CHOLMOD's supernodal solve on thousands of columns at once streams the whole
// block through the cache for every supernode and was 3x slower than chunks of 64 (35k-tet Laplacian,
// 2760 columns: 24 s in one call, 7 s in chunks).
constexpr Eigen::Index kSolveColumns = 64;
// Columns per in-place solve in the factor's order (no copies): each block streams the whole factor
// twice, and larger blocks stream it fewer times. Six solves on 450 columns of the 38,921-tet
// Laplacian's factor on both cores (CHOLMOD's column-major solves), blocks of 225 instead of
// 56: 1.16 s of wall and 1.97-2.00 s of CPU instead of 1.26-1.29 s and 2.34-2.38 s.
constexpr Eigen::Index kPermutedSolveColumns = 256;

// Eigen keeps the factor protected; the parallel solve hands it to cholmod_solve2 directly.
struct SupernodalLlt : Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> {
  cholmod_factor* factor() const { return m_cholmodFactor; }
};

// A CHOLMOD workspace per thread. cholmod_solve2 and the row-major solves only read the factor; their
// status, allocations and workspace go through the Common they are given, so solves on different
// Commons may run at once.
struct ThreadCommon {
  ThreadCommon() {
    cholmod_start(&common);
    common.print = 0;
    common.try_catch = 1;
  }
  ~ThreadCommon() { cholmod_finish(&common); }
  ThreadCommon(const ThreadCommon&) = delete;
  ThreadCommon& operator=(const ThreadCommon&) = delete;
  cholmod_common common;
  std::vector<double> workspace;  // E of the row-major supernodal solves
};

ThreadCommon& threadCommon() {
  static tbb::enumerable_thread_specific<ThreadCommon> commons;
  keepCholmodOnThisThread();
  return commons.local();
}

// Columns first .. first + count − 1 of a column-major block of rows × cols doubles, as CHOLMOD's view.
cholmod_dense denseColumns(double* data, Eigen::Index rows, Eigen::Index first, Eigen::Index count) {
  cholmod_dense d{};
  d.nrow = std::size_t(rows);
  d.ncol = std::size_t(count);
  d.nzmax = d.nrow * d.ncol;
  d.d = d.nrow;
  d.x = data + first * rows;
  d.xtype = CHOLMOD_REAL;
  d.dtype = CHOLMOD_DOUBLE;
  return d;
}

// Solves one block of columns of B into X with this thread's Common; false if CHOLMOD fails. B and X may
// be the same matrix: the block is read before it is written.
bool solveColumns(cholmod_factor* factor, const Eigen::MatrixXd& B, Eigen::Index first, Eigen::Index count,
                  Eigen::MatrixXd& X) {
  cholmod_common& common = threadCommon().common;
  cholmod_dense b = denseColumns(const_cast<double*>(B.data()), B.rows(), first, count);
  cholmod_dense *x = nullptr, *y = nullptr, *e = nullptr;
  const bool solved = cholmod_solve2(CHOLMOD_A, factor, &b, nullptr, &x, nullptr, &y, &e, &common) && x;
  if (solved) X.middleCols(first, count) = Eigen::Map<const Eigen::MatrixXd>(static_cast<double*>(x->x), B.rows(), count);
  for (cholmod_dense* d : {x, y, e})
    if (d) cholmod_free_dense(&d, &common);
  return solved;
}

// BLAS-3 kernels for the row-major supernodal solves, looked up at run time like the thread settings
// above: CHOLMOD brings its BLAS into the process, and this module does not link one itself.
using Dgemm = void (*)(const char*, const char*, const int*, const int*, const int*, const double*, const double*,
                       const int*, const double*, const int*, const double*, double*, const int*);
using Dtrsm = void (*)(const char*, const char*, const char*, const char*, const int*, const int*, const double*,
                       const double*, const int*, double*, const int*);

struct Blas3 {
  Dgemm gemm = reinterpret_cast<Dgemm>(dlsym(RTLD_DEFAULT, "dgemm_"));
  Dtrsm trsm = reinterpret_cast<Dtrsm>(dlsym(RTLD_DEFAULT, "dtrsm_"));
};

const Blas3& blas3() {
  static const Blas3 blas;
  if (!blas.gemm || !blas.trsm) throw NumericalFailure("sparse Cholesky: no BLAS (dgemm_, dtrsm_) in the process");
  return blas;
}

// One supernode of the factor: columns k1 .. k1 + cols − 1, its rows (the first `cols` are the diagonal
// block's), and its dense column-major values (rows by cols): L1 on top, L2 below.
struct Supernode {
  int k1, cols, rows;
  const int* rowIndex;
  const double* values;
};

Supernode supernode(const cholmod_factor* L, std::size_t s) {
  const int* super = static_cast<const int*>(L->super);
  const int* pi = static_cast<const int*>(L->pi);
  const int* px = static_cast<const int*>(L->px);
  return {super[s], super[s + 1] - super[s], pi[s + 1] - pi[s], static_cast<const int*>(L->s) + pi[s],
          static_cast<const double*>(L->x) + px[s]};
}

// L Lᵀ X = B on `count` columns of the row-major X (row stride ld), rows in the factor's order. Per
// supernode, the rows of X it owns are contiguous: X1 holds them as a column-major count by cols block,
// so L1 X1 = B1 is X1ᵀ L1ᵀ = B1ᵀ, and the update L2 X1 of the rows below goes through E (count by the
// rows below, column-major) row by row.
void solveRowMajorColumns(const Blas3& blas, const cholmod_factor* L, double* X, int ld, int count,
                          std::vector<double>& E) {
  E.resize(std::max<std::size_t>(1, std::size_t(count) * L->maxesize));
  const double one = 1.0, minusOne = -1.0, zero = 0.0;
  for (std::size_t s = 0; s < L->nsuper; ++s) {
    const Supernode n = supernode(L, s);
    const int below = n.rows - n.cols;
    double* X1 = X + std::size_t(n.k1) * std::size_t(ld);
    blas.trsm("R", "L", "T", "N", &count, &n.cols, &one, n.values, &n.rows, X1, &ld);
    if (below == 0) continue;
    blas.gemm("N", "T", &count, &below, &n.cols, &one, X1, &ld, n.values + n.cols, &n.rows, &zero, E.data(), &count);
    for (int i = 0; i < below; ++i) {
      double* row = X + std::size_t(n.rowIndex[n.cols + i]) * std::size_t(ld);
      const double* e = E.data() + std::size_t(i) * std::size_t(count);
      for (int j = 0; j < count; ++j) row[j] -= e[j];
    }
  }
  for (std::size_t s = L->nsuper; s-- > 0;) {
    const Supernode n = supernode(L, s);
    const int below = n.rows - n.cols;
    double* X1 = X + std::size_t(n.k1) * std::size_t(ld);
    if (below > 0) {
      for (int i = 0; i < below; ++i)
        std::copy_n(X + std::size_t(n.rowIndex[n.cols + i]) * std::size_t(ld), count,
                    E.data() + std::size_t(i) * std::size_t(count));
      blas.gemm("N", "N", &count, &n.cols, &below, &minusOne, E.data(), &count, n.values + n.cols, &n.rows, &one, X1,
                &ld);
    }
    blas.trsm("R", "L", "N", "N", &count, &n.cols, &one, n.values, &n.rows, X1, &ld);
  }
}

}  // namespace

struct SparseCholesky::Impl {
  // CHOLMOD prints nothing: its failures become the NumericalFailure below, and Newton solvers try
  // matrices that may not be positive definite on purpose. (print = 0 alone does not silence the
  // supernodal factorization's "not positive definite"; try_catch does, and keeps the status.)
  explicit Impl(FillReducingOrdering ordering) {
    llt.cholmod().print = 0;
    llt.cholmod().try_catch = 1;
    if (ordering == FillReducingOrdering::nestedDissection) {
      llt.cholmod().nmethods = 1;
      llt.cholmod().method[0].ordering = CHOLMOD_METIS;
    }
  }
  SupernodalLlt llt;
  std::vector<int> outer, inner;  // pattern of the analysed matrix
  bool analysed = false;
  Eigen::Index n = 0;
};

SparseCholesky::SparseCholesky(FillReducingOrdering ordering) : impl_(std::make_unique<Impl>(ordering)) {}
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
    impl_->n = 0;
    throw NumericalFailure("sparse Cholesky: the matrix is not positive definite");
  }
  impl_->n = M.rows();
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& B) const {
  Eigen::MatrixXd X = B;
  solveInPlace(X);
  return X;
}

void SparseCholesky::solveInPlace(Eigen::MatrixXd& X) const {
  solveBlocks(X.rows(), X.cols(), kSolveColumns, [&](Eigen::Index first, Eigen::Index count) {
    return solveColumns(impl_->llt.factor(), X, first, count, X);
  });
}

Eigen::VectorXi SparseCholesky::permutation() const {
  if (impl_->n == 0) throw NumericalFailure("sparse Cholesky: permutation before factor");
  return Eigen::Map<const Eigen::VectorXi>(static_cast<const int*>(impl_->llt.factor()->Perm), impl_->n);
}

void SparseCholesky::solvePermutedInPlace(RowMajorMatrixXd& X) const {
  const Blas3& blas = blas3();
  solveBlocks(X.rows(), X.cols(), kPermutedSolveColumns, [&](Eigen::Index first, Eigen::Index count) {
    const cholmod_factor* L = impl_->llt.factor();
    if (!L->is_super || L->xtype != CHOLMOD_REAL) return false;
    solveRowMajorColumns(blas, L, X.data() + first, int(X.cols()), int(count), threadCommon().workspace);
    return true;
  });
}

// Blocks of `blockColumns` columns of X in parallel (Wang et al. 2021, §3.4: the many right-hand sides of Z);
// each column's solution is the same whatever the threads.
template <class SolveBlock>
void SparseCholesky::solveBlocks(Eigen::Index rows, Eigen::Index cols, Eigen::Index blockColumns,
                                 SolveBlock solveBlock) const {
  if (impl_->n == 0) throw NumericalFailure("sparse Cholesky: solve before factor");
  if (rows != impl_->n) throw NumericalFailure("sparse Cholesky: right-hand side has the wrong size");
  std::atomic<bool> failed{false};
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, cols, blockColumns),
                    [&](const tbb::blocked_range<Eigen::Index>& r) {
                      if (!solveBlock(r.begin(), r.size())) failed = true;
                    });
  if (failed) throw NumericalFailure("sparse Cholesky: solve failed");
}

Eigen::VectorXd SparseCholesky::solve(const Eigen::VectorXd& b) const {
  return solve(Eigen::MatrixXd(b)).col(0);
}

Eigen::Index SparseCholesky::size() const { return impl_->n; }

double SparseCholesky::factorEntries() const { return impl_->analysed ? impl_->llt.cholmod().lnz : 0.0; }

}  // namespace vesalius
