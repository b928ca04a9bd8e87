// Posed scans and label maps (Sujar et al. 2018, §5, Fig. 11): the four-bone bar of the skinning tests carries a
// label map and a scan through the identity, a rigid motion, a whole-voxel translation and a bend.
#include "vesalius/posing/bone_weights.h"
#include "vesalius/posing/linear_blend_skinning.h"
#include "vesalius/posing/posed_volume.h"

#include "vesalius/core/error.h"

#include "posing_test_support.h"

#include <tbb/global_control.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

using namespace vesalius;

namespace {

GridGeometry grid(const Eigen::Vector3d& origin, const Eigen::Vector3d& spacing, const Eigen::Vector3i& size) {
  GridGeometry g;
  g.origin = origin;
  g.spacing = spacing;
  g.size = size;
  return g;
}

// The bar [0, 48] × [0, 8] × [0, 8] moved by `motion`, tested at a world point (closed, to rounding).
bool inBar(const Eigen::Vector3d& world, const Eigen::Isometry3d& motion = Eigen::Isometry3d::Identity()) {
  const Eigen::Vector3d x = motion.inverse() * world;
  return (x.array() >= -1e-9).all() && (x.array() <= Eigen::Array3d(48, 8, 8) + 1e-9).all();
}

// Background 0; label 1 everywhere else, a ball of label 3 (centre (20, 4, 4), radius 3) and a box of
// label 7 ([30, 40] × [2, 6] × [3, 5]) inside the bar, on voxels of 0.5 mm whose centres hit the bar's faces.
LabelMap barLabels() {
  LabelMap m;
  m.labels = Grid<Label>(grid({-3, -2.5, -2}, Eigen::Vector3d::Constant(0.5), {110, 26, 24}), 1);
  const GridGeometry& g = m.labels.geometry;
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i) {
        const Eigen::Vector3d x = g.indexToWorld(Eigen::Vector3d(i, j, k));
        if ((x - Eigen::Vector3d(20, 4, 4)).norm() <= 3) m.labels.at(i, j, k) = 3;
        if ((x.array() >= Eigen::Array3d(30, 2, 3)).all() && (x.array() <= Eigen::Array3d(40, 6, 5)).all())
          m.labels.at(i, j, k) = 7;
      }
  return m;
}

// Voxel count and world centroid of `label`.
std::pair<long, Eigen::Vector3d> countAndCentroid(const Grid<Label>& g, Label label) {
  long n = 0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int k = 0; k < g.geometry.size.z(); ++k)
    for (int j = 0; j < g.geometry.size.y(); ++j)
      for (int i = 0; i < g.geometry.size.x(); ++i)
        if (g.at(i, j, k) == label) ++n, sum += g.geometry.indexToWorld(Eigen::Vector3d(i, j, k));
  return {n, sum / double(n)};
}

MatrixX3d moved(const MatrixX3d& V, const Eigen::Isometry3d& motion) {
  return (V * motion.linear().transpose()).rowwise() + motion.translation().transpose();
}

// A linear ramp in world space on an anisotropic grid, with one voxel far below the others (the minimum).
Image rampImage() {
  Image scan(grid({-3.1, -2.3, -1.7}, {0.5, 0.75, 1.0}, {120, 18, 15}));
  for (int k = 0; k < 15; ++k)
    for (int j = 0; j < 18; ++j)
      for (int i = 0; i < 120; ++i) {
        const Eigen::Vector3d x = scan.geometry.indexToWorld(Eigen::Vector3d(i, j, k));
        scan.at(i, j, k) = float(0.5 * x.x() - 0.25 * x.y() + 0.125 * x.z());
      }
  scan.at(119, 17, 14) = -1024;
  scan.fileType = PixelType::Int16;
  return scan;
}

}  // namespace

TEST(PosedVolume, IdentityPoseReproducesTheLabelMapInsideTheMesh) {
  const test::BoneBar bar = test::fourBoneBar();
  const LabelMap labels = barLabels();
  const LabelMap posed = posing::poseLabels(bar.mesh.V, bar.mesh.T, bar.mesh.V, labels);
  const GridGeometry& g = labels.labels.geometry;
  ASSERT_EQ(posed.labels.geometry.size, g.size);
  long inside = 0, wrong = 0;
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i) {
        const bool in = inBar(g.indexToWorld(Eigen::Vector3d(i, j, k)));
        inside += in;
        wrong += posed.labels.at(i, j, k) != (in ? labels.labels.at(i, j, k) : Label(0));
      }
  EXPECT_EQ(inside, 97L * 17 * 17);  // the centres on the bar's faces count as inside
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(posed.table.entries.size(), labels.table.entries.size());
}

