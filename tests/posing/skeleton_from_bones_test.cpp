// Rigging from labelled bones (Sujar et al. 2018, §3.1): the sphere fit of a joint centre, the principal axis and
// the two-direction frame of a bone on synthetic shapes (exact), the bone vertices of a labelled tet
// mesh, and the skeleton of the test CT's pelvis, femurs and lumbar spine.
#include "vesalius/posing/bone_frame.h"
#include "vesalius/posing/bone_vertices.h"
#include "vesalius/posing/principal_axis.h"
#include "vesalius/posing/skeleton_from_bones.h"
#include "vesalius/posing/sphere_fit.h"

#include "vesalius/core/error.h"
#include "vesalius/io/image_io.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <random>

using namespace vesalius;

namespace {

const std::string kCt = std::string(VESALIUS_TESTDATA) + "/ct-abdomen-pelvis/";

Eigen::Matrix3d someRotation() {
  return (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()) *
          Eigen::AngleAxisd(-1.1, Eigen::Vector3d(0.3, -1, 0.2).normalized()))
      .toRotationMatrix();
}

// Points on a 50° cap of a sphere, as a femoral head shows its acetabulum.
TEST(SphereFit, RecoversASphereFromACapExactly) {
  const Eigen::Vector3d centre(12.3, -45.6, 78.9), pole = Eigen::Vector3d(1, -2, 0.5).normalized();
  const double radius = 23.4;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  MatrixX3d P(200, 3);
  for (Eigen::Index i = 0; i < P.rows();) {
    const Eigen::Vector3d d = Eigen::Vector3d(unit(random), unit(random), unit(random));
    if (d.norm() > 1 || d.normalized().dot(pole) < std::cos(50 * M_PI / 180)) continue;
    P.row(i++) = (centre + radius * d.normalized()).transpose();
  }
  const posing::SphereFit fit = posing::fitSphere(P);
  EXPECT_LT((fit.centre - centre).norm(), 1e-9);
  EXPECT_NEAR(fit.radius, radius, 1e-9);
  EXPECT_LT(fit.rmsResidual, 1e-9);
}

// On noisy points the geometric refinement must not end worse than the algebraic start (Kåsa alone).
TEST(SphereFit, GeometricStepsLowerTheResidualOfNoisyCapPoints) {
  std::mt19937 random(11);
  std::normal_distribution<double> noise(0, 0.5);
  std::uniform_real_distribution<double> angle(0, 2 * M_PI), height(std::cos(40 * M_PI / 180), 1);
  MatrixX3d P(300, 3);
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const double z = height(random), a = angle(random), s = std::sqrt(1 - z * z);
    P.row(i) = (20.0 * Eigen::Vector3d(s * std::cos(a), s * std::sin(a), z) +
                Eigen::Vector3d(noise(random), noise(random), noise(random)))
                   .transpose();
  }
  posing::SphereFitOptions algebraic;
  algebraic.maxIterations = 0;
  const posing::SphereFit kasa = posing::fitSphere(P, algebraic), full = posing::fitSphere(P);
  EXPECT_LE(full.rmsResidual, kasa.rmsResidual);
  EXPECT_LT(full.centre.norm(), 2.0);
  EXPECT_NEAR(full.radius, 20.0, 2.0);
}

TEST(SphereFit, RefusesTooFewOrCoplanarPoints) {
  EXPECT_THROW(posing::fitSphere(MatrixX3d::Random(3, 3)), BadInput);
  MatrixX3d flat = MatrixX3d::Random(20, 3);
  flat.col(2).setConstant(4.0);
  EXPECT_THROW(posing::fitSphere(flat), BadInput);
}

// A 40 × 10 × 4 box of grid points, turned and moved: its principal axis is the turned x axis.
TEST(PrincipalAxis, IsTheLongSideOfATurnedBox) {
  const Eigen::Matrix3d R = someRotation();
  MatrixX3d P(41 * 11 * 5, 3);
  Eigen::Index n = 0;
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 10; ++j)
      for (int k = 0; k <= 4; ++k) P.row(n++) = (R * Eigen::Vector3d(i, j, k) + Eigen::Vector3d(5, -7, 9)).transpose();
  const Eigen::Vector3d axis = posing::principalAxis(P, R.col(0));
  EXPECT_LT((axis - R.col(0)).norm(), 1e-9);
  EXPECT_LT((posing::principalAxis(P, -R.col(0)) + R.col(0)).norm(), 1e-9);
  MatrixX3d cube(8, 3);
  for (int c = 0; c < 8; ++c) cube.row(c) << (c & 1), (c >> 1 & 1), (c >> 2 & 1);
  EXPECT_THROW(posing::principalAxis(cube, Eigen::Vector3d::UnitX()), BadInput);
}

