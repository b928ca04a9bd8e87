// Anatomy transfer on a synthetic body (Dicko et al. 2013, §7–8): the rules R1, R2, R5–R7 as numbers.
#include "vesalius/transfer/anatomy_transfer.h"

#include "vesalius/core/error.h"
#include "vesalius/meshing/mesh_volume.h"
#include "vesalius/transfer/anatomy_checks.h"
#include "test_shapes.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <iostream>

using namespace vesalius;
using namespace vesalius::transfer;

namespace {

TriMesh ellipsoid(int levels, const Eigen::Vector3d& radii, const Eigen::Vector3d& centre) {
  TriMesh m = test::sphere(levels);
  m.V = (m.V * radii.asDiagonal()).rowwise() + centre.transpose();
  return m;
}

// A torso-like body (L-R 160, P-A 100, S-I 300 mm half-axes 80, 50, 150): a spine on the sagittal
// plane, two long bones left and right, an organ.
ReferenceAnatomy syntheticBody() {
  ReferenceAnatomy body;
  body.name = "synthetic";
  body.skin = ellipsoid(5, {80, 50, 150}, {0, 0, 0});
  body.sagittal = {Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX()};
  body.tissues.push_back({"spine", TissueKind::Bone, "trunk", true, ellipsoid(3, {8, 8, 100}, {0, 25, 0})});
  body.tissues.push_back({"femur_left", TissueKind::Bone, "", false, ellipsoid(3, {7, 7, 60}, {40, 0, -60})});
  body.tissues.push_back({"femur_right", TissueKind::Bone, "", false, ellipsoid(3, {7, 7, 60}, {-40, 0, -60})});
  body.tissues.push_back({"liver", TissueKind::Organ, "", false, ellipsoid(3, {30, 20, 25}, {-20, -10, 60})});
  body.points.push_back({"insertion", "femur_left", Eigen::Vector3d(47, 0, -60)});
  body.points.push_back({"organ centre", "liver", Eigen::Vector3d(-20, -10, 60)});
  return body;
}

Grid<std::uint8_t> insideOf(const ReferenceAnatomy& body, double voxel) {
  meshing::CoveringGridOptions grid;
  grid.voxelSizeMm = voxel;
  grid.marginMm = 3 * voxel;
  return meshing::meshInsideMask(body.skin, meshing::coveringGrid({&body.skin}, grid));
}

// A smooth, non-affine target: wider hips, a belly pushed forward, the whole body 6 % taller.
MatrixX3d bulgingTarget(const MatrixX3d& V) {
  MatrixX3d T = V;
  for (Eigen::Index r = 0; r < V.rows(); ++r) {
    const double z = V(r, 2) / 150;
    T(r, 0) *= 1.0 + 0.15 * std::max(0.0, -z);
    if (V(r, 1) < 0) T(r, 1) -= 15 * (1 - z * z) * (-V(r, 1) / 50);
    T(r, 2) *= 1.06;
  }
  return T;
}

// A back dented over the spine's middle: the posterior skin pushed 28 mm forward at the sagittal plane
// and S-I 0, fading over 30 mm sideways and 40 mm up and down, as a thin back over a spine.
MatrixX3d dentedBack(const MatrixX3d& V) {
  MatrixX3d T = V;
  for (Eigen::Index r = 0; r < V.rows(); ++r)
    if (V(r, 1) > 0)
      T(r, 1) -= 28 * std::exp(-std::pow(V(r, 0) / 30, 2) - std::pow(V(r, 2) / 40, 2)) * (V(r, 1) / 50);
  return T;
}

// The target skin's signed distance (mm, negative inside) on a 2 mm grid, exact within 6 mm of it.
Grid<float> skinDistance(const TriMesh& skin) {
  meshing::CoveringGridOptions grid;
  grid.voxelSizeMm = 2;
  meshing::SignedDistanceOptions band;
  band.bandMm = 6;
  return meshing::meshSignedDistance(skin, meshing::coveringGrid({&skin}, grid), band);
}

}  // namespace

