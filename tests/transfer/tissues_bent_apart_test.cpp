// Tissues bent out of the tissues they reach into (tissues_bent_apart.h), inside a sphere of radius 100 mm
// as the skin: a bone poking into an organ, and a coarse bone across the thin rim of an organ (the organ's
// vertices inside the bone, none of the bone's corners inside the organ).
#include "vesalius/transfer/tissues_bent_apart.h"

#include "vesalius/core/error.h"

#include "deepest_inside.h"
#include "test_shapes.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace vesalius::transfer {
namespace {

using test::deepestEitherWay;

constexpr double kSkinRadius = 100.0;

SkinDistances sphereSkin(const MatrixX3d& P) {
  return {P.rowwise().norm().array() - kSkinRadius, P.rowwise().normalized()};
}

ReferenceAnatomy anatomyOf(const std::vector<std::pair<std::string, TriMesh>>& tissues) {
  ReferenceAnatomy a;
  a.skin = test::sphere(3, kSkinRadius);
  for (const auto& [name, mesh] : tissues) a.tissues.push_back({name, TissueKind::Bone, "", false, mesh});
  return a;
}

TEST(TissuesBentApart, ABonePokingIntoAnOrganIsBentOutAndTheOrganStays) {
  const TriMesh organ = test::sphere(4, 30.0), bone = test::sphere(3, 8.0, {0, 0, 35}),
                far = test::sphere(2, 5.0, {0, 0, -85});
  ReferenceAnatomy anatomy = anatomyOf({{"organ", organ}, {"bone", bone}, {"far", far}});
  anatomy.points.push_back({"on the bone", "bone", Eigen::Vector3d(0, 0, 35)});
  const double before = deepestEitherWay(organ, bone);
  const TissuesBentApart bend = bendTissuesApart(anatomy, {BendRole::Fixed, BendRole::Bent, BendRole::Bent}, sphereSkin, {});
  const TriMesh& moved = anatomy.tissues[1].mesh;
  const double after = deepestEitherWay(anatomy.tissues[0].mesh, moved);
  std::printf("bone 3 mm into the organ: deepest %.2f mm before, %.2f after; %ld points inside before, %ld after, "
              "largest move %.2f mm\n", before, after, bend.insideBefore, bend.insideAfter, bend.largestMoveMm);
  EXPECT_GT(before, 2.0);
  EXPECT_GT(bend.insideBefore, 0);
  EXPECT_EQ(bend.insideAfter, 0);
  EXPECT_EQ(after, 0.0);
  EXPECT_EQ(anatomy.tissues[0].mesh.V, organ.V);  // fixed
  EXPECT_EQ(anatomy.tissues[2].mesh.V, far.V);    // beyond the bend's reach
  // The bone is moved up and off, not crushed: its far side moves less than its near side, and its point
  // moves with it.
  EXPECT_GT(moved.V.col(2).minCoeff(), 30.0);
  EXPECT_GT(anatomy.points[0].position.z(), 35.0);
  EXPECT_LT((moved.V - bone.V).rowwise().norm().maxCoeff(), bend.largestMoveMm + 1e-9);
}

TEST(TissuesBentApart, ACoarseBoneAcrossAThinRimIsMovedOffIt) {
  // An organ 60 mm across and 4 mm thick; a bone of 32 triangles whose flat face the rim pokes into.
  TriMesh organ = test::sphere(4, 30.0);
  organ.V.col(2) *= 2.0 / 30.0;
  TriMesh bone = test::sphere(1, 14.0);
  const Eigen::Vector3d centre(30.0 + 14.0 * 0.55, 0, 0);  // the rim 0.45 radii into the bone along x
  bone.V.rowwise() += centre.transpose();
  ReferenceAnatomy anatomy = anatomyOf({{"organ", organ}, {"bone", bone}});
  const double before = deepestEitherWay(organ, bone);
  const TissuesBentApart bend = bendTissuesApart(anatomy, {BendRole::Fixed, BendRole::Bent}, sphereSkin, {});
  const double after = deepestEitherWay(anatomy.tissues[0].mesh, anatomy.tissues[1].mesh);
  std::printf("rim into a coarse bone: deepest %.2f mm before, %.2f after; %ld points before, %ld after\n", before,
              after, bend.insideBefore, bend.insideAfter);
  EXPECT_GT(before, 1.0);
  EXPECT_EQ(after, 0.0);
  EXPECT_EQ(bend.insideAfter, 0);
}

TEST(TissuesBentApart, TissuesApartStayAndRolesOfAnotherLengthAreRefused) {
  ReferenceAnatomy anatomy = anatomyOf({{"a", test::sphere(2, 10.0, {-30, 0, 0})}, {"b", test::sphere(2, 10.0, {30, 0, 0})}});
  const ReferenceAnatomy before = anatomy;
  const TissuesBentApart bend = bendTissuesApart(anatomy, {BendRole::Fixed, BendRole::Bent}, sphereSkin, {});
  EXPECT_EQ(bend.insideBefore, 0);
  EXPECT_EQ(anatomy.tissues[1].mesh.V, before.tissues[1].mesh.V);
  EXPECT_THROW(bendTissuesApart(anatomy, {BendRole::Fixed}, sphereSkin, {}), UsageError);
}

}  // namespace
}  // namespace vesalius::transfer