// Any two of a rotation's axes give the rotation back, the second one skewed towards the first or not.
TEST(BoneFrame, RebuildsARotationFromAnyTwoOfItsAxes) {
  const Eigen::Matrix3d R = someRotation();
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      if (a == b) continue;
      const Eigen::Vector3d skewed = 2.5 * R.col(b) + 0.8 * R.col(a);
      const Eigen::Matrix3d frame = posing::boneFrame(a, 3.0 * R.col(a), b, skewed);
      EXPECT_LT((frame - R).norm(), 1e-12) << a << b;
      EXPECT_NEAR(frame.determinant(), 1.0, 1e-12);
    }
  EXPECT_THROW(posing::boneFrame(2, R.col(0), 2, R.col(1)), UsageError);
  EXPECT_THROW(posing::boneFrame(2, R.col(0), 0, -2 * R.col(0)), BadInput);
  EXPECT_THROW(posing::boneFrame(2, Eigen::Vector3d::Zero(), 0, R.col(1)), BadInput);
}

// Two tets sharing a face, of bones 0 and 1: the shared vertices follow the later bone.
TEST(BoneVertices, TouchingBonesGiveTheirSharedVerticesToTheLaterBone) {
  MatrixX4i T(3, 4);
  T << 0, 1, 2, 3, 1, 2, 3, 4, 2, 3, 4, 5;
  const Eigen::VectorXi label = (Eigen::VectorXi(3) << 5, 7, 1).finished();
  const Eigen::VectorXi bone = posing::boneVerticesOfLabels(T, label, {{5}, {7, 8}}, 7);
  EXPECT_EQ(bone, (Eigen::VectorXi(7) << 0, 1, 1, 1, 1, -1, -1).finished());
  EXPECT_THROW(posing::boneVerticesOfLabels(T, label, {{5}}, 5), BadInput);
  EXPECT_THROW(posing::boneVerticesOfLabels(T, label.head(2), {{5}}, 7), BadInput);
}

// A soft-tissue tet spanning two bones (a joint space thinner than a tet): the earlier bone's vertices in it
// are freed, so the untangler can move them; a bone that would lose every vertex keeps them.
TEST(BoneVertices, ASoftTissueTetSpanningTwoBonesFreesTheEarlierBonesCorners) {
  MatrixX4i T(5, 4);
  T << 0, 1, 2, 3,  // bone 0
      1, 2, 3, 4,   // bone 0
      5, 6, 7, 8,   // bone 1
      3, 4, 5, 6,   // soft tissue between the two
      4, 6, 8, 9;   // soft tissue touching bones 0 and 1 and a free vertex
  const Eigen::VectorXi label = (Eigen::VectorXi(5) << 5, 5, 7, 1, 1).finished();
  EXPECT_EQ(posing::boneVerticesOfLabels(T, label, {{5}, {7}}, 10),
            (Eigen::VectorXi(10) << 0, 0, 0, -1, -1, 1, 1, 1, 1, -1).finished());
  // Every vertex of bone 0 in a tet that bridges it to bone 1: bone 0 keeps them all.
  MatrixX4i U(4, 4);
  U << 0, 1, 2, 3, 4, 5, 6, 7, 0, 1, 2, 4, 3, 5, 6, 8;
  const Eigen::VectorXi labelU = (Eigen::VectorXi(4) << 5, 7, 1, 1).finished();
  EXPECT_EQ(posing::boneVerticesOfLabels(U, labelU, {{5}, {7}}, 9),
            (Eigen::VectorXi(9) << 0, 0, 0, 0, 1, 1, 1, 1, -1).finished());
}

class CtBones : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    labels_ = new LabelMap(io::readLabelMap(kCt + "example_seg_total_v1_for_example_ct.nii.gz", kCt + "labels_total_v1.tsv"));
    bones_ = new posing::BoneSkeleton(posing::skeletonFromBones(*labels_));
  }
  static void TearDownTestSuite() {
    delete bones_;
    delete labels_;
  }
  static Label labelAt(const Eigen::Vector3d& p) {
    const Eigen::Vector3i i = labels_->labels.geometry.worldToIndex(p).array().round().cast<int>();
    return labels_->labels.at(i.x(), i.y(), i.z());
  }
  // Distance from p to the nearest voxel centre whose label is (inside) or is not (!inside) `id`.
  static double distanceToLabel(const Eigen::Vector3d& p, Label id, bool inside = true) {
    double best = INFINITY;
    const GridGeometry& g = labels_->labels.geometry;
    for (int k = 0; k < g.size.z(); ++k)
      for (int j = 0; j < g.size.y(); ++j)
        for (int i = 0; i < g.size.x(); ++i)
          if ((labels_->labels.at(i, j, k) == id) == inside) best = std::min(best, (g.indexToWorld(Eigen::Vector3d(i, j, k)) - p).norm());
    return best;
  }
  static LabelMap* labels_;
  static posing::BoneSkeleton* bones_;
};
LabelMap* CtBones::labels_ = nullptr;
posing::BoneSkeleton* CtBones::bones_ = nullptr;

