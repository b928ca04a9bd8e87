#include "vesalius/posing/bone_vertices.h"

#include "vesalius/core/error.h"

#include <algorithm>
#include <map>

namespace vesalius::posing {

namespace {

// In soft-tissue tets that span two bones, the vertices of every bone but the latest set to -1, except
// where a bone would be left without a vertex.
void releaseBridges(const MatrixX4i& T, const Eigen::VectorXi& tetBone, Eigen::VectorXi& bone) {
  Eigen::VectorXi released = bone;
  for (Eigen::Index t = 0; t < T.rows(); ++t) {
    if (tetBone[t] >= 0) continue;
    const int latest = std::max({bone[T(t, 0)], bone[T(t, 1)], bone[T(t, 2)], bone[T(t, 3)]});
    for (int c = 0; c < 4; ++c)
      if (bone[T(t, c)] >= 0 && bone[T(t, c)] < latest) released[T(t, c)] = -1;
  }
  const int bones = bone.size() > 0 ? bone.maxCoeff() + 1 : 0;
  for (int b = 0; b < bones; ++b)
    if ((bone.array() == b).any() && !(released.array() == b).any())
      released = (bone.array() == b).select(bone, released);
  bone = released;
}

}  // namespace

Eigen::VectorXi boneVerticesOfLabels(const MatrixX4i& T, const Eigen::VectorXi& tetLabel,
                                     const std::vector<std::vector<Label>>& labelsOfBone, Eigen::Index vertexCount) {
  if (tetLabel.size() != T.rows())
    throw BadInput("", std::to_string(tetLabel.size()) + " tet labels for " + std::to_string(T.rows()) + " tets");
  if (T.rows() > 0 && (T.minCoeff() < 0 || T.maxCoeff() >= vertexCount))
    throw BadInput("", "a tet refers to a vertex outside the " + std::to_string(vertexCount) + " vertices");
  std::map<int, int> boneOfLabel;
  for (std::size_t b = 0; b < labelsOfBone.size(); ++b)
    for (Label l : labelsOfBone[b]) boneOfLabel[int(l)] = int(b);
  Eigen::VectorXi bone = Eigen::VectorXi::Constant(vertexCount, -1), tetBone(T.rows());
  for (Eigen::Index t = 0; t < T.rows(); ++t) {
    const auto found = boneOfLabel.find(tetLabel[t]);
    tetBone[t] = found == boneOfLabel.end() ? -1 : found->second;
    if (tetBone[t] < 0) continue;
    for (int c = 0; c < 4; ++c) bone[T(t, c)] = std::max(bone[T(t, c)], tetBone[t]);
  }
  releaseBridges(T, tetBone, bone);
  return bone;
}

}  // namespace vesalius::posing
