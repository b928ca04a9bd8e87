#include "vesalius/fit/plastic_laplacian.h"

#include "vesalius/core/error.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace vesalius::fit {

const std::array<double, 6> kPlasticStrainWeights{1.0, std::sqrt(2.0), std::sqrt(2.0), 1.0, std::sqrt(2.0), 1.0};

namespace {

using Eigen::Index;

// BLAS's symmetric rank-k update, C := α AᵀA + β C (lower triangle). The Woodbury setup's Gram matrix
// costs #T · #C² with #C in the hundreds or thousands; the BLAS kernel (OpenBLAS picks AVX2/FMA at run
// time) is several times faster than Eigen's portable SSE2 build.
extern "C" void dsyrk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha,
                       const double* a, const int* lda, const double* beta, double* c, const int* ldc);

// GᵀG α, lower triangle only, for a row-major G (rows by n): row blocks on all cores, summed in a fixed
// order so that results are reproducible. Row-major G is the column-major n by rows block Gᵀ, so each
// row block is one contiguous BLAS call (Gᵀ Gᵀᵀ, "N") on the calling thread (CHOLMOD's setting keeps
// OpenBLAS single-threaded).
Eigen::MatrixXd lowerGram(const RowMajorMatrixXd& G, double alpha) {
  constexpr Index kRowBlock = 8192;
  const int n = int(G.cols());
  return tbb::parallel_deterministic_reduce(
      tbb::blocked_range<Index>(0, G.rows(), kRowBlock), Eigen::MatrixXd(Eigen::MatrixXd::Zero(n, n)),
      [&](const tbb::blocked_range<Index>& r, Eigen::MatrixXd sum) {
        const int k = int(r.size());
        const double beta = 1.0;
        if (n > 0 && k > 0) dsyrk_("L", "N", &n, &k, &alpha, G.data() + r.begin() * n, &n, &beta, sum.data(), &n);
        return sum;
      },
      [](Eigen::MatrixXd a, const Eigen::MatrixXd& b) {
        a += b;
        return a;
      });
}

double weightSquared(Index c) { return kPlasticStrainWeights[std::size_t(c)] * kPlasticStrainWeights[std::size_t(c)]; }

// The column sums of X, over row blocks in parallel and summed in a fixed order.
Eigen::RowVectorXd columnSums(const RowMajorMatrixXd& X) {
  constexpr Index kRowBlock = 4096;
  return tbb::parallel_deterministic_reduce(
      tbb::blocked_range<Index>(0, X.rows(), kRowBlock), Eigen::RowVectorXd(Eigen::RowVectorXd::Zero(X.cols())),
      [&](const tbb::blocked_range<Index>& r, Eigen::RowVectorXd sum) {
        sum += X.middleRows(r.begin(), r.size()).colwise().sum();
        return sum;
      },
      [](Eigen::RowVectorXd a, const Eigen::RowVectorXd& b) {
        a += b;
        return a;
      });
}

// True if every tet reaches tet 0 through shared faces (off-diagonal entries of Lsc).
bool faceConnected(const Eigen::SparseMatrix<double>& Lsc) {
  std::vector<char> seen(std::size_t(Lsc.rows()), 0);
  std::vector<Index> stack{0};
  seen[0] = 1;
  Index reached = 1;
  while (!stack.empty()) {
    const Index t = stack.back();
    stack.pop_back();
    for (Eigen::SparseMatrix<double>::InnerIterator it(Lsc, t); it; ++it)
      if (it.value() != 0.0 && !seen[std::size_t(it.row())]) {
        seen[std::size_t(it.row())] = 1;
        ++reached;
        stack.push_back(it.row());
      }
  }
  return reached == Lsc.rows();
}

}  // namespace