TEST(PosedVolume, RigidMotionMovesALabelledBallAndBoxRigidly) {
  const test::BoneBar bar = test::fourBoneBar();
  const LabelMap labels = barLabels();
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.translate(Eigen::Vector3d(5, -3, 2)).rotate(Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 1, 0.3).normalized()));
  const MatrixX3d posedV = moved(bar.mesh.V, motion);
  // The moved bar leaves the input's field of view: give an output grid around it.
  const Eigen::Vector3d lo = posedV.colwise().minCoeff().transpose().array() - 2;
  const Eigen::Vector3d extent = posedV.colwise().maxCoeff().transpose() - lo;
  posing::PosedVolumeOptions options;
  options.outputGeometry = grid(lo, Eigen::Vector3d::Constant(0.5), (extent / 0.5).cast<int>().array() + 5);
  const LabelMap posed = posing::poseLabels(bar.mesh.V, bar.mesh.T, posedV, labels, options);
  for (const Label label : {Label(3), Label(7)}) {
    const auto [restCount, restCentroid] = countAndCentroid(labels.labels, label);
    const auto [posedCount, posedCentroid] = countAndCentroid(posed.labels, label);
    const double countChange = double(posedCount - restCount) / double(restCount);
    const double centroidError = (posedCentroid - motion * restCentroid).norm();
    RecordProperty("label " + std::to_string(label) + " count change", testing::PrintToString(countChange));
    RecordProperty("label " + std::to_string(label) + " centroid error mm", testing::PrintToString(centroidError));
    EXPECT_LT(std::abs(countChange), 0.03) << "label " << label << ": " << restCount << " -> " << posedCount;
    EXPECT_LT(centroidError, 0.5) << "label " << label;  // one voxel
  }
}

TEST(PosedVolume, WholeVoxelTranslationShiftsALinearRamp) {
  const test::BoneBar bar = test::fourBoneBar();
  const Image scan = rampImage();
  const Eigen::Vector3i shift(4, -2, 3);  // voxels
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.translate(scan.geometry.spacing.cwiseProduct(shift.cast<double>()));
  const Image posed = posing::poseImage(bar.mesh.V, bar.mesh.T, moved(bar.mesh.V, motion), scan);
  EXPECT_EQ(posed.fileType, PixelType::Int16);
  long inside = 0;
  double error = 0;
  for (int k = 0; k < 15; ++k)
    for (int j = 0; j < 18; ++j)
      for (int i = 0; i < 120; ++i) {
        if (!inBar(scan.geometry.indexToWorld(Eigen::Vector3d(i, j, k)), motion)) continue;
        ++inside;
        error = std::max(error, double(std::abs(posed.at(i, j, k) - scan.at(i - shift.x(), j - shift.y(), k - shift.z()))));
      }
  RecordProperty("voxels inside", testing::PrintToString(inside));
  RecordProperty("max error", testing::PrintToString(error));
  EXPECT_EQ(inside, 96L * 10 * 8);  // centres of the moved bar: x in [2, 50], y in [-1.5, 6.5], z in [3, 11]
  EXPECT_LT(error, 1e-6);
}

TEST(PosedVolume, VoxelsOutsideThePosedMeshTakeTheBackground) {
  const test::BoneBar bar = test::fourBoneBar();
  const Image scan = rampImage();
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.translate(Eigen::Vector3d(1.3, -0.4, 0.9));
  const MatrixX3d posedV = moved(bar.mesh.V, motion);
  posing::PosedVolumeOptions given;
  given.background = -500;
  const Image byDefault = posing::poseImage(bar.mesh.V, bar.mesh.T, posedV, scan);
  const Image byOption = posing::poseImage(bar.mesh.V, bar.mesh.T, posedV, scan, given);
  LabelMap labels = barLabels();
  const LabelMap labelsByDefault = posing::poseLabels(bar.mesh.V, bar.mesh.T, posedV, labels);
  given.background = 9;
  const LabelMap labelsByOption = posing::poseLabels(bar.mesh.V, bar.mesh.T, posedV, labels, given);
  long outside = 0, wrong = 0;
  for (std::int64_t v = 0; v < scan.geometry.voxelCount(); ++v) {
    const int i = int(v % 120), j = int(v / 120 % 18), k = int(v / (120 * 18));
    if (inBar(scan.geometry.indexToWorld(Eigen::Vector3d(i, j, k)), motion)) {
      wrong += byDefault.at(i, j, k) < -3.0f || byOption.at(i, j, k) != byDefault.at(i, j, k);
      continue;
    }
    ++outside;
    wrong += byDefault.at(i, j, k) != -1024.0f || byOption.at(i, j, k) != -500.0f;
  }
  EXPECT_GT(outside, 0);
  EXPECT_EQ(wrong, 0);
  long labelOutside = 0, labelWrong = 0;
  const GridGeometry& g = labels.labels.geometry;
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i) {
        const bool in = inBar(g.indexToWorld(Eigen::Vector3d(i, j, k)), motion);
        labelOutside += !in;
        labelWrong += in ? labelsByDefault.labels.at(i, j, k) == 0 || labelsByOption.labels.at(i, j, k) == 9
                         : labelsByDefault.labels.at(i, j, k) != 0 || labelsByOption.labels.at(i, j, k) != 9;
      }
  EXPECT_GT(labelOutside, 0);
  EXPECT_EQ(labelWrong, 0);
}

