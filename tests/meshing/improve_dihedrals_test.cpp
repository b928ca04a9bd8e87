// improveDihedrals (an internal step of tetrahedralize) on a sliver it cannot smooth directly: all four of
// its vertices lie on the boundary, as TetGen leaves them across thin plates of bone.
#include "improve_dihedrals.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/tet_quality.h"

#include <gtest/gtest.h>

namespace vesalius {
namespace {

// A nearly flat tet a b c d (ridge a-b on top, ridge c-d below), capped by apex p over its two upper faces
// and apex q under its two lower faces. Every vertex is on the boundary; the ridges lie on no boundary face.
TetMesh cappedSliver() {
  TetMesh m;
  m.V.resize(6, 3);
  m.V << 0, 0, 0.01,  // a
      1, 1, 0.01,     // b
      1, 0, -0.01,    // c
      0, 1, -0.01,    // d
      0.5, 0.5, 1,    // p
      0.5, 0.5, -1;   // q
  m.T.resize(5, 4);
  m.T << 0, 1, 2, 3,  // the sliver
      0, 1, 3, 4,     // p over a b d
      1, 0, 2, 4,     // p over a b c
      2, 3, 0, 5,     // q under c d a
      3, 2, 1, 5;     // q under c d b
  const Eigen::VectorXd v = tetVolumes(m.V, m.T);
  for (Eigen::Index t = 0; t < m.T.rows(); ++t)
    if (v(t) < 0) std::swap(m.T(t, 2), m.T(t, 3));
  m.tetAttributes.integer[kLabel] = Eigen::VectorXi::Constant(5, 7);
  return m;
}

TEST(ImproveDihedrals, SliverWithEveryVertexOnTheBoundaryIsSplitAndSmoothed) {
  TetMesh m = cappedSliver();
  const double before = tetQualityReport(m.V, m.T).minDihedral;
  const double volume = tetVolumes(m.V, m.T).sum();
  const MatrixX3i boundary = tetBoundary(m.T);
  ASSERT_LT(before, 10.0);

  meshing::improveDihedrals(m, 12.0, 0.0);
  const TetQualityReport after = tetQualityReport(m.V, m.T);
  RecordProperty("min_dihedral_before", std::to_string(before));
  RecordProperty("min_dihedral_after", std::to_string(after.minDihedral));
  EXPECT_EQ(m.V.rows(), 7);  // one midpoint added
  EXPECT_EQ(after.inverted, 0);
  EXPECT_GT(after.minDihedral, 2.0 * before);
  EXPECT_NEAR(tetVolumes(m.V, m.T).sum(), volume, 1e-12);
  EXPECT_TRUE(m.V.topRows(6).isApprox(cappedSliver().V));  // boundary vertices stay
  EXPECT_NEAR(enclosedVolume(m.V, tetBoundary(m.T)), enclosedVolume(m.V, boundary), 1e-12);
  EXPECT_EQ(m.tetAttributes.integer.at(kLabel).size(), m.T.rows());
  EXPECT_TRUE((m.tetAttributes.integer.at(kLabel).array() == 7).all());
}

TEST(ImproveDihedrals, TetsOfTwoLabelsAcrossTheRidgeKeepItFixed) {
  // With the upper caps labelled differently, the sliver's upper ridge lies on an interface and the lower
  // ridge is the one split; the interface faces keep their vertices.
  TetMesh m = cappedSliver();
  m.tetAttributes.integer[kLabel] << 7, 8, 8, 7, 7;
  meshing::improveDihedrals(m, 12.0, 0.0);
  ASSERT_EQ(m.V.rows(), 7);
  EXPECT_TRUE(m.V.topRows(6).isApprox(cappedSliver().V));
  EXPECT_EQ(tetQualityReport(m.V, m.T).inverted, 0);
}

}  // namespace
}  // namespace vesalius