Eigen::SparseMatrix<double> tetAdjacencyLaplacian(const MatrixX4i& T) {
  if (T.size() > 0 && T.minCoeff() < 0) throw BadInput("", "tet mesh has a negative vertex index");
  // Each face as its sorted vertices plus the tet it belongs to; equal faces end up next to each other.
  std::vector<std::array<int, 4>> faces;
  faces.reserve(std::size_t(4 * T.rows()));
  for (int t = 0; t < int(T.rows()); ++t)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 4> f{};
      for (int k = 0, n = 0; k < 4; ++k)
        if (k != skip) f[std::size_t(n++)] = T(t, k);
      std::sort(f.begin(), f.begin() + 3);
      f[3] = t;
      faces.push_back(f);
    }
  tbb::parallel_sort(faces.begin(), faces.end());
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && std::equal(faces[i].begin(), faces[i].begin() + 3, faces[j].begin())) ++j;
    if (j - i > 2)
      throw BadInput("", "tet mesh has a face shared by " + std::to_string(j - i) + " tets");
    if (j - i == 2) {
      const int a = faces[i][3], b = faces[i + 1][3];
      entries.insert(entries.end(), {{a, b, -1.0}, {b, a, -1.0}, {a, a, 1.0}, {b, b, 1.0}});
    }
    i = j;
  }
  Eigen::SparseMatrix<double> Lsc(T.rows(), T.rows());
  Lsc.setFromTriplets(entries.begin(), entries.end());
  return Lsc;
}

Eigen::VectorXd applyPlasticLaplacian(const Eigen::SparseMatrix<double>& Lsc, const Eigen::VectorXd& s) {
  const Index m = Lsc.rows();
  if (s.size() != 6 * m)
    throw BadInput("", "plastic strains have " + std::to_string(s.size()) + " entries, not 6 x " + std::to_string(m));
  // Row c of the 6 by #T view is s_c; Lsc is symmetric, so s_cᵀ Lsc = (Lsc s_c)ᵀ.
  const Eigen::Map<const Eigen::Matrix<double, 6, Eigen::Dynamic>> S(s.data(), 6, m);
  Eigen::VectorXd out(6 * m);
  Eigen::Map<Eigen::Matrix<double, 6, Eigen::Dynamic>> O(out.data(), 6, m);
  O.noalias() = S * Lsc;
  O = Eigen::Map<const Eigen::Matrix<double, 6, 1>>(kPlasticStrainWeights.data()).asDiagonal() * O;
  return out;
}

Eigen::MatrixXd plasticLaplacianNullspace(Index tetCount) {
  Eigen::MatrixXd psi = Eigen::MatrixXd::Zero(6 * tetCount, 6);
  const double value = 1.0 / std::sqrt(double(tetCount));
  for (Index t = 0; t < tetCount; ++t)
    for (Index c = 0; c < 6; ++c) psi(6 * t + c, c) = value;
  return psi;
}

SmoothnessBaseSolver::SmoothnessBaseSolver(const Eigen::SparseMatrix<double>& Lsc) : tetCount_(Lsc.rows()), Lsc_(Lsc) {
  if (tetCount_ == 0 || Lsc.cols() != tetCount_) throw BadInput("", "smoothness solver: empty or non-square Lsc");
  if (!faceConnected(Lsc))
    throw BadInput("", "tet mesh is not face-connected; the plastic strain Laplacian has a larger nullspace");
  if (tetCount_ == 1) return;
  groundedCholesky_.factor(Lsc.bottomRightCorner(tetCount_ - 1, tetCount_ - 1));
  groundedOrder_ = groundedCholesky_.permutation().array() + 1;
}

// A block with zero-mean columns is stored without its row 0, which is minus the sum of the others, and
// with its rows in the grounded factor's order (row i: tet groundedOrder_(i)), so that the solves need
// no permuting copies. Lsc⁺ b for b ⊥ 1: solve the grounded system for x' (x'_0 = 0), then subtract the
// mean of [0; x'].
Eigen::RowVectorXd SmoothnessBaseSolver::applyScalarPseudoInverse(RowMajorMatrixXd& X) const {
  if (tetCount_ == 1) return Eigen::RowVectorXd::Zero(X.cols());  // a single tet: Lsc = 0, blocks are empty
  groundedCholesky_.solvePermutedInPlace(X);
  const Eigen::RowVectorXd mean = columnSums(X) / double(tetCount_);
  tbb::parallel_for(tbb::blocked_range<Index>(0, X.rows(), 4096), [&](const tbb::blocked_range<Index>& r) {
    X.middleRows(r.begin(), r.size()).rowwise() -= mean;
  });
  return mean;
}