TEST(AnatomyTransfer, TheSameSkinGivesTheSameAnatomy) {
  const ReferenceAnatomy body = syntheticBody();
  const TransferredAnatomy result = transferAnatomy(body, body.skin.V, insideOf(body, 4));
  for (std::size_t t = 0; t < body.tissues.size(); ++t)
    EXPECT_LT((result.tissues[t] - body.tissues[t].mesh.V).cwiseAbs().maxCoeff(), 1e-3) << body.tissues[t].name;
  EXPECT_LT((result.sagittal.normal - Eigen::Vector3d::UnitX()).norm(), 1e-6);
}

TEST(AnatomyTransfer, BonesStayStraightAndTheTrunkSymmetric) {
  const ReferenceAnatomy body = syntheticBody();
  const TransferredAnatomy result = transferAnatomy(body, bulgingTarget(body.skin.V), insideOf(body, 4));
  const MatrixX3i& spineF = body.tissues[0].mesh.F;
  // R2: the spine is mirror-symmetric about the target's plane as it was about the reference's.
  EXPECT_LT(mirrorAsymmetry(result.tissues[0], spineF, result.sagittal), 0.05);
  // R1: long bones stay straight; the skin field alone bends them (the hips widen along them).
  for (int t : {1, 2}) {
    const MatrixX3d& rest = body.tissues[t].mesh.V;
    EXPECT_LT(centreLineDeviation(rest, rest), 1e-9);
    EXPECT_LT(centreLineDeviation(rest, result.tissues[t]), 1e-9);
    EXPECT_GT(centreLineDeviation(rest, result.interpolated[t]), 0.002);
  }
  // R7: the insertion on the femur moves with it exactly.
  const AffineMap& femur = result.boneGroups[1].map;
  EXPECT_LT((result.points.row(0).transpose() - femur.apply(body.points[0].position)).norm(), 1e-9);
  // The field folds nowhere.
  EXPECT_GT(jacobianDeterminant(result.finalField).minimum, 0.3);
  // R5/R6: every tissue vertex lies inside the target skin (an ellipsoid-like shape: checked against the
  // target's inside mask, sampled at each vertex).
  ReferenceAnatomy target = body;
  target.skin.V = bulgingTarget(body.skin.V);
  meshing::CoveringGridOptions grid;
  grid.voxelSizeMm = 2;
  const Grid<std::uint8_t> inside = meshing::meshInsideMask(target.skin, meshing::coveringGrid({&target.skin}, grid));
  for (std::size_t t = 0; t < body.tissues.size(); ++t)
    for (Eigen::Index r = 0; r < result.tissues[t].rows(); ++r) {
      const Eigen::Vector3d index = inside.geometry.worldToIndex(result.tissues[t].row(r).transpose()).array().round();
      ASSERT_TRUE(inside.at(int(index.x()), int(index.y()), int(index.z()))) << body.tissues[t].name << " vertex " << r;
    }
}

// R1 applies to long bones: a shaft 8.6 times as long as it is wide is one, turned any way; a patella-like
// lump is not, nor a bone at the 3x threshold's short side (2.9).
TEST(AnatomyChecks, LongBonesHaveAShaft) {
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const MatrixX3d femur = ellipsoid(3, {7, 7, 60}, {40, 0, -60}).V * turn.transpose();
  EXPECT_TRUE(isLongBone(femur));
  EXPECT_FALSE(isLongBone(ellipsoid(3, {25, 24, 12}, {0, 0, 0}).V));
  EXPECT_FALSE(isLongBone(ellipsoid(3, {5, 4, 14.5}, {0, 0, 0}).V));
  EXPECT_TRUE(isLongBone(ellipsoid(3, {5, 4, 15.5}, {0, 0, 0}).V));
}

