// Decimation by edge collapses that keep a closed surface closed, over surfaces of different size, shape and
// topology: a fine muscle, a torus, bodies' voxel surfaces at a coarse voxel, pieces of very different size.
#include "makehuman_bodies.h"
#include "test_shapes.h"
#include "vesalius/core/error.h"
#include "vesalius/core/label_map.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/self_intersections.h"
#include "vesalius/io/body_axes.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/meshing/decimate_surface.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/meshing/mesh_volume.h"
#include "vesalius/meshing/winding_mask.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

namespace vesalius::meshing {
namespace {

const std::string kMuscle = std::string(VESALIUS_TESTDATA) + "/muscles/VHF_Left_Muscle_GluteusMedius_smooth.stl";

// The pieces a decimation to `target` keeps (decimate_surface.h): those whose share of the target, by area,
// is at least a tetrahedron's four triangles, and the largest. Returns their count and summed V - E + F
// (2 per sphere-like piece, 0 per torus).
std::pair<int, long> keptPieces(const TriMesh& m, int target) {
  const Eigen::VectorXi piece = triangleComponentIds(m.V.rows(), m.F);
  const Eigen::VectorXd area = triangleAreas(m.V, m.F);
  const int pieces = piece.maxCoeff() + 1;
  std::vector<double> pieceArea(std::size_t(pieces), 0.0);
  std::vector<long> faces(std::size_t(pieces), 0);
  std::vector<std::set<int>> vertices{std::size_t(pieces)};
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    pieceArea[std::size_t(piece[f])] += area[f];
    ++faces[std::size_t(piece[f])];
    for (int k = 0; k < 3; ++k) vertices[std::size_t(piece[f])].insert(m.F(f, k));
  }
  const auto largest = std::max_element(pieceArea.begin(), pieceArea.end()) - pieceArea.begin();
  int kept = 0;
  long euler = 0;
  for (int p = 0; p < pieces; ++p)
    if (p == largest || pieceArea[std::size_t(p)] >= 4.0 * area.sum() / target) {
      ++kept;
      euler += long(vertices[std::size_t(p)].size()) - faces[std::size_t(p)] / 2;
    }
  return {kept, euler};
}

// The promise for a closed 2-manifold input: still closed and 2-manifold, free of crossings, the pieces above
// the decimation's resolution kept with their handles, the target reached (each collapse takes two
// triangles) wherever their handles allow it, and the enclosed volume kept by each collapse's placement.
void expectDecimatedClosed(const TriMesh& fine, const TriMesh& coarse, int target, const std::string& what) {
  SCOPED_TRACE(what + " to " + std::to_string(target));
  const EdgeCounts edges = countEdges(coarse.F);
  EXPECT_EQ(edges.boundary, 0);
  EXPECT_EQ(edges.nonManifold, 0);
  EXPECT_TRUE(selfIntersections(coarse.V, coarse.F).empty());
  const auto [pieces, euler] = keptPieces(fine, target);
  EXPECT_EQ(triangleComponents(coarse.V.rows(), coarse.F), pieces);
  EXPECT_EQ(long(coarse.V.rows()) - long(coarse.F.rows()) / 2, euler);
  EXPECT_LE(coarse.F.rows(), target);
  EXPECT_GE(coarse.F.rows(), target - 1);
  const double ratio = enclosedVolume(coarse.V, coarse.F) / enclosedVolume(fine.V, fine.F);
  std::printf("%s: %ld -> %ld triangles (target %d) in %d pieces, volume ratio %.5f\n", what.c_str(),
              long(fine.F.rows()), long(coarse.F.rows()), target, pieces, ratio);
  // Pieces left out take their volume with them: within the tolerance only when they are small.
  EXPECT_NEAR(ratio, 1.0, 0.005);
}

// A torus of radii R and r, n by m quads split in two; outward.
TriMesh torus(double R, double r, int n, int m) {
  TriMesh t;
  t.V.resize(n * m, 3);
  t.F.resize(2 * n * m, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
      t.V.row(i * m + j) << (R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v);
      const int a = i * m + j, b = ((i + 1) % n) * m + j, c = ((i + 1) % n) * m + (j + 1) % m, d = i * m + (j + 1) % m;
      t.F.row(2 * (i * m + j)) << a, b, c;
      t.F.row(2 * (i * m + j) + 1) << a, c, d;
    }
  return t;
}

TEST(DecimateSurface, MuscleKeepsItsVolumeAndStaysClosed) {
  const TriMesh fine = io::readTriMesh(kMuscle);
  ASSERT_EQ(fine.F.rows(), 30072);
  for (int target : {5000, 1500, 500}) {
    expectDecimatedClosed(fine, decimateSurface(fine, target), target, "gluteus medius");
  }
}

TEST(DecimateSurface, TorusKeepsItsHole) {
  const TriMesh fine = torus(30.0, 8.0, 120, 40);
  for (int target : {2000, 400, 60}) expectDecimatedClosed(fine, decimateSurface(fine, target), target, "torus");
}

// The voxel surface of a body at 8 mm (arms meeting the trunk make a handle): the fewer triangles asked, the
// fewer kept, down to a few hundred.
TEST(DecimateSurface, BodiesAtACoarseVoxelReachEveryTarget) {
  for (const char* name : {"male_young_thin", "female_young_heavy"}) {
    const auto body = std::find_if(test::kBodies.begin(), test::kBodies.end(),
                                   [&](const test::Body& b) { return std::string(b.name) == name; });
    ASSERT_NE(body, test::kBodies.end());
    TriMesh skin = test::bodySkin(*body);
    skin.V = io::transformPoints(skin.V, io::yUpToLps(), 100.0);  // decimetres to mm
    CoveringGridOptions grid;
    grid.voxelSizeMm = 8.0;
    LabelMap solid;
    const Grid<std::uint8_t> mask = windingNumberMask(skin, coveringGrid({&skin}, grid));
    solid.labels = Grid<Label>(mask.geometry, 0);
    std::copy(mask.values.begin(), mask.values.end(), solid.labels.values.begin());
    const TriMesh fine = labelSurface(solid, 1);
    ASSERT_EQ(countEdges(fine.F).boundary, 0);
    ASSERT_EQ(countEdges(fine.F).nonManifold, 0);
    ASSERT_TRUE(selfIntersections(fine.V, fine.F).empty());
    long previous = fine.F.rows();
    for (int target : {8200, 4100, 2050, 820}) {
      const TriMesh coarse = decimateSurface(fine, target);
      expectDecimatedClosed(fine, coarse, target, name);
      EXPECT_LT(coarse.F.rows(), previous);
      previous = coarse.F.rows();
    }
  }
}

// A fine sphere, a coarse one and a small tetrahedron: each piece keeps at least a tetrahedron's four
// triangles, so a piece whose share of the target is under four goes, and a target below what the rest can
// reach stops there.
TEST(DecimateSurface, PiecesOfEverySizeStayClosedOrGo) {
  const TriMesh a = test::sphere(5, 20.0), b = test::sphere(2, 5.0, Eigen::Vector3d(40, 0, 0)),
                c = test::tetrahedron(3.0);
  TriMesh pieces;
  pieces.V.resize(a.V.rows() + b.V.rows() + c.V.rows(), 3);
  pieces.V << a.V, b.V, c.V;
  pieces.F.resize(a.F.rows() + b.F.rows() + c.F.rows(), 3);
  pieces.F << a.F, (b.F.array() + int(a.V.rows())).matrix(), (c.F.array() + int(a.V.rows() + b.V.rows())).matrix();
  EXPECT_EQ(keptPieces(pieces, 2000).first, 3);
  EXPECT_EQ(keptPieces(pieces, 200).first, 2);  // the tetrahedron's share is under four triangles
  for (int target : {2000, 200}) expectDecimatedClosed(pieces, decimateSurface(pieces, target), target, "pieces");
  const TriMesh fewest = decimateSurface(pieces, 6);
  EXPECT_EQ(triangleComponents(fewest.V.rows(), fewest.F), 1);  // the large sphere alone
  EXPECT_LE(fewest.F.rows(), 6);
  EXPECT_EQ(countEdges(fewest.F).nonManifold, 0);
}

// Two surfaces decimated apart: a sphere in a sphere a few percent larger, each to a few dozen triangles,
// which one by one cross each other.
TEST(DecimateSurface, NestedSurfacesDecimatedApartDoNotCross) {
  const TriMesh inner = test::sphere(4, 10.0), outer = test::sphere(4, 10.8);
  const auto crossing = [](const TriMesh& x, const TriMesh& y) {
    return !selfIntersections(concatenate(x, y).V, concatenate(x, y).F).empty();
  };
  ASSERT_TRUE(crossing(decimateSurface(inner, 40), decimateSurface(outer, 40)));
  const std::vector<TriMesh> apart = decimateSurfacesApart({&inner, &outer}, {40, 40});
  ASSERT_EQ(apart.size(), 2u);
  EXPECT_FALSE(crossing(apart[0], apart[1]));
  for (const TriMesh& m : apart) {
    std::printf("nested sphere: %ld triangles\n", long(m.F.rows()));
    EXPECT_LE(m.F.rows(), 80);  // within twice the target where keeping apart costs collapses
    EXPECT_EQ(countEdges(m.F).boundary, 0);
  }
  EXPECT_THROW(decimateSurfacesApart({&inner}, {40, 40}), UsageError);
}

// A small sphere a hair inside one side of a box a thousand times larger, both turned obliquely, the box an
// obstacle (target 0): the box's triangles each span far more of the collapses' search cells than a
// decimated triangle, and must still be found. The side lies halfway between the sphere and the farthest
// point of the sphere decimated alone, which would cross it; decimated apart, it does not.
TEST(DecimateSurface, AHugeObstacleTriangleIsStillAvoided) {
  const Eigen::Matrix3d turn = (Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()) *
                                Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitY())).toRotationMatrix();
  TriMesh ball = test::sphere(4, 10.0);
  ball.V = ball.V * turn.transpose();
  const int target = 1000;
  const Eigen::Vector3d side = turn.col(0);  // the box's side faces this way
  const double alone = (decimateSurface(ball, target).V * side).maxCoeff(), before = (ball.V * side).maxCoeff();
  ASSERT_GT(alone, before);
  TriMesh box;
  box.V.resize(8, 3);
  for (int i = 0; i < 8; ++i)
    box.V.row(i) << (i & 1 ? 0.5 * (alone + before) : -20000.0), (i & 2 ? 10000.0 : -10000.0),
        (i & 4 ? 10000.0 : -10000.0);
  box.V = box.V * turn.transpose();
  box.F.resize(12, 3);
  box.F << 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4, 2, 6, 7, 2, 7, 3, 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6;
  ASSERT_GT(enclosedVolume(box.V, box.F), 0.0);
  const auto crossing = [](const TriMesh& x, const TriMesh& y) {
    return !selfIntersections(concatenate(x, y).V, concatenate(x, y).F).empty();
  };
  ASSERT_FALSE(crossing(ball, box));
  ASSERT_TRUE(crossing(decimateSurface(ball, target), box));
  const std::vector<TriMesh> apart = decimateSurfacesApart({&ball, &box}, {target, 0});
  EXPECT_FALSE(crossing(apart[0], apart[1]));
  EXPECT_EQ(apart[1].F, box.F);
  EXPECT_EQ(apart[1].V, box.V);
  std::printf("the side %.2e mm beyond the sphere\n", 0.5 * (alone - before));
  expectDecimatedClosed(ball, apart[0], target, "ball beside a huge box");
}

