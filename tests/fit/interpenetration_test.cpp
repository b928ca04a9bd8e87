// Interpenetration removal (Wang et al. 2021, §4.1.4): two fitted meshes that overlap are pushed apart until no
// boundary vertex of either lies inside the other, without moving anything beyond the contact regions
// (the penetrating vertices' tets grown by 5 rings) and without inverting a tet.
#include "vesalius/fit/interpenetration.h"

#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/tet_locator.h"

#include "test_tets.h"

#include <gtest/gtest.h>

namespace vesalius::fit {
namespace {

TetMesh shifted(TetMesh mesh, const Eigen::RowVector3d& by) {
  mesh.V.rowwise() += by;
  return mesh;
}

// Boundary vertices of `mesh` inside `other`, counted independently of the method's own bookkeeping.
long verticesInside(const TetMesh& mesh, const TetMesh& other) {
  const TetLocator locator(other.V, other.T);
  const MatrixX3i F = tetBoundary(mesh.T);
  std::vector<char> onBoundary(std::size_t(mesh.V.rows()), 0);
  for (Eigen::Index i = 0; i < F.size(); ++i) onBoundary[std::size_t(F.data()[i])] = 1;
  long count = 0;
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    count += onBoundary[std::size_t(v)] && locator.locate(mesh.V.row(v).transpose()).has_value();
  return count;
}

// Vertices with `coordinate` beyond `limit` on the far side (below it when `below`) must not have moved.
long movedBeyond(const TetMesh& before, const TetMesh& after, double limit, bool below) {
  long moved = 0;
  for (Eigen::Index v = 0; v < before.V.rows(); ++v)
    if ((below ? before.V(v, 0) < limit : before.V(v, 0) > limit) && before.V.row(v) != after.V.row(v)) ++moved;
  return moved;
}

// Two boxes of 2 mm cubes overlapping by 1 mm along x: A = [0, 24] x [0, 12]², B = [23, 47] x ... offset
// in y and z so that the overlap is a proper box. The contact regions reach 6 cube layers (12 mm) from
// the faces that penetrate: A's x = 24 face and B's x = 23 face.
TEST(Interpenetration, PushesTwoOverlappingBoxesApartAndLeavesTheRestAlone) {
  const TetMesh a0 = test::boxTets(12, 6, 6, 2.0), b0 = shifted(a0, {23.0, 0.7, 0.9});
  TetMesh a = a0, b = b0;
  ASSERT_GT(verticesInside(a, b) + verticesInside(b, a), 0);

  const InterpenetrationReport r = removeInterpenetration(a, b);
  EXPECT_EQ(r.penetratingBefore, verticesInside(a0, b0) + verticesInside(b0, a0));
  EXPECT_EQ(r.penetratingAfter, 0);
  EXPECT_EQ(verticesInside(a, b), 0);
  EXPECT_EQ(verticesInside(b, a), 0);
  EXPECT_GE(r.rounds, 1);
  EXPECT_GT(r.maxDisplacement, 0.4);  // the 1 mm overlap is shared: each face moves about half of it
  EXPECT_LT(r.maxDisplacement, 1.5);
  EXPECT_EQ(movedBeyond(a0, a, 24.0 - 12.0, true), 0);
  EXPECT_EQ(movedBeyond(b0, b, 23.0 + 12.0, false), 0);
  EXPECT_GT(tetVolumes(a.V, a.T).minCoeff(), 0.0);
  EXPECT_GT(tetVolumes(b.V, b.T).minCoeff(), 0.0);
  EXPECT_GT(r.regionTets[0], 0);
  EXPECT_LT(r.regionTets[0], a.T.rows());
}

TEST(Interpenetration, LeavesMeshesThatDoNotTouchExactlyAsTheyWere) {
  const TetMesh a0 = test::boxTets(4, 4, 4, 2.0), b0 = shifted(a0, {8.5, 0.0, 0.0});
  TetMesh a = a0, b = b0;
  const InterpenetrationReport r = removeInterpenetration(a, b);
  EXPECT_EQ(r.penetratingBefore, 0);
  EXPECT_EQ(r.rounds, 0);
  EXPECT_EQ(a.V, a0.V);
  EXPECT_EQ(b.V, b0.V);
}

// A small box poking into the face of another: only one side penetrates, so it is pushed the whole way out.
TEST(Interpenetration, PushesAPokingBoxOutOfAFace) {
  const TetMesh a0 = test::boxTets(8, 8, 8, 2.0);  // [0, 16]^3 with vertices every 2 mm
  // B: one 1.5 mm cube 0.8 mm into A's x = 16 face, between A's vertices in y and z.
  TetMesh a = a0, b = shifted(test::boxTets(1, 1, 1, 1.5), {15.2, 8.2, 8.2});
  ASSERT_EQ(verticesInside(a, b), 0);
  ASSERT_GT(verticesInside(b, a), 0);
  const InterpenetrationReport r = removeInterpenetration(a, b);
  EXPECT_EQ(r.penetratingAfter, 0);
  EXPECT_EQ(verticesInside(a, b) + verticesInside(b, a), 0);
  EXPECT_EQ(a.V, a0.V);  // A had no vertex inside B: its region stays empty
  EXPECT_EQ(r.regionTets[0], 0);
}

// A chain of three (Wang et al.'s contact islands): the second against the first, the third against both.
TEST(Interpenetration, SeparatesAChainOfThreeMeshes) {
  const TetMesh box = test::boxTets(6, 4, 4, 2.0);  // 12 x 8 x 8 mm
  std::vector<TetMesh> meshes = {box, shifted(box, {11.0, 0.5, 0.6}), shifted(box, {5.0, 7.2, 0.3})};
  const std::vector<InterpenetrationReport> reports = removeInterpenetrations(meshes);
  ASSERT_EQ(reports.size(), 3u);
  for (const InterpenetrationReport& r : reports) {
    EXPECT_GT(r.penetratingBefore, 0);  // every pair overlaps at the start
    EXPECT_EQ(r.penetratingAfter, 0);
    EXPECT_LT(r.maxDisplacement, 3.0);  // overlaps of 0.8 to 1 mm
  }
  for (std::size_t i = 0; i < meshes.size(); ++i)
    for (std::size_t j = 0; j < meshes.size(); ++j) {
      if (i == j) continue;
      EXPECT_EQ(verticesInside(meshes[i], meshes[j]), 0) << i << " in " << j;
    }
}

}  // namespace
}  // namespace vesalius::fit
