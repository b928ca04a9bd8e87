// Decimating a fine template surface before TetGen: the Visible Human gluteus medius (30,072 triangles).
#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/self_intersections.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/meshing/decimate_surface.h"
#include "vesalius/meshing/tetrahedralize.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace vesalius::meshing {
namespace {

const std::string kMuscle = std::string(VESALIUS_TESTDATA) + "/muscles/VHF_Left_Muscle_GluteusMedius_smooth.stl";

TEST(DecimateSurface, MuscleKeepsItsVolumeAndStaysClosed) {
  const TriMesh fine = io::readTriMesh(kMuscle);
  ASSERT_EQ(fine.F.rows(), 30072);
  const TriMesh coarse = decimateSurface(fine, 1500);
  EXPECT_NEAR(double(coarse.F.rows()), 1500.0, 150.0);
  const EdgeCounts edges = countEdges(coarse.F);
  EXPECT_EQ(edges.boundary, 0);
  EXPECT_EQ(edges.nonManifold, 0);
  EXPECT_TRUE(selfIntersections(coarse.V, coarse.F).empty());
  const double ratio = enclosedVolume(coarse.V, coarse.F) / enclosedVolume(fine.V, fine.F);
  RecordProperty("volume_ratio", std::to_string(ratio));
  EXPECT_NEAR(ratio, 1.0, 0.01);

  // What the decimation is for: TetGen follows the tet target instead of the surface's triangle count.
  TetrahedralizeOptions options;
  options.targetTets = 8000;
  const TetMesh tets = tetrahedralize(coarse, options, kMuscle);
  RecordProperty("tets", std::to_string(tets.T.rows()));
  EXPECT_LT(tets.T.rows(), 35000);  // 147k without decimation
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