// The hip centres lie in the femoral heads, in their acetabula, and mirror each other across the body.
TEST_F(CtBones, HipCentresSitInTheFemoralHeads) {
  const auto& b = *bones_;
  for (const auto& [side, fit, femur, hip] :
       {std::tuple{"left", b.femoralHeadLeft, "femur_left", "hip_left"},
        std::tuple{"right", b.femoralHeadRight, "femur_right", "hip_right"}}) {
    RecordProperty(std::string("head_radius_") + side, std::to_string(fit.radius));
    RecordProperty(std::string("head_rms_") + side, std::to_string(fit.rmsResidual));
    std::cout << side << ": centre " << fit.centre.transpose() << ", radius " << fit.radius << " mm, rms "
              << fit.rmsResidual << " mm, to the hip bone " << distanceToLabel(fit.centre, labels_->table.resolve(hip))
              << " mm\n";
    EXPECT_EQ(labelAt(fit.centre), labels_->table.resolve(femur)) << side;
    EXPECT_GT(fit.radius, 18.0) << side;  // adult femoral heads: 20-27 mm, less half a 3 mm voxel
    EXPECT_LT(fit.radius, 28.0) << side;
    EXPECT_LT(fit.rmsResidual, 2.0) << side;
    // The acetabulum's voxels are one head radius from the centre: 21.0 vs 22.4 mm (left), 23.6 vs 24.0 (right).
    EXPECT_NEAR(distanceToLabel(fit.centre, labels_->table.resolve(hip)), fit.radius, 2.0) << side;
  }
  const Eigen::Vector3d d = b.femoralHeadLeft.centre - b.femoralHeadRight.centre;
  std::cout << "left - right centre: " << d.transpose() << " mm\n";
  EXPECT_GT(d.x(), 140.0);  // left is +x in LPS; adult hip centres are 150-200 mm apart
  EXPECT_LT(d.x(), 220.0);
  EXPECT_LT(std::abs(d.y()), 6.0);
  EXPECT_LT(std::abs(d.z()), 6.0);
}

// Joints: pelvis, femurs, L5 to L1 chained at their discs, upward; frames right-handed, the femurs' x
// towards the left and z up, every vertebra's joint between its neighbours' centroids.
TEST_F(CtBones, SkeletonChainsTheLumbarSpineAtItsDiscs) {
  const Skeleton& s = bones_->skeleton;
  const std::vector<std::string> names{"pelvis", "femur_left", "femur_right", "vertebrae_L5", "vertebrae_L4",
                                       "vertebrae_L3", "vertebrae_L2", "vertebrae_L1"};
  ASSERT_EQ(s.joints.size(), names.size());
  for (std::size_t j = 0; j < names.size(); ++j) EXPECT_EQ(s.joints[j].name, names[j]);
  EXPECT_EQ(s.joints[3].parent, 0);
  EXPECT_EQ(s.joints[7].parent, 6);
  const std::vector<Eigen::Isometry3d> world = s.restWorld();
  for (const Eigen::Isometry3d& w : world) EXPECT_NEAR(w.linear().determinant(), 1.0, 1e-12);
  EXPECT_LT((world[1].translation() - bones_->femoralHeadLeft.centre).norm(), 1e-9);
  EXPECT_GT(world[0].linear().col(0).x(), 0.99);  // the pelvis's x: left
  for (int j : {3, 4, 5, 6, 7}) {  // the vertebrae: x left, z up
    EXPECT_GT(world[j].linear().col(0).x(), 0.95) << names[j];
    EXPECT_GT(world[j].linear().col(2).z(), 0.9) << names[j];
  }
  // The test CT cuts the femurs 5 cm below the head: their principal axis runs between neck and shaft
  // (z·S 0.33 and 0.27 measured), still proximal, and x keeps leaning left.
  for (int j : {1, 2}) {
    EXPECT_GT(world[j].linear().col(2).z(), 0.2) << names[j];
    EXPECT_GT(world[j].linear().col(0).x(), 0.4) << names[j];
  }
  const auto centroidZ = [&](const std::string& name) {
    const Label id = labels_->table.resolve(name);
    double sum = 0;
    long n = 0;
    const GridGeometry& g = labels_->labels.geometry;
    for (int k = 0; k < g.size.z(); ++k)
      for (int jj = 0; jj < g.size.y(); ++jj)
        for (int i = 0; i < g.size.x(); ++i)
          if (labels_->labels.at(i, jj, k) == id) sum += g.indexToWorld(Eigen::Vector3d(i, jj, k)).z(), ++n;
    return sum / double(n);
  };
  std::string below = "sacrum";
  for (int j = 3; j < 8; ++j) {
    const double z = world[j].translation().z();
    std::cout << names[j] << " joint " << world[j].translation().transpose() << "\n";
    EXPECT_GT(z, centroidZ(below)) << names[j];
    EXPECT_LT(z, centroidZ(names[j])) << names[j];
    below = names[j];
  }
  ASSERT_EQ(bones_->labels.size(), names.size());
  EXPECT_EQ(bones_->labels[0].size(), 3u);
}

TEST_F(CtBones, RefusesAMapWithoutAFemur) {
  LabelMap cut = *labels_;
  const Label femur = cut.table.resolve("femur_right");
  for (Label& l : cut.labels.values)
    if (l == femur) l = 0;
  EXPECT_THROW(posing::skeletonFromBones(cut, {}, "cut.nii.gz"), BadInput);
}

}  // namespace
