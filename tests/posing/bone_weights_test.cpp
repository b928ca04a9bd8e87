// Bone weights by Laplace diffusion (Sujar et al. 2018, §3.3): constraints (eqs. 2-3) on a TetGen mesh of a body
// with bones, exact linear weights along a bar, and the refusals.
#include "vesalius/posing/bone_weights.h"

#include "vesalius/core/error.h"
#include "vesalius/meshing/tetrahedralize.h"

#include "test_shapes.h"
#include "test_tets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace vesalius;

namespace {

// A TetGen quality mesh of a ball of radius 40 holding three bones (balls of radius 8); bone vertices are
// the corners of the tets labelled as bone, as in Sujar et al. 2018, §3.2.
struct BodyWithBones {
  TetMesh mesh;
  Eigen::VectorXi boneOfVertex;
};

BodyWithBones bodyWithBones() {
  meshing::TetrahedralizeOptions options;
  options.targetTets = 40000;
  BodyWithBones b{meshing::tetrahedralizeRegions({{test::sphere(4, 40.0), 1, "body"},
                                                  {test::sphere(3, 8.0, {-22, 0, 0}), 2, "bone 0"},
                                                  {test::sphere(3, 8.0, {6, 10, 0}), 3, "bone 1"},
                                                  {test::sphere(3, 8.0, {10, -14, 12}), 4, "bone 2"}},
                                                 options),
                  {}};
  const Eigen::VectorXi& label = b.mesh.tetAttributes.integer.at(kLabel);
  b.boneOfVertex = Eigen::VectorXi::Constant(b.mesh.V.rows(), -1);
  for (Eigen::Index t = 0; t < b.mesh.T.rows(); ++t)
    if (label[t] >= 2)
      for (int k = 0; k < 4; ++k) b.boneOfVertex[b.mesh.T(t, k)] = label[t] - 2;
  return b;
}

}  // namespace

TEST(BoneWeights, MeetSujarEtAlsConstraintsOnATetgenBody) {
  const BodyWithBones b = bodyWithBones();
  const Eigen::MatrixXd raw = posing::computeBoneWeights(b.mesh.V, b.mesh.T, b.boneOfVertex, {false});
  const Eigen::MatrixXd W = posing::computeBoneWeights(b.mesh.V, b.mesh.T, b.boneOfVertex);
  ASSERT_EQ(W.cols(), 3);
  // The raw FEM solution: rows sum to 1 (constants are harmonic), values leave [0, 1] only by the
  // failure of the discrete maximum principle on obtuse tets.
  const double excursion = std::max({0.0, -raw.minCoeff(), raw.maxCoeff() - 1.0});
  const double rawSumError = (raw.rowwise().sum().array() - 1.0).abs().maxCoeff();
  RecordProperty("vertices", int(b.mesh.V.rows()));
  RecordProperty("raw_excursion", testing::PrintToString(excursion));
  RecordProperty("raw_row_sum_error", testing::PrintToString(rawSumError));
  std::printf("bone weights on %ld vertices, %ld tets: raw excursion outside [0, 1] %.3e, raw row-sum error %.1e\n",
              long(b.mesh.V.rows()), long(b.mesh.T.rows()), excursion, rawSumError);
  EXPECT_LT(excursion, 1e-2);
  EXPECT_LT(rawSumError, 1e-9);
  EXPECT_GE(W.minCoeff(), 0.0);
  EXPECT_LE(W.maxCoeff(), 1.0);
  EXPECT_LT((W.rowwise().sum().array() - 1.0).abs().maxCoeff(), 1e-12);
  for (Eigen::Index v = 0; v < W.rows(); ++v) {
    if (b.boneOfVertex[v] < 0) continue;
    for (Eigen::Index j = 0; j < 3; ++j) ASSERT_EQ(W(v, j), j == b.boneOfVertex[v] ? 1.0 : 0.0) << "vertex " << v;
  }
}