TEST(DecimateSurface, NonFiniteVerticesAreRefused) {
  TriMesh ball = test::sphere(3, 10.0);
  ball.V(5, 1) = std::nan("");
  EXPECT_THROW(decimateSurface(ball, 100), BadInput);
}

// Open and non-manifold edges keep their vertices: the rest of the surface is decimated around them.
TEST(DecimateSurface, OpenEdgesStay) {
  TriMesh open = test::sphere(4, 10.0);
  open.F.conservativeResize(open.F.rows() - 1, 3);
  const TriMesh coarse = decimateSurface(open, 200);
  EXPECT_EQ(countEdges(coarse.F).boundary, 3);
  EXPECT_EQ(countEdges(coarse.F).nonManifold, 0);
  EXPECT_LE(coarse.F.rows(), 200);
}

TEST(DecimateSurface, FewerFacesThanTheTargetIsTheSameMesh) {
  const TriMesh fine = io::readTriMesh(kMuscle);
  const TriMesh same = decimateSurface(fine, 40000);
  EXPECT_EQ(same.F, fine.F);
  EXPECT_EQ(same.V, fine.V);
  EXPECT_EQ(decimateSurface(fine, 0).F.rows(), fine.F.rows());
}

}  // namespace
}  // namespace vesalius::meshing