// A rigid part (a bone) moves by its own map, whatever the tets around it do: the bar moves by A, the
// ball's part by B, which slides it 2 mm along the bar. Every voxel of the posed ball is the ball's label,
// also where the tets alone would have put the bar's tissue there.
TEST(PosedVolume, RigidPartsMoveByTheirOwnMapAndWinOverTheTets) {
  const test::BoneBar bar = test::fourBoneBar();
  const LabelMap labels = barLabels();
  Eigen::Isometry3d a = Eigen::Isometry3d::Identity();
  a.translate(Eigen::Vector3d(5, -3, 2)).rotate(Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 1, 0.3).normalized()));
  const Eigen::Isometry3d b = a * Eigen::Translation3d(2, 0, 0);
  const MatrixX3d posedV = moved(bar.mesh.V, a);
  const Eigen::Vector3d lo = posedV.colwise().minCoeff().transpose().array() - 2;
  const Eigen::Vector3d extent = posedV.colwise().maxCoeff().transpose() - lo;
  posing::PosedVolumeOptions options;
  options.outputGeometry = grid(lo, Eigen::Vector3d::Constant(0.5), (extent / 0.5).cast<int>().array() + 5);
  const GridGeometry& out = *options.outputGeometry;
  const Eigen::Vector3d centre(20, 4, 4);
  posing::RigidParts rigid;
  rigid.parts = Grid<Label>(out, 0);
  rigid.restFromPosed = {b.inverse()};
  for (int k = 0; k < out.size.z(); ++k)
    for (int j = 0; j < out.size.y(); ++j)
      for (int i = 0; i < out.size.x(); ++i)
        if ((b.inverse() * out.indexToWorld(Eigen::Vector3d(i, j, k)) - centre).norm() <= 3) rigid.parts.at(i, j, k) = 1;
  options.rigid = &rigid;
  const LabelMap posed = posing::poseLabels(bar.mesh.V, bar.mesh.T, posedV, labels, options);
  // Half a voxel's diagonal (0.43 mm) inside the ball, nearest-voxel sampling gives the ball's label.
  long inPart = 0, wrongInPart = 0, partOnly = 0, inTetsBall = 0, wrongInTetsBall = 0;
  for (int k = 0; k < out.size.z(); ++k)
    for (int j = 0; j < out.size.y(); ++j)
      for (int i = 0; i < out.size.x(); ++i) {
        const Eigen::Vector3d y = out.indexToWorld(Eigen::Vector3d(i, j, k));
        const double fromPart = (b.inverse() * y - centre).norm(), fromTets = (a.inverse() * y - centre).norm();
        const bool ball = posed.labels.at(i, j, k) == 3;
        if (fromPart <= 2.5) ++inPart, wrongInPart += !ball, partOnly += fromTets > 3.5;
        if (fromTets <= 2.5 && fromPart > 3.5) ++inTetsBall, wrongInTetsBall += !ball;
      }
  std::cout << inPart << " voxels deep in the moved part (" << partOnly << " where the tets hold the bar's tissue): "
            << wrongInPart << " not the ball; " << inTetsBall << " deep in the ball the tets carry, outside the part: "
            << wrongInTetsBall << " not the ball\n";
  EXPECT_GT(partOnly, 0);
  EXPECT_EQ(wrongInPart, 0);
  EXPECT_GT(inTetsBall, 0);
  EXPECT_EQ(wrongInTetsBall, 0);
  // The same on a scan: a voxel of the part takes the ramp's value at its rest point.
  const Image scan = rampImage();
  const Image posedScan = posing::poseImage(bar.mesh.V, bar.mesh.T, posedV, scan, options);
  double worst = 0;
  for (int k = 0; k < out.size.z(); ++k)
    for (int j = 0; j < out.size.y(); ++j)
      for (int i = 0; i < out.size.x(); ++i)
        if (rigid.parts.at(i, j, k)) {
          const Eigen::Vector3d x = b.inverse() * out.indexToWorld(Eigen::Vector3d(i, j, k));
          worst = std::max(worst, std::abs(posedScan.at(i, j, k) - (0.5 * x.x() - 0.25 * x.y() + 0.125 * x.z())));
        }
  std::cout << "ramp in the part: largest error " << worst << '\n';
  EXPECT_LT(worst, 1e-4);  // trilinear sampling of a linear ramp is exact; float rounding only
  // Parts on another grid, or a part without its map, are refused.
  posing::RigidParts offGrid = rigid;
  offGrid.parts = Grid<Label>(labels.labels.geometry, 0);
  options.rigid = &offGrid;
  EXPECT_THROW(posing::poseLabels(bar.mesh.V, bar.mesh.T, posedV, labels, options), BadInput);
  posing::RigidParts unmapped = rigid;
  unmapped.parts.values[0] = 2;
  options.rigid = &unmapped;
  EXPECT_THROW(posing::poseImage(bar.mesh.V, bar.mesh.T, posedV, scan, options), BadInput);
  // No maps: no parts, whatever the grid.
  const posing::RigidParts none;
  options.rigid = &none;
  const LabelMap throughTets = posing::poseLabels(bar.mesh.V, bar.mesh.T, posedV, labels, options);
  options.rigid = nullptr;
  EXPECT_TRUE(throughTets.labels.values == posing::poseLabels(bar.mesh.V, bar.mesh.T, posedV, labels, options).labels.values);
}

