// Sparse symmetric positive-definite solves: factor once, solve many (CHOLMOD, supernodal).
//
// The fitter (Wang et al. 2021, §3.4) factors the tangent stiffness once per iteration and solves for hundreds of
// right-hand sides; posing and transfer factor a Laplacian once and solve one column per bone. Analyse
// the pattern once, refactor numerically when only the values change, and solve blocks of columns at
// once (CHOLMOD's supernodal solve uses BLAS-3 on a block).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <memory>

namespace vesalius {

// How the rows are ordered before factoring, to limit the factor's fill.
enum class FillReducingOrdering {
  // CHOLMOD's default: AMD, and METIS only where AMD leaves much fill. The cheapest analysis.
  automatic,
  // METIS nested dissection always. On the tet adjacency Laplacian of a 38,921-tet liver the factor has
  // 1.73M entries instead of AMD's 2.54M and solves 450 columns in a quarter less time, for 0.2 s more of
  // analysis: for a factor that solves thousands of columns (the fitter's Z (L²)⁺ Zᵀ).
  nestedDissection,
};

// Row-major blocks: each row's right-hand-side entries contiguous.
using RowMajorMatrixXd = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

class SparseCholesky {
 public:
  explicit SparseCholesky(FillReducingOrdering ordering = FillReducingOrdering::automatic);
  ~SparseCholesky();
  SparseCholesky(SparseCholesky&&) noexcept;
  SparseCholesky& operator=(SparseCholesky&&) noexcept;

  // A: #N by #N, symmetric (both triangles stored). Reuses the symbolic analysis when A has the pattern
  // of the previous call. Throws NumericalFailure if A is not positive definite or is empty.
  void factor(const Eigen::SparseMatrix<double>& A);

  // B: #N by #K. Returns A⁻¹ B.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;
  // X: #N by #K, replaced by A⁻¹ X without a second block of its size (the fitter's are hundreds of MB).
  void solveInPlace(Eigen::MatrixXd& X) const;
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;

  // The fill-reducing order of the last factor: row i of the factored P A Pᵀ is row permutation()(i) of A.
  Eigen::VectorXi permutation() const;
  // X: #N by #K, row-major, with its rows in the factor's order (row i holds row permutation()(i)),
  // replaced by (P A Pᵀ)⁻¹ X in place: the supernodal solves with BLAS-3 on each supernode's rows, which
  // are contiguous in a row-major block, and whole-row gathers and scatters. For callers that can build X
  // in that order. 450 columns of the 38,921-tet adjacency Laplacian's factor on one thread: 0.19-0.20 s
  // of CPU; CHOLMOD's supernodal solves on a column-major block, whose loops step across the columns,
  // 0.25-0.26 s (cholmod_solve2 with its permuting copies: 0.49 s).
  void solvePermutedInPlace(RowMajorMatrixXd& X) const;

  Eigen::Index size() const;
  // Entries of the factor's lower triangle (its fill) from the last analysis; 0 before any.
  double factorEntries() const;

 private:
  // Checks a rows by cols block against the factor, then solveBlock(first, count) on blocks of its columns
  // in parallel; throws NumericalFailure if any block fails.
  template <class SolveBlock>
  void solveBlocks(Eigen::Index rows, Eigen::Index cols, Eigen::Index blockColumns, SolveBlock solveBlock) const;

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vesalius