TEST(AnatomyTransfer, TheSpineStaysInsideADentedBack) {
  // One affine map cannot follow a dent over the middle of the spine: fitted to the interpolated spine
  // alone, its middle ends outside the target's back (measured 4.3 mm); the springs of the vertices it puts
  // outside, made stiffer, keep every vertex inside (rule R6; −2.0 mm, the margin) and the map symmetric
  // (R2), for a map 4.95 mm (RMS) from the interpolated spine instead of 3.77.
  const ReferenceAnatomy body = syntheticBody();
  TriMesh target = body.skin;
  target.V = dentedBack(body.skin.V);
  const Grid<float> distance = skinDistance(target);
  const Grid<std::uint8_t> inside = insideOf(body, 4);
  AnatomyTransferOptions options;
  options.finalUnfoldPasses = 0;  // the fields as the maps leave them (unfolded below)
  const TransferredAnatomy plain = transferAnatomy(body, target.V, inside, options);
  options.targetSkinDistance = &distance;
  const TransferredAnatomy kept = transferAnatomy(body, target.V, inside, options);
  const double plainWorst = sampleSignedDistance(distance, plain.tissues[0], 6).maxCoeff();
  const double keptWorst = sampleSignedDistance(distance, kept.tissues[0], 6).maxCoeff();
  std::cout << "spine's outermost vertex: " << plainWorst << " mm plain, " << keptWorst << " mm kept inside; RMS to "
            << "the interpolated spine " << plain.boneGroups[0].rmsToAttractorMm << " -> "
            << kept.boneGroups[0].rmsToAttractorMm << " mm\n";
  EXPECT_GT(plainWorst, 1.0);
  EXPECT_LT(keptWorst, 0.0);
  EXPECT_LT(mirrorAsymmetry(kept.tissues[0], body.tissues[0].mesh.F, kept.sagittal), 0.05);
  // The plain map folds the field between the spine's middle and the dent (interior minimum −0.34); the
  // kept one far less (−0.03 on this 4 mm grid).
  const double plainFold = jacobianDeterminant(plain.finalField).interiorMinimum;
  const double keptFold = jacobianDeterminant(kept.finalField).interiorMinimum;
  std::cout << "interior Jacobian minimum " << plainFold << " plain, " << keptFold << " kept inside\n";
  EXPECT_GT(keptFold, plainFold + 0.2);
  // With the fixed cells at folds freed (the default), even the plain map's field folds nowhere.
  const TransferredAnatomy unfolded = transferAnatomy(body, target.V, inside);
  const JacobianSummary jacobian = jacobianDeterminant(unfolded.finalField);
  std::cout << "plain, unfolded: minimum " << jacobian.minimum << ", " << unfolded.finalField.releasedCells
            << " fixed cells freed in " << unfolded.finalField.unfoldPasses << " passes\n";
  EXPECT_EQ(jacobian.nonPositiveCells, 0);
  EXPECT_GT(unfolded.finalField.releasedCells, 0);
}

TEST(AnatomyTransfer, CutSkinFixesNothing) {
  // The top of the body is cut (as a scan's field of view cuts it): wherever the registration slid those
  // vertices, the anatomy does not follow; marked as skin, they drag the organ below them along.
  ReferenceAnatomy body = syntheticBody();
  MatrixX3d target = body.skin.V;
  for (Eigen::Index v = 0; v < target.rows(); ++v)
    if (body.skin.V(v, 2) > 120) body.skinCutVertices.push_back(int(v)), target(v, 0) += 10;
  const Grid<std::uint8_t> inside = insideOf(body, 4);
  const double cutMoved = (transferAnatomy(body, target, inside).tissues[3] - body.tissues[3].mesh.V).cwiseAbs().maxCoeff();
  body.skinCutVertices.clear();
  const double skinMoved = (transferAnatomy(body, target, inside).tissues[3] - body.tissues[3].mesh.V).cwiseAbs().maxCoeff();
  EXPECT_LT(cutMoved, 1e-3);
  EXPECT_GT(skinMoved, 0.1);
}

TEST(AnatomyTransfer, WrongSkinSizeIsRefused) {
  const ReferenceAnatomy body = syntheticBody();
  EXPECT_THROW(transferAnatomy(body, body.skin.V.topRows(10), insideOf(body, 6)), BadInput);
}
