#include "vesalius/transfer/surface_harmonic_extension.h"

#include "skin_correspondences.h"

#include "vesalius/core/error.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

namespace vesalius::transfer {

Eigen::MatrixXd extendHarmonically(const Eigen::MatrixXd& values, const std::vector<char>& known, const MatrixX3i& F) {
  const Eigen::Index n = values.rows();
  if (known.size() != std::size_t(n)) throw BadInput("", "harmonic extension: one known flag per value row is needed");
  if (F.size() && (F.minCoeff() < 0 || F.maxCoeff() >= n))
    throw BadInput("", "harmonic extension: a face indexes outside the vertices");
  const std::vector<std::vector<int>> neighbours = detail::skinNeighbours(n, F);
  // Unknown vertices joined to a known one through unknown ones; the rest (pieces with nothing known) get 0.
  std::vector<char> reachable(std::size_t(n), 0);
  std::vector<int> queue;
  for (Eigen::Index v = 0; v < n; ++v)
    if (known[std::size_t(v)])
      for (const int w : neighbours[std::size_t(v)])
        if (!known[std::size_t(w)] && !reachable[std::size_t(w)]) {
          reachable[std::size_t(w)] = 1;
          queue.push_back(w);
        }
  for (std::size_t q = 0; q < queue.size(); ++q)
    for (const int w : neighbours[std::size_t(queue[q])])
      if (!known[std::size_t(w)] && !reachable[std::size_t(w)]) {
        reachable[std::size_t(w)] = 1;
        queue.push_back(w);
      }
  Eigen::MatrixXd result = values;
  std::vector<Eigen::Index> freeIndex(std::size_t(n), -1);
  Eigen::Index freeCount = 0;
  for (Eigen::Index v = 0; v < n; ++v) {
    if (reachable[std::size_t(v)]) freeIndex[std::size_t(v)] = freeCount++;
    else if (!known[std::size_t(v)]) result.row(v).setZero();
  }
  if (freeCount == 0) return result;
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(freeCount, values.cols());
  for (Eigen::Index v = 0; v < n; ++v) {
    const Eigen::Index i = freeIndex[std::size_t(v)];
    if (i < 0) continue;
    entries.emplace_back(i, i, double(neighbours[std::size_t(v)].size()));
    for (const int w : neighbours[std::size_t(v)]) {
      const Eigen::Index j = freeIndex[std::size_t(w)];
      if (j >= 0) entries.emplace_back(i, j, -1.0);
      else rhs.row(i) += values.row(w);  // known: a free vertex's neighbours are free or known
    }
  }
  Eigen::SparseMatrix<double> L(freeCount, freeCount);
  L.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(L);
  if (solver.info() != Eigen::Success) throw NumericalFailure("harmonic extension: the graph Laplacian did not factor");
  const Eigen::MatrixXd solved = solver.solve(rhs);
  for (Eigen::Index v = 0; v < n; ++v)
    if (freeIndex[std::size_t(v)] >= 0) result.row(v) = solved.row(freeIndex[std::size_t(v)]);
  return result;
}

}  // namespace vesalius::transfer