Eigen::MatrixXd SmoothnessBaseSolver::solve(const Eigen::MatrixXd& h, double smoothnessScale) const {
  const Index m = tetCount_, K = h.cols();
  if (h.rows() != 6 * m) throw BadInput("", "smoothness solver: right-hand side has the wrong number of rows");
  // Component-major block X (#T − 1 by 6K, row-major): entry (i, 6k + c) is component c of column k at
  // the tet of row i, mean removed (projection onto the range of L, Singular Lemma (iii)); each row is
  // six contiguous entries of h per column.
  Eigen::MatrixXd mean(6, K);
  for (Index k = 0; k < K; ++k)
    mean.col(k) = Eigen::Map<const Eigen::Matrix<double, 6, Eigen::Dynamic>>(h.col(k).data(), 6, m).rowwise().mean();
  RowMajorMatrixXd X(m - 1, 6 * K);
  tbb::parallel_for(tbb::blocked_range<Index>(0, m - 1, 4096), [&](const tbb::blocked_range<Index>& r) {
    for (Index i = r.begin(); i < r.end(); ++i)
      for (Index k = 0; k < K; ++k)
        X.row(i).segment<6>(6 * k) = (h.col(k).segment<6>(6 * groundedOrder_(i)) - mean.col(k)).transpose();
  });
  applyScalarPseudoInverse(X);
  applyScalarPseudoInverse(X);
  // Back to tet-major: (1/(a ξ_c²)) (Lsc⁺)² h_c − (ψ_cᵀh) ψ_c, where (ψ_cᵀh) ψ_c is the mean of h_c; tet
  // 0's row is minus the sum of the others (the columns have zero mean).
  Eigen::Array<double, 6, 1> scale;
  for (Index c = 0; c < 6; ++c) scale(c) = 1.0 / (smoothnessScale * weightSquared(c));
  Eigen::MatrixXd y(6 * m, K);
  const auto put = [&](Index t, const auto& row) {
    for (Index k = 0; k < K; ++k)
      y.col(k).segment<6>(6 * t) = row.template segment<6>(6 * k).transpose().array() * scale - mean.col(k).array();
  };
  put(0, Eigen::RowVectorXd(-columnSums(X)));
  tbb::parallel_for(tbb::blocked_range<Index>(0, m - 1, 4096), [&](const tbb::blocked_range<Index>& r) {
    for (Index i = r.begin(); i < r.end(); ++i) put(groundedOrder_(i), X.row(i));
  });
  return y;
}

Eigen::MatrixXd SmoothnessBaseSolver::sandwich(const ConstraintJacobian& Z, const Eigen::MatrixXd& Zpsi) const {
  const Index m = tetCount_, C = Z.rows();
  if (Z.cols() != 6 * m) throw BadInput("", "smoothness solver: Z has the wrong number of columns");
  if (Zpsi.rows() != C || Zpsi.cols() != 6) throw BadInput("", "smoothness solver: Z ψ is not #C by 6");
  // Z (L²)⁺ Zᵀ = Σ_c G_cᵀ G_c / ξ_c² for G_c = Lsc⁺ (Z_cᵀ − mean), one component at a time in one buffer
  // (#T by #C, a sixth of Z): first touches of fresh memory cost 20 µs a page on a virtual machine, more
  // than the work that fills it (bench_fit woodbury: 2-5 s for a buffer as large as Z). The means of Z_c's
  // rows are Z ψ_c / √#T. G_c is row-major with its rows in the factor's order: row i is Z's column
  // 6 t + c for the tet t of that row, and the supernodal solves and the Gram matrix read whole rows;
  // the Gram matrix does not depend on the rows' order.
  RowMajorMatrixXd G(m - 1, C);
  Eigen::MatrixXd result = Eigen::MatrixXd::Zero(C, C);
  for (Index c = 0; c < 6; ++c) {
    const Eigen::VectorXd shift = Zpsi.col(c) / std::sqrt(double(m));
    tbb::parallel_for(tbb::blocked_range<Index>(0, m - 1, 1024), [&](const tbb::blocked_range<Index>& r) {
      for (Index i = r.begin(); i < r.end(); ++i) {
        Eigen::Map<Eigen::VectorXd> row(G.row(i).data(), C);
        Z.column(6 * groundedOrder_(i) + c, row);
        row -= shift;
      }
    });
    const Eigen::RowVectorXd mean = applyScalarPseudoInverse(G);
    const double weight = 1.0 / weightSquared(c);
    result += lowerGram(G, weight);
    result.selfadjointView<Eigen::Lower>().rankUpdate(mean.transpose(), weight);  // row 0 of G_c: −mean
  }
  return result.selfadjointView<Eigen::Lower>();
}

}  // namespace vesalius::fit