TEST(BoneWeights, AnObtuseTetBreaksTheMaximumPrincipleAndIsClamped) {
  // One tet: bone 0 at a, bone 1 on the edge cd, the free vertex f across the edge from a, with a dihedral
  // angle θ at cd above 90°. The linear weight of least energy that is 1 at a and 0 on cd is cos θ < 0 at f
  // (∇φ_a·∇φ_f = -cos θ / (h_a h_f), and h_a = h_f here): the FEM solution leaves [0, 1].
  TetMesh tet;
  tet.V.resize(4, 3);
  tet.V << -1, 0, 0, 1, 0, 0, 0, 1, 0.3, 0, -1, 0.3;  // c, d, a, f
  tet.T.resize(1, 4);
  tet.T << 0, 1, 2, 3;
  if (tetVolumes(tet.V, tet.T)[0] < 0) tet.T.row(0) << 1, 0, 2, 3;
  Eigen::VectorXi bone(4);
  bone << 1, 1, 0, -1;
  const double cosTheta = std::cos(M_PI - 2.0 * std::atan(0.3));
  const Eigen::MatrixXd raw = posing::computeBoneWeights(tet.V, tet.T, bone, {false});
  EXPECT_NEAR(raw(3, 0), cosTheta, 1e-12);
  EXPECT_NEAR(raw(3, 1), 1.0 - cosTheta, 1e-12);
  const Eigen::MatrixXd W = posing::computeBoneWeights(tet.V, tet.T, bone);
  EXPECT_EQ(W(3, 0), 0.0);
  EXPECT_EQ(W(3, 1), 1.0);
}

TEST(BoneWeights, AreLinearAlongABarBetweenTwoBones) {
  // Bone 0 is the face x = 0, bone 1 the face x = 20: the harmonic weight of bone 0 is 1 - x/20, which
  // linear elements reproduce exactly.
  const TetMesh bar = test::boxTets(20, 3, 3, 1.0);
  Eigen::VectorXi bone = Eigen::VectorXi::Constant(bar.V.rows(), -1);
  for (Eigen::Index v = 0; v < bar.V.rows(); ++v) {
    if (bar.V(v, 0) == 0.0) bone[v] = 0;
    if (bar.V(v, 0) == 20.0) bone[v] = 1;
  }
  const Eigen::MatrixXd W = posing::computeBoneWeights(bar.V, bar.T, bone);
  const double error = (W.col(0) - (1.0 - bar.V.col(0).array() / 20.0).matrix()).cwiseAbs().maxCoeff();
  RecordProperty("max_error", testing::PrintToString(error));
  EXPECT_LT(error, 1e-3);
  EXPECT_LT(error, 1e-10);  // not just close: exact up to the solver's round-off
}

TEST(BoneWeights, RefuseTissueThatNoBoneReaches) {
  // Two separate boxes; only the first holds a bone.
  const TetMesh a = test::boxTets(2, 2, 2), b = test::boxTets(2, 2, 2);
  TetMesh both;
  both.V.resize(2 * a.V.rows(), 3);
  both.V << a.V, (b.V.rowwise() + Eigen::RowVector3d(5, 0, 0));
  both.T.resize(2 * a.T.rows(), 4);
  both.T << a.T, (b.T.array() + int(a.V.rows())).matrix();
  Eigen::VectorXi bone = Eigen::VectorXi::Constant(both.V.rows(), -1);
  bone[0] = 0;
  try {
    posing::computeBoneWeights(both.V, both.T, bone);
    ADD_FAILURE() << "accepted";
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("27 vertices are in no connected part"), std::string::npos) << e.what();
  }
}

TEST(BoneWeights, RefuseAMissingBoneAndAWrongLabelCount) {
  const TetMesh box = test::boxTets(2, 2, 2);
  Eigen::VectorXi bone = Eigen::VectorXi::Constant(box.V.rows(), -1);
  bone[0] = 1;  // bone 0 has no vertex
  EXPECT_THROW(posing::computeBoneWeights(box.V, box.T, bone), BadInput);
  EXPECT_THROW(posing::computeBoneWeights(box.V, box.T, Eigen::VectorXi::Constant(3, 0)), UsageError);
  EXPECT_THROW(posing::computeBoneWeights(box.V, box.T, Eigen::VectorXi::Constant(box.V.rows(), -1)), BadInput);
}
