#include "vesalius/core/tet_adjacency.h"

#include "vesalius/core/error.h"

#include <numeric>

namespace vesalius {

VertexTets vertexTets(const MatrixX4i& T, Eigen::Index vertexCount) {
  if (T.size() > 0 && (T.minCoeff() < 0 || T.maxCoeff() >= vertexCount))
    throw BadInput("", "tet mesh: a tet refers to a vertex outside the mesh");
  VertexTets a;
  a.start.assign(std::size_t(vertexCount) + 1, 0);
  for (Eigen::Index i = 0; i < T.size(); ++i) ++a.start[std::size_t(T.data()[i]) + 1];
  std::partial_sum(a.start.begin(), a.start.end(), a.start.begin());
  a.tets.resize(std::size_t(T.size()));
  std::vector<int> next(a.start.begin(), a.start.end() - 1);
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    for (int c = 0; c < 4; ++c) a.tets[std::size_t(next[std::size_t(T(t, c))]++)] = int(t);
  return a;
}

std::vector<int> vertexRings(const MatrixX4i& T, const VertexTets& tetsOf, const std::vector<int>& seeds, int rings) {
  std::vector<char> reached(tetsOf.start.size() - 1, 0);
  std::vector<int> all;
  const auto reach = [&](int v) {
    if (reached[std::size_t(v)]) return;
    reached[std::size_t(v)] = 1;
    all.push_back(v);
  };
  for (int v : seeds) reach(v);
  std::size_t ringBegin = 0;
  for (int ring = 0; ring < rings && ringBegin < all.size(); ++ring) {
    const std::size_t ringEnd = all.size();
    for (std::size_t i = ringBegin; i < ringEnd; ++i)
      for (const int* t = tetsOf.begin(all[i]); t != tetsOf.end(all[i]); ++t)
        for (int c = 0; c < 4; ++c) reach(T(*t, c));
    ringBegin = ringEnd;
  }
  return all;
}

}  // namespace vesalius
