#include "vesalius/posing/bone_vertices.h"

#include "vesalius/core/error.h"

#include <map>

namespace vesalius::posing {

Eigen::VectorXi boneVerticesOfLabels(const MatrixX4i& T, const Eigen::VectorXi& tetLabel,
                                     const std::vector<std::vector<Label>>& labelsOfBone, Eigen::Index vertexCount) {
  if (tetLabel.size() != T.rows())
    throw BadInput("", std::to_string(tetLabel.size()) + " tet labels for " + std::to_string(T.rows()) + " tets");
  if (T.rows() > 0 && (T.minCoeff() < 0 || T.maxCoeff() >= vertexCount))
    throw BadInput("", "a tet refers to a vertex outside the " + std::to_string(vertexCount) + " vertices");
  std::map<int, int> boneOfLabel;
  for (std::size_t b = 0; b < labelsOfBone.size(); ++b)
    for (Label l : labelsOfBone[b]) boneOfLabel[int(l)] = int(b);
  Eigen::VectorXi bone = Eigen::VectorXi::Constant(vertexCount, -1);
  for (Eigen::Index t = 0; t < T.rows(); ++t) {
    const auto found = boneOfLabel.find(tetLabel[t]);
    if (found == boneOfLabel.end()) continue;
    for (int c = 0; c < 4; ++c) bone[T(t, c)] = std::max(bone[T(t, c)], found->second);
  }
  return bone;
}

}  // namespace vesalius::posing
