// The rigid parts of a posed volume (rigging/rigid_bone_parts.h): two bones on two joints, the second
// moved 2 mm so that the posed bones overlap, and a third bone that lies outside the scan at rest. Each
// voxel inside one posed bone is that bone's joint's part, with the map back to its rest point; a voxel
// inside both is left to the tets; a bone with nothing of the scan to carry gives no part.
#include "vesalius/rigging/rigid_bone_parts.h"

#include "vesalius/posing/skeleton_pose.h"

#include <gtest/gtest.h>

#include <iostream>

namespace vesalius::rigging {
namespace {

// The box lo..hi as a closed mesh, its triangles counter-clockwise seen from outside.
TriMesh box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  TriMesh m;
  m.V.resize(8, 3);
  for (int c = 0; c < 8; ++c)
    m.V.row(c) << (c & 1 ? hi : lo).x(), (c & 2 ? hi : lo).y(), (c & 4 ? hi : lo).z();
  m.F.resize(12, 3);
  m.F << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5;
  return m;
}

GridGeometry grid(const Eigen::Vector3d& origin, const Eigen::Vector3i& size) {
  GridGeometry g;
  g.origin = origin;
  g.size = size;
  return g;
}

TEST(RigidBoneParts, EachPosedBoneIsItsJointsPartAndContestedVoxelsAreLeftToTheTets) {
  AnatomyRig rig;
  rig.skeleton.joints = {{"a", -1, Eigen::Isometry3d::Identity(), {}}, {"b", 0, Eigen::Isometry3d(Eigen::Translation3d(10, 0, 0)), {}}};
  rig.meshes = {"skin.obj", "bone_a.obj", "bone_b.obj", "beyond_the_scan.obj"};
  rig.meshJoint = {-1, 0, 1, 1};
  // Voxel centres sit on whole millimetres, the faces between them.
  const std::vector<TriMesh> rest{box({-30.5, -15.5, -9.5}, {50.5, 15.5, 9.5}), box({-5.5, -5.5, -5.5}, {5.5, 5.5, 5.5}),
                                  box({3.5, -5.5, -5.5}, {13.5, 5.5, 5.5}), box({30.5, -5.5, -5.5}, {40.5, 5.5, 5.5})};
  std::vector<Eigen::Isometry3d> world = rig.skeleton.restWorld();
  world[1] = Eigen::Translation3d(0, 2, 0) * world[1];
  const std::vector<Eigen::Isometry3d> moved = posing::restToPosed(rig.skeleton, world);
  std::vector<MatrixX3d> posed;
  for (std::size_t m = 0; m < rest.size(); ++m) {
    const Eigen::Isometry3d map = rig.meshJoint[m] < 0 ? Eigen::Isometry3d::Identity() : moved[std::size_t(rig.meshJoint[m])];
    posed.push_back((rest[m].V * map.linear().transpose()).rowwise() + map.translation().transpose());
  }
  const GridGeometry scan = grid({-20, -15, -9}, {41, 31, 19}), out = grid({-20, -15, -9}, {71, 31, 19});
  const posing::RigidParts rigid = rigidBoneParts(rig, rest, posed, world, scan, out);
  ASSERT_EQ(rigid.restFromPosed.size(), 2u);
  const auto part = [&](int x, int y, int z) {
    const Eigen::Vector3d i = out.worldToIndex(Eigen::Vector3d(x, y, z));
    return rigid.parts.at(int(i.x()), int(i.y()), int(i.z()));
  };
  long a = 0, b = 0, none = 0;
  for (Label p : rigid.parts.values) (p == 1 ? a : p == 2 ? b : none)++;
  std::cout << "voxels of joint a " << a << ", of joint b " << b << ", of none " << none << '\n';
  // Bone a: 11³ voxels less the 2 × 9 × 11 it shares with the posed bone b (x 4..5, y -3..5).
  EXPECT_EQ(a, 11L * 11 * 11 - 2 * 9 * 11);
  EXPECT_EQ(b, 10L * 11 * 11 - 2 * 9 * 11);
  EXPECT_EQ(part(0, 0, 0), 1);
  EXPECT_EQ(part(10, 7, 0), 2);
  EXPECT_EQ(part(4, 0, 0), 0);   // inside both posed bones
  EXPECT_EQ(part(35, 0, 0), 0);  // inside a bone that was beyond the scan at rest
  EXPECT_EQ(part(0, 0, 8), 0);   // tissue
  EXPECT_LT((rigid.restFromPosed[1] * Eigen::Vector3d(10, 7, 0) - Eigen::Vector3d(10, 5, 0)).norm(), 1e-12);
  EXPECT_LT((rigid.restFromPosed[0] * Eigen::Vector3d(1, 2, 3) - Eigen::Vector3d(1, 2, 3)).norm(), 1e-12);
  EXPECT_THROW(rigidBoneParts(rig, {rest[0]}, posed, world, scan, out), BadInput);
}

}  // namespace
}  // namespace vesalius::rigging