TEST(PosedVolume, OverlappingPosedTetsGiveTheSameResultOnAnyThreadCount) {
  // LBS bent by 100° folds the inside of the joint: posed tets overlap there, the lowest index wins.
  const test::BoneBar bar = test::fourBoneBar();
  const Eigen::MatrixXd W = posing::computeBoneWeights(bar.mesh.V, bar.mesh.T, bar.boneOfVertex);
  const MatrixX3d posedV =
      posing::linearBlendSkinning(bar.mesh.V, W, test::middleJointPose(bar, Eigen::Vector3d::UnitY(), 100));
  const LabelMap labels = barLabels();
  const LabelMap parallel = posing::poseLabels(bar.mesh.V, bar.mesh.T, posedV, labels);
  const tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);
  const LabelMap serial = posing::poseLabels(bar.mesh.V, bar.mesh.T, posedV, labels);
  EXPECT_TRUE(parallel.labels.values == serial.labels.values);
  EXPECT_GT(countAndCentroid(parallel.labels, 3).first, 0);
}

TEST(PosedVolume, RefusesMismatchedInputs) {
  const test::BoneBar bar = test::fourBoneBar();
  const LabelMap labels = barLabels();
  const Image scan = rampImage();
  const MatrixX3d fewer = bar.mesh.V.topRows(bar.mesh.V.rows() - 1);
  EXPECT_THROW(posing::poseLabels(bar.mesh.V, bar.mesh.T, fewer, labels), BadInput);
  EXPECT_THROW(posing::poseImage(bar.mesh.V, bar.mesh.T, fewer, scan), BadInput);
  MatrixX4i badT = bar.mesh.T;
  badT(0, 2) = int(bar.mesh.V.rows());
  EXPECT_THROW(posing::poseImage(bar.mesh.V, badT, bar.mesh.V, scan), BadInput);
  Image short_ = scan;
  short_.values.pop_back();
  EXPECT_THROW(posing::poseImage(bar.mesh.V, bar.mesh.T, bar.mesh.V, short_), BadInput);
  posing::PosedVolumeOptions options;
  options.background = 1.5;
  EXPECT_THROW(posing::poseLabels(bar.mesh.V, bar.mesh.T, bar.mesh.V, labels, options), BadInput);
  options.background = std::nan("");
  EXPECT_THROW(posing::poseImage(bar.mesh.V, bar.mesh.T, bar.mesh.V, scan, options), BadInput);
  options.background.reset();
  options.outputGeometry = grid({0, 0, 0}, {1, 0, 1}, {4, 4, 4});
  EXPECT_THROW(posing::poseImage(bar.mesh.V, bar.mesh.T, bar.mesh.V, scan, options), BadInput);
}
