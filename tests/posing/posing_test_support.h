// Shared by the posing tests: the bar of Sujar et al. 2018, Fig. 7 (four bones along a box bar of Kuhn tets) and its
// poses, and the volume change of a posed tet mesh.
#pragma once

#include "vesalius/core/error.h"
#include "vesalius/core/mesh.h"

#include "test_tets.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <utility>

#include <vector>

namespace vesalius::test {

struct BoneBar {
  TetMesh mesh;
  Eigen::VectorXi boneOfVertex;  // #V: -1 for tissue, 0..3 for the four bones
  Eigen::Vector3d middleJoint;   // between bones 1 and 2, on the bar's axis
};

// A bar [0, 48] × [0, 8] × [0, 8] of cubes of side 1/n with four bones along its axis: bone j is the core
// |y - 4|, |z - 4| <= 2 of its quarter of the bar, less 2 either side of the three joints (x = 12, 24, 36),
// so tissue surrounds the bones and fills the joints.
inline BoneBar fourBoneBar(int n = 1) {
  BoneBar bar{boxTets(48 * n, 8 * n, 8 * n, 1.0 / n), {}, Eigen::Vector3d(24, 4, 4)};
  bar.boneOfVertex = Eigen::VectorXi::Constant(bar.mesh.V.rows(), -1);
  for (Eigen::Index v = 0; v < bar.mesh.V.rows(); ++v) {
    const Eigen::RowVector3d x = bar.mesh.V.row(v);
    if (std::abs(x.y() - 4) > 2 + 1e-9 || std::abs(x.z() - 4) > 2 + 1e-9) continue;
    const int bone = std::min(3, int(x.x() / 12 + 1e-9));
    const double from = bone == 0 ? 0 : 12 * bone + 2, to = bone == 3 ? 48 : 12 * bone + 10;
    if (x.x() > from - 1e-9 && x.x() < to + 1e-9) bar.boneOfVertex[v] = bone;
  }
  return bar;
}

// Bones 0 and 1 stay; bones 2 and 3 turn by `degrees` about `axis` through the middle joint.
inline std::vector<Eigen::Isometry3d> middleJointPose(const BoneBar& bar, const Eigen::Vector3d& axis, double degrees) {
  Eigen::Isometry3d turn = Eigen::Isometry3d::Identity();
  turn.translate(bar.middleJoint).rotate(Eigen::AngleAxisd(degrees * M_PI / 180.0, axis.normalized())).translate(-bar.middleJoint);
  return {Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity(), turn, turn};
}

// A per-frame post-step of skinning built on a rest rig, `build(V, T, boneOfVertex)`, refuses with BadInput a
// bone index list of the wrong length, an inverted rest tet and a tet referring to a missing vertex
// (src/rest_rig.h).
template <class Build>
void expectBadRestRigsRefused(const TetMesh& mesh, const Eigen::VectorXi& boneOfVertex, Build build) {
  EXPECT_THROW(build(mesh.V, mesh.T, boneOfVertex.head(10)), BadInput);
  MatrixX4i flipped = mesh.T;
  std::swap(flipped(5, 2), flipped(5, 3));
  EXPECT_THROW(build(mesh.V, flipped, boneOfVertex), BadInput);
  MatrixX4i outside = mesh.T;
  outside(0, 0) = int(mesh.V.rows());
  EXPECT_THROW(build(mesh.V, outside, boneOfVertex), BadInput);
}

// (posed volume - rest volume) / rest volume of the whole tet mesh.
inline double volumeChange(const MatrixX3d& restV, const MatrixX4i& T, const MatrixX3d& posedV) {
  const double rest = tetVolumes(restV, T).sum();
  return (tetVolumes(posedV, T).sum() - rest) / rest;
}

}  // namespace vesalius::test
