// The fat editor on a reference anatomy (bone_fat_amounts.h, Dicko et al. 2013, §6) on synthetic bodies: an
// elongated skin with a two-bone "pelvis" group at one end, a "skull" at the other and an organ between.
// The editor promises thickness = maxThicknessMm · Σ_j w_j · amount_j with weights that are a partition of
// unity in [0, 1]: equal amounts give that thickness everywhere, the thickness is linear in the amounts
// and lies between the smallest and largest amount's thickness, and a bone's amount rules near it.
#include "vesalius/fat/bone_fat_amounts.h"

#include "vesalius/core/error.h"
#include "test_shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <string>

namespace vesalius::fat {
namespace {

TriMesh ellipsoid(int levels, const Eigen::Vector3d& radii, const Eigen::Vector3d& centre) {
  TriMesh m = test::sphere(levels);
  m.V = (m.V * radii.asDiagonal()).rowwise() + centre.transpose();
  return m;
}

// Skin half-axes (length, 40, 40) mm along x; the pelvis's two bones near -x, the skull near +x.
ReferenceAnatomy body(double length) {
  ReferenceAnatomy r;
  r.skin = ellipsoid(4, {length, 40, 40}, Eigen::Vector3d::Zero());
  const double x = 0.6 * length;
  r.tissues.push_back({"hip_l", TissueKind::Bone, "pelvis", true, ellipsoid(2, {10, 8, 8}, {-x, 14, 0})});
  r.tissues.push_back({"liver", TissueKind::Organ, "", false, ellipsoid(2, {15, 15, 15}, {0, 0, 0})});
  r.tissues.push_back({"hip_r", TissueKind::Bone, "pelvis", true, ellipsoid(2, {10, 8, 8}, {-x, -14, 0})});
  r.tissues.push_back({"skull", TissueKind::Bone, "", true, ellipsoid(2, {12, 12, 12}, {x, 0, 0})});
  return r;
}

struct Case {
  double length, voxel;
};
const Case kCases[] = {{100, 8}, {160, 10}, {220, 12}};

BoneFatAmountsOptions options(double voxel) {
  BoneFatAmountsOptions o;
  o.voxelSizeMm = voxel;
  o.referenceSource = "ref";
  o.amountsSource = "amounts.json";
  return o;
}

TEST(BoneFatAmounts, BonesAreTheReferencesBoneGroups) {
  const std::vector<std::string> names = boneFatBoneNames(body(100));
  ASSERT_EQ(names.size(), 2u);
  EXPECT_EQ(names[0], "pelvis");
  EXPECT_EQ(names[1], "skull");
}

TEST(BoneFatAmounts, EqualAmountsGiveThatThicknessEverywhere) {
  for (const Case& c : kCases) {
    const ReferenceAnatomy r = body(c.length);
    const BoneFatAmounts named = boneFatFromAmounts(r, {{"pelvis", 0.3}, {"skull", 0.3}}, options(c.voxel));
    BoneFatAmountsOptions o = options(c.voxel);
    o.defaultAmount = 0.3;
    const BoneFatAmounts byDefault = boneFatFromAmounts(r, {}, o);
    ASSERT_EQ(named.thickness.size(), r.skin.V.rows());
    const double deviation = (named.thickness.array() - 15.0).abs().maxCoeff();
    const double defaultDeviation = (byDefault.thickness.array() - 15.0).abs().maxCoeff();
    std::cout << "length " << c.length << " mm, voxel " << c.voxel << " mm: grid " << named.grid.size.transpose()
              << ", largest deviation from 15 mm " << deviation << " (named), " << defaultDeviation
              << " (default amount)\n";
    EXPECT_LT(deviation, 1e-6);
    EXPECT_LT(defaultDeviation, 1e-6);
    ASSERT_EQ(named.bones.size(), 2u);
    EXPECT_EQ(named.bones[0].name, "pelvis");
    EXPECT_GT(named.bones[0].voxels, 0);
    EXPECT_GT(named.bones[1].voxels, 0);
    EXPECT_TRUE(named.withoutVoxels.empty());
  }
}

TEST(BoneFatAmounts, LinearBoundedAndLocal) {
  for (const Case& c : kCases) {
    const ReferenceAnatomy r = body(c.length);
    const BoneFatAmountsOptions o = options(c.voxel);
    const Eigen::VectorXd pelvis = boneFatFromAmounts(r, {{"pelvis", 0.4}}, o).thickness;
    const Eigen::VectorXd skull = boneFatFromAmounts(r, {{"skull", 0.2}}, o).thickness;
    const Eigen::VectorXd both = boneFatFromAmounts(r, {{"pelvis", 0.4}, {"skull", 0.2}}, o).thickness;
    EXPECT_LT((pelvis + skull - both).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_GE(both.minCoeff(), 10.0 - 1e-9);  // 0.2 · 50 mm
    EXPECT_LE(both.maxCoeff(), 20.0 + 1e-9);  // 0.4 · 50 mm
    // The ends of the body beyond each bone: the nearer bone's weight is the larger there.
    double nearPelvis = 0, nearSkull = 0;
    int nP = 0, nS = 0;
    for (Eigen::Index v = 0; v < r.skin.V.rows(); ++v) {
      if (r.skin.V(v, 0) < -0.8 * c.length) nearPelvis += pelvis[v], ++nP;
      if (r.skin.V(v, 0) > 0.8 * c.length) nearSkull += pelvis[v], ++nS;
    }
    ASSERT_GT(nP, 0);
    ASSERT_GT(nS, 0);
    nearPelvis /= nP, nearSkull /= nS;
    std::cout << "length " << c.length << " mm: pelvis 0.4 alone gives " << nearPelvis << " mm at the pelvis end, "
              << nearSkull << " mm at the skull end (20 mm is all the pelvis's weight)\n";
    EXPECT_GT(nearPelvis, 10.0);
    EXPECT_LT(nearSkull, 10.0);
  }
}

TEST(BoneFatAmounts, BadAmountsNameTheirSource) {
  const ReferenceAnatomy r = body(100);
  const BoneFatAmountsOptions o = options(10);
  const auto problem = [&](const std::vector<std::pair<std::string, double>>& amounts) -> std::string {
    try {
      boneFatFromAmounts(r, amounts, o);
    } catch (const BadInput& e) {
      EXPECT_EQ(e.file(), "amounts.json");
      return e.problem();
    }
    return "";
  };
  EXPECT_EQ(problem({{"femur", 0.1}}), "no bone or bone group 'femur' in the reference (its bones: pelvis, skull)");
  EXPECT_EQ(problem({{"hip_l", 0.1}}), "'hip_l' is one bone of the group 'pelvis'; give the group's amount");
  EXPECT_EQ(problem({{"liver", 0.1}}), "no bone or bone group 'liver' in the reference (its bones: pelvis, skull)");
  EXPECT_EQ(problem({{"skull", -0.1}}), "the amount of 'skull' must be a number >= 0");
  EXPECT_EQ(problem({{"skull", std::numeric_limits<double>::quiet_NaN()}}),
            "the amount of 'skull' must be a number >= 0");
  EXPECT_NE(problem({{"skull", 30}}).find("more than 1000 mm of fat"), std::string::npos);
}

TEST(BoneFatAmounts, BadOptionsAndReferences) {
  const ReferenceAnatomy r = body(100);
  BoneFatAmountsOptions o = options(0);
  EXPECT_THROW(checkBoneFatOptions(r, o), UsageError);
  EXPECT_THROW(boneFatFromAmounts(r, {}, o), UsageError);
  o = options(10);
  o.defaultAmount = 30;  // 1500 mm of fat
  EXPECT_THROW(boneFatFromAmounts(r, {}, o), UsageError);
  o = options(10);
  o.maxThicknessMm = std::numeric_limits<double>::infinity();
  EXPECT_THROW(boneFatFromAmounts(r, {}, o), UsageError);

  ReferenceAnatomy noBones = r;
  noBones.tissues = {r.tissues[1]};
  try {
    boneFatFromAmounts(noBones, {}, options(10));
    ADD_FAILURE() << "a reference without bones was taken";
  } catch (const BadInput& e) {
    EXPECT_EQ(e.file(), "ref");
  }
  ReferenceAnatomy allOutside = r;
  for (ReferenceTissue& t : allOutside.tissues) t.mesh.V.col(0).array() += 1000;
  EXPECT_THROW(boneFatFromAmounts(allOutside, {}, options(10)), BadInput);
}

TEST(BoneFatAmounts, BoneOutsideTheSkinHasNoEffect) {
  ReferenceAnatomy r = body(100);
  r.tissues.push_back({"finger", TissueKind::Bone, "", false, ellipsoid(1, {5, 5, 5}, {0, 500, 0})});
  const BoneFatAmountsOptions o = options(10);
  const BoneFatAmounts with = boneFatFromAmounts(r, {{"pelvis", 0.4}, {"finger", 1.0}}, o);
  const BoneFatAmounts without = boneFatFromAmounts(r, {{"pelvis", 0.4}}, o);
  ASSERT_EQ(with.withoutVoxels.size(), 1u);
  EXPECT_EQ(with.withoutVoxels[0], "finger");
  EXPECT_EQ(with.bones.size(), 2u);
  EXPECT_LT((with.thickness - without.thickness).cwiseAbs().maxCoeff(), 1e-12);
}

}  // namespace
}  // namespace vesalius::fat
