// RigPoser's carrying (posing/rig_poser.h) on the four-bone bar: a bone mesh (AnatomyRig::meshJoint) moves
// rigidly with its joint, every other mesh is carried by the tets, and QualityMeter measures how far a
// bone mesh lies from where the tets would have carried it. The rig folder keeps which meshes are bones
// (io/anatomy_rig_io.h, bone_meshes.txt).
#include "vesalius/io/anatomy_rig_io.h"
#include "vesalius/posing/bone_weights.h"
#include "vesalius/posing/pose_quality.h"
#include "vesalius/posing/rig_poser.h"
#include "vesalius/posing/rotation_centers.h"
#include "vesalius/posing/skeleton_pose.h"

#include "posing_test_support.h"
#include "test_shapes.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>

namespace vesalius::test {
namespace {

namespace fs = std::filesystem;

// The bar's rig: a chain of four joints on its axis at x = 0, 12, 24, 36, bone j on joint j. Its meshes:
// a sphere inside bone 2's core (x 26..34, |y - 4|, |z - 4| <= 2), a sphere astride the middle joint's
// tissue and bone 2, and a sphere of tissue above the middle joint.
struct BarRig {
  AnatomyRig rig;
  std::vector<TriMesh> meshes;
};

BarRig barRig(bool boneMeshes) {
  const BoneBar bar = fourBoneBar();
  BarRig r;
  r.rig.tets = bar.mesh;
  r.rig.tets.vertexAttributes.integer["bone"] = bar.boneOfVertex;
  r.rig.tets.vertexAttributes.real["weights"] = posing::computeBoneWeights(bar.mesh.V, bar.mesh.T, bar.boneOfVertex);
  for (int j = 0; j < 4; ++j) {
    Joint joint;
    joint.name = "bone" + std::to_string(j);
    joint.parent = j - 1;
    joint.restLocal = Eigen::Translation3d(j == 0 ? Eigen::Vector3d(0, 4, 4) : Eigen::Vector3d(12, 0, 0));
    joint.tail = Eigen::Vector3d(12, 0, 0);
    r.rig.skeleton.joints.push_back(joint);
    r.rig.boneJoint.push_back(j);
  }
  r.rig.meshes = {"inner_bone.obj", "astride.obj", "tissue.obj"};
  r.meshes = {sphere(2, 1.5, {30, 4, 4}), sphere(2, 1.8, {25.5, 4, 4}), sphere(2, 0.8, {24, 4, 7})};
  if (boneMeshes) r.rig.meshJoint = {2, 2, -1};
  return r;
}

// Posed world transforms that turn bones 2 and 3 by `degrees` about z through the middle joint.
std::vector<Eigen::Isometry3d> turned(const BarRig& r, double degrees) {
  const std::vector<Eigen::Isometry3d> skinning = middleJointPose(fourBoneBar(), Eigen::Vector3d::UnitZ(), degrees);
  std::vector<Eigen::Isometry3d> world = r.rig.skeleton.restWorld();
  for (std::size_t j = 0; j < world.size(); ++j) world[j] = skinning[j] * world[j];
  return world;
}

double largestDistance(const MatrixX3d& a, const MatrixX3d& b) { return (a - b).rowwise().norm().maxCoeff(); }

TEST(RigPoser, BoneMeshesMoveRigidlyWithTheirJointAndTheOthersWithTheTets) {
  for (const std::string method : {"lbs", "dqs", "cor"}) {
    BarRig r = barRig(true);
    r.rig.tets.vertexAttributes.real["cor_centre"] = posing::computeRotationCenters(r.rig.tets.V, r.rig.tets.T, r.rig.weights());
    const posing::RigPoser poser(r.rig, r.meshes, /*untangle=*/false, /*restoreVolume=*/false);
    const std::vector<Eigen::Isometry3d> world = turned(r, 60);
    MatrixX3d tets;
    poser.skinTets(world, method, tets);
    std::vector<MatrixX3d> carried;
    poser.carry(tets, world, carried);
    const Eigen::Isometry3d bone2 = posing::restToPosed(r.rig.skeleton, world)[2];
    for (int m : {0, 1}) {
      const MatrixX3d rigid = (r.meshes[std::size_t(m)].V * bone2.linear().transpose()).rowwise() + bone2.translation().transpose();
      EXPECT_LT(largestDistance(carried[std::size_t(m)], rigid), 1e-9) << method << " mesh " << m;
    }
    MatrixX3d byTets;
    poser.embeddings()[2].apply(tets, byTets);
    EXPECT_LT(largestDistance(carried[2], byTets), 1e-12) << method;

    // The inner sphere lies in tets of bone 2's vertices alone, which the skinning moves by bone 2's map:
    // the tets carry it where the bone goes. The sphere astride the joint reaches into tissue the skinning
    // bends, where the tets would have carried it elsewhere: that distance is the gap measured.
    const posing::QualityMeter meter(poser.rig(), poser.meshes(), poser.embeddings());
    const posing::PoseQuality q = meter(tets, carried);
    MatrixX3d innerByTets, astrideByTets;
    poser.embeddings()[0].apply(tets, innerByTets);
    poser.embeddings()[1].apply(tets, astrideByTets);
    std::cout << method << ": inner bone sphere " << largestDistance(carried[0], innerByTets)
              << " mm from the tets' carrying, the sphere astride the joint up to " << q.boneMeshGapMax
              << " mm (mean " << q.boneMeshGapMean << ")\n";
    EXPECT_LT(largestDistance(carried[0], innerByTets), 1e-9) << method;
    EXPECT_NEAR(q.boneMeshGapMax, largestDistance(carried[1], astrideByTets), 1e-12) << method;
    EXPECT_GT(q.boneMeshGapMax, 0.0) << method;
    // Only the carried meshes count as tissue inside the rest tets.
    EXPECT_EQ(meter.insideAtRest(), r.meshes[2].V.rows());
    EXPECT_EQ(q.leftOutside, 0);
  }
}

TEST(RigPoser, WithoutBoneMeshesEveryMeshIsCarriedByTheTets) {
  const BarRig r = barRig(false);
  const posing::RigPoser poser(r.rig, r.meshes, false, false);
  const std::vector<Eigen::Isometry3d> world = turned(r, 60);
  MatrixX3d tets;
  poser.skinTets(world, "lbs", tets);
  std::vector<MatrixX3d> carried;
  poser.carry(tets, world, carried);
  for (std::size_t m = 0; m < carried.size(); ++m) {
    MatrixX3d byTets;
    poser.embeddings()[m].apply(tets, byTets);
    EXPECT_LT(largestDistance(carried[m], byTets), 1e-12) << m;
  }
  const posing::QualityMeter meter(poser.rig(), poser.meshes(), poser.embeddings());
  EXPECT_EQ(meter(tets, carried).boneMeshGapMax, 0.0);
}

TEST(RigPoser, RefusesBoneMeshJointsThatDoNotMatchItsMeshes) {
  BarRig r = barRig(true);
  r.rig.meshJoint = {2, 2};
  EXPECT_THROW(posing::RigPoser(r.rig, r.meshes), UsageError);
  r.rig.meshJoint = {2, 4, -1};
  EXPECT_THROW(posing::RigPoser(r.rig, r.meshes), UsageError);
}

TEST(AnatomyRigIo, TheRigFolderKeepsWhichMeshesAreBonesAndRefusesAnUnknownJoint) {
  const BarRig r = barRig(true);
  const std::string dir = (fs::temp_directory_path() / ("vesalius_rig_poser_" + std::to_string(getpid()))).string();
  fs::remove_all(dir);
  std::vector<std::pair<std::string, TriMesh>> meshes;
  for (std::size_t m = 0; m < r.meshes.size(); ++m) meshes.emplace_back(r.rig.meshes[m], r.meshes[m]);
  io::writeAnatomyRig(dir, r.rig, meshes, {});
  const AnatomyRig read = io::readAnatomyRig(dir);
  ASSERT_EQ(read.meshes.size(), 3u);
  for (std::size_t m = 0; m < 3; ++m) {
    const std::string name = fs::path(read.meshes[m]).filename().string();
    const int expected = name == "tissue.obj" ? -1 : 2;
    EXPECT_EQ(read.jointOfMesh(m), expected) << name;
  }
  std::ofstream(dir + "/bone_meshes.txt") << "inner_bone.obj\tbone9\n";
  try {
    io::readAnatomyRig(dir);
    ADD_FAILURE() << "a bone mesh of an unknown joint was read";
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("bone_meshes.txt"), std::string::npos) << e.what();
  }
  fs::remove(dir + "/bone_meshes.txt");
  EXPECT_TRUE(io::readAnatomyRig(dir).meshJoint.empty());  // a rig without bone meshes: every mesh carried
  fs::remove_all(dir);
}

}  // namespace
}  // namespace vesalius::test
