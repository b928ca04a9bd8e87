#include "vesalius/fem/plastic_fem.h"

#include "vesalius/core/error.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <string>

namespace vesalius {

PlasticFem::PlasticFem(const MatrixX3d& restV, const MatrixX4i& T, StableNeoHookean material)
    : vertexCount_(int(restV.rows())), T_(T), material_(material), rest_(T.rows()), restVolumes_(T.rows()) {
  if (!(material.mu > 0) || !(material.lambda > 0)) throw BadInput("", "plastic FEM needs mu > 0 and lambda > 0");
  if (T.rows() == 0) throw BadInput("", "plastic FEM needs at least one tet");
  if (T.minCoeff() < 0 || T.maxCoeff() >= vertexCount_)
    throw BadInput("", "plastic FEM: a tet indexes a vertex that does not exist");
  for (int t = 0; t < tetCount(); ++t) {
    Eigen::Matrix<double, 4, 3> c;
    for (int k = 0; k < 4; ++k) c.row(k) = restV.row(T(t, k));
    try {
      rest_[t] = plasticTetRest(c);
    } catch (const BadInput& e) {
      throw BadInput("", "plastic FEM: tet " + std::to_string(t) + ": " + e.problem());
    }
    restVolumes_[t] = rest_[t].volume;
  }
  buildStiffnessPattern();
}

// Column 3v + l holds rows 3u..3u+2 for v itself and every u sharing a tet with v, in order of u.
void PlasticFem::buildStiffnessPattern() {
  std::vector<std::vector<int>> neighbours(vertexCount_);
  for (int v = 0; v < vertexCount_; ++v) neighbours[v].push_back(v);
  for (int t = 0; t < tetCount(); ++t)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) neighbours[T_(t, b)].push_back(T_(t, a));
  std::vector<int> firstOfColumn(3 * vertexCount_ + 1, 0);
  for (int v = 0; v < vertexCount_; ++v) {
    std::sort(neighbours[v].begin(), neighbours[v].end());
    neighbours[v].erase(std::unique(neighbours[v].begin(), neighbours[v].end()), neighbours[v].end());
    for (int l = 0; l < 3; ++l)
      firstOfColumn[3 * v + l + 1] = firstOfColumn[3 * v + l] + 3 * int(neighbours[v].size());
  }
  pattern_ = Eigen::SparseMatrix<double>(3 * vertexCount_, 3 * vertexCount_);
  pattern_.resizeNonZeros(firstOfColumn.back());
  std::copy(firstOfColumn.begin(), firstOfColumn.end(), pattern_.outerIndexPtr());
  std::fill_n(pattern_.valuePtr(), pattern_.nonZeros(), 0.0);
  for (int v = 0; v < vertexCount_; ++v)
    for (int l = 0; l < 3; ++l)
      for (std::size_t i = 0; i < neighbours[v].size(); ++i)
        for (int k = 0; k < 3; ++k)
          pattern_.innerIndexPtr()[firstOfColumn[3 * v + l] + 3 * i + k] = 3 * neighbours[v][i] + k;
  blockStart_.resize(tetCount());
  for (int t = 0; t < tetCount(); ++t)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        const std::vector<int>& column = neighbours[T_(t, b)];
        const auto row = std::lower_bound(column.begin(), column.end(), T_(t, a)) - column.begin();
        for (int l = 0; l < 3; ++l)
          blockStart_[t][3 * (4 * a + b) + l] = firstOfColumn[3 * T_(t, b) + l] + 3 * int(row);
      }
}

Eigen::Matrix<double, 4, 3> PlasticFem::corners(const Eigen::VectorXd& x, int t) const {
  Eigen::Matrix<double, 4, 3> c;
  for (int k = 0; k < 4; ++k) c.row(k) = x.segment<3>(3 * T_(t, k)).transpose();
  return c;
}

void PlasticFem::checkSizes(const Eigen::VectorXd& x, const Eigen::VectorXd& s) const {
  if (x.size() != 3 * vertexCount_ || s.size() != 6 * tetCount())
    throw BadInput("", "plastic FEM: x has " + std::to_string(x.size()) + " entries and s " +
                           std::to_string(s.size()) + ", expected " + std::to_string(3 * vertexCount_) + " and " +
                           std::to_string(6 * tetCount()));
}

