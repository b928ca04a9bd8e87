#include "vesalius/core/keep_faces.h"

#include <gtest/gtest.h>

namespace vesalius {
namespace {

// Two triangles sharing an edge and a third apart, with a vertex no face uses.
TriMesh stripWithAnIsland() {
  TriMesh m;
  m.V.resize(8, 3);
  m.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 9, 9, 9, 5, 0, 0, 6, 0, 0, 5, 1, 0;
  m.F.resize(3, 3);
  m.F << 0, 1, 2, 0, 2, 3, 5, 6, 7;
  m.vertexAttributes.real["x"] = m.V.col(0);
  m.faceAttributes.integer["id"] = Eigen::Vector3i(10, 11, 12);
  return m;
}

TEST(KeepFaces, KeepsTheChosenFacesAndOnlyTheVerticesTheyUse) {
  const TriMesh m = stripWithAnIsland();
  const TriMesh kept = keepFaces(m, {false, true, true});
  ASSERT_EQ(kept.F.rows(), 2);
  ASSERT_EQ(kept.V.rows(), 6);  // 0, 2, 3 of the second face and 5, 6, 7 of the third: not 1, not the lone 4
  kept.validate("kept");
  for (Eigen::Index f = 0; f < kept.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(kept.V.row(kept.F(f, k)), m.V.row(m.F(f + 1, k))) << "face " << f << " corner " << k;
  EXPECT_EQ(kept.faceAttributes.integer.at("id"), Eigen::Vector2i(11, 12));
  EXPECT_EQ(kept.vertexAttributes.real.at("x"), kept.V.col(0));
}

TEST(KeepFaces, NoFaceKeptIsAnEmptyMesh) {
  const TriMesh kept = keepFaces(stripWithAnIsland(), {false, false, false});
  EXPECT_EQ(kept.F.rows(), 0);
  EXPECT_EQ(kept.V.rows(), 0);
}

}  // namespace
}  // namespace vesalius