// Calls plasticTetDerivatives on every tet in parallel and keeps keep(derivatives) of each tet, in tet
// order, so the serial sums that follow do not depend on the number of threads.
template <class PerTet>
auto PlasticFem::perTet(const Eigen::VectorXd& x, const Eigen::VectorXd& s, const PlasticTetBlocks& blocks,
                        PerTet keep) const {
  checkSizes(x, s);
  using Kept = decltype(keep(PlasticTetDerivatives{}));
  std::vector<Kept> kept(tetCount());
  tbb::parallel_for(tbb::blocked_range<int>(0, tetCount(), 64), [&](const tbb::blocked_range<int>& range) {
    for (int t = range.begin(); t != range.end(); ++t)
      kept[t] = keep(plasticTetDerivatives(rest_[t], corners(x, t), s.segment<6>(6 * t), material_, blocks));
  });
  return kept;
}

double PlasticFem::energy(const Eigen::VectorXd& x, const Eigen::VectorXd& s) const {
  const auto e = perTet(x, s, {}, [](const PlasticTetDerivatives& d) { return d.energy; });
  double sum = 0;
  for (double v : e) sum += v;
  return sum;
}

Eigen::VectorXd PlasticFem::gradient(const Eigen::VectorXd& x, const Eigen::VectorXd& s) const {
  const auto g = perTet(x, s, {}, [](const PlasticTetDerivatives& d) { return d.gradient; });
  Eigen::VectorXd out = Eigen::VectorXd::Zero(3 * vertexCount_);
  for (int t = 0; t < tetCount(); ++t)
    for (int c = 0; c < 4; ++c) out.segment<3>(3 * T_(t, c)) += g[t].segment<3>(3 * c);
  return out;
}

Eigen::SparseMatrix<double> PlasticFem::stiffness(const Eigen::VectorXd& x, const Eigen::VectorXd& s,
                                                  bool projected) const {
  PlasticTetBlocks blocks;
  blocks.stiffness = projected ? PlasticTetBlocks::Stiffness::projected : PlasticTetBlocks::Stiffness::exact;
  const auto K = perTet(x, s, blocks, [](const PlasticTetDerivatives& d) { return d.stiffness; });
  Eigen::SparseMatrix<double> out = pattern_;
  double* values = out.valuePtr();
  for (int t = 0; t < tetCount(); ++t)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        for (int l = 0; l < 3; ++l) {
          double* column = values + blockStart_[t][3 * (4 * a + b) + l];
          for (int k = 0; k < 3; ++k) column[k] += K[t](3 * a + k, 3 * b + l);
        }
  return out;
}

Eigen::SparseMatrix<double> PlasticFem::plasticForceJacobian(const Eigen::VectorXd& x,
                                                             const Eigen::VectorXd& s) const {
  PlasticTetBlocks blocks;
  blocks.mixed = true;
  const auto mixed = perTet(x, s, blocks, [](const PlasticTetDerivatives& d) { return d.mixed; });
  // Each tet owns its 6 columns, 12 rows each; rows sorted by vertex as compressed storage requires.
  Eigen::SparseMatrix<double> out(3 * vertexCount_, 6 * tetCount());
  out.resizeNonZeros(72 * tetCount());
  for (int col = 0; col <= 6 * tetCount(); ++col) out.outerIndexPtr()[col] = 12 * col;
  for (int t = 0; t < tetCount(); ++t) {
    std::array<int, 4> order{0, 1, 2, 3};
    std::sort(order.begin(), order.end(), [&](int a, int b) { return T_(t, a) < T_(t, b); });
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) {
          const int at = 12 * (6 * t + j) + 3 * i + k;
          out.innerIndexPtr()[at] = 3 * T_(t, order[i]) + k;
          out.valuePtr()[at] = mixed[t](3 * order[i] + k, j);
        }
  }
  return out;
}

Eigen::VectorXd PlasticFem::elasticJacobians(const Eigen::VectorXd& x, const Eigen::VectorXd& s) const {
  checkSizes(x, s);
  Eigen::VectorXd J(tetCount());
  tbb::parallel_for(tbb::blocked_range<int>(0, tetCount(), 256), [&](const tbb::blocked_range<int>& range) {
    for (int t = range.begin(); t != range.end(); ++t)
      J[t] = plasticTetJacobian(rest_[t], corners(x, t), s.segment<6>(6 * t));
  });
  return J;
}

Eigen::VectorXd PlasticFem::flatten(const MatrixX3d& V) {
  const Eigen::Matrix<double, 3, Eigen::Dynamic> Vt = V.transpose();
  return Eigen::Map<const Eigen::VectorXd>(Vt.data(), Vt.size());
}

MatrixX3d PlasticFem::unflatten(const Eigen::VectorXd& x) {
  if (x.size() % 3 != 0) throw BadInput("", "unflatten: " + std::to_string(x.size()) + " is not a multiple of 3");
  return Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>>(x.data(), 3, x.size() / 3).transpose();
}

}  // namespace vesalius
