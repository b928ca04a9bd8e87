// Skin registration with an articulated stage (articulated_registration.h) on a synthetic limb: a capped
// tube whose far half holds a bone of its own, registered onto the same tube bent at the joint and with
// the far half larger. The true correspondence is vertex i bent; closest points alone slide the far half
// along the target instead of turning it.
#include "vesalius/transfer/articulated_registration.h"

#include "vesalius/core/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace vesalius;
using namespace vesalius::transfer;

namespace {

// A tube along +x from x0 to x1 (mm) of the given radius, closed by a centre vertex at each end; rings
// every `step` mm with `around` vertices each. Faces counter-clockwise seen from outside.
TriMesh cappedTube(double x0, double x1, double radius, double step, int around) {
  const int rings = int(std::lround((x1 - x0) / step)) + 1;
  TriMesh m;
  m.V.resize(rings * around + 2, 3);
  for (int r = 0; r < rings; ++r)
    for (int a = 0; a < around; ++a) {
      const double t = 2 * M_PI * a / around;
      m.V.row(r * around + a) << x0 + (x1 - x0) * r / (rings - 1), radius * std::cos(t), radius * std::sin(t);
    }
  const int start = rings * around, end = start + 1;
  m.V.row(start) << x0, 0, 0;
  m.V.row(end) << x1, 0, 0;
  std::vector<Eigen::RowVector3i> faces;
  for (int r = 0; r + 1 < rings; ++r)
    for (int a = 0; a < around; ++a) {
      const int i = r * around + a, j = r * around + (a + 1) % around;
      faces.push_back({i, i + around, j});
      faces.push_back({j, i + around, j + around});
    }
  for (int a = 0; a < around; ++a) {
    faces.push_back({start, a, (a + 1) % around});
    faces.push_back({end, (rings - 1) * around + (a + 1) % around, (rings - 1) * around + a});
  }
  m.F.resize(Eigen::Index(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) m.F.row(Eigen::Index(f)) = faces[f];
  return m;
}

// The limb: a 400 mm tube, a trunk bone in its near half and a free bone ("forearm") in its far half.
ReferenceAnatomy limb() {
  ReferenceAnatomy a;
  a.name = "limb";
  a.skin = cappedTube(0, 400, 30, 10, 24);
  a.tissues.push_back({"spine", TissueKind::Bone, "trunk_bones", true, cappedTube(10, 190, 5, 10, 8)});
  a.tissues.push_back({"ulna", TissueKind::Bone, "forearm", false, cappedTube(210, 390, 5, 10, 8)});
  return a;
}

// Vertices beyond x = 200 turned by `degrees` about S through (200, 0, 0) and scaled by `scale` about it.
MatrixX3d bent(const MatrixX3d& V, double degrees, double scale) {
  const Eigen::Vector3d joint(200, 0, 0);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(degrees * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  MatrixX3d B = V;
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    if (V(v, 0) > 200) B.row(v) = (joint + scale * R * (V.row(v).transpose() - joint)).transpose();
  return B;
}

// Mean distance to the truth of the vertices beyond the joint, mm.
double farError(const MatrixX3d& V, const MatrixX3d& truth, const MatrixX3d& rest) {
  double sum = 0;
  int count = 0;
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    if (rest(v, 0) > 200) sum += (V.row(v) - truth.row(v)).norm(), ++count;
  return sum / count;
}

}  // namespace

TEST(ArticulatedRegistration, PartsFollowTheBones) {
  const ReferenceAnatomy a = limb();
  const SkinParts parts = skinPartsFromBones(a);
  ASSERT_EQ(parts.names.size(), 2u);
  EXPECT_EQ(parts.names[0], "trunk");
  EXPECT_EQ(parts.names[1], "forearm");
  EXPECT_EQ(parts.parent[1], 0);
  EXPECT_EQ(parts.order, (std::vector<int>{0, 1}));
  for (Eigen::Index v = 0; v < a.skin.V.rows(); ++v)  // away from the border, the side of x = 200 decides
    EXPECT_TRUE(std::abs(a.skin.V(v, 0) - 200) <= 10 || parts.partOfVertex[v] == (a.skin.V(v, 0) > 200 ? 1 : 0)) << v;
  // The border ring lies between x = 200 and the next ring: its edges' midpoints average to the axis.
  EXPECT_LT((parts.joint[1] - Eigen::Vector3d(200, 0, 0)).norm(), 10.0);
}

// The far half turned by 50° and scaled by 1.15 about the joint. Measured: the far half 6.8 mm off the
// truth with ICP and shape matching alone, 1.9 mm with the articulated stage (3.5 mm after its blending
// alone), the far part's scale 1.177. A tube is a weak case for both (closest points on a cylinder
// leave its slide along the axis to the cap, and the bend's inner side overlaps itself): at 60° or
// more the articulated stage gains little here; the MakeHuman hands are the real case
// (tests/apps/cli_transfer_test.cpp).
TEST(ArticulatedRegistration, TheLimbTurnsAndGrowsAboutItsJoint) {
  const ReferenceAnatomy a = limb();
  const TriMesh target{bent(a.skin.V, 50, 1.15), a.skin.F, {}, {}, {}, {}};
  const SkinParts parts = skinPartsFromBones(a);
  const SkinRegistration plain = registerSkin(a.skin.V, a.skin.F, target.V, target.F);
  const ArticulatedRegistration articulated = registerSkinArticulated(a.skin.V, a.skin.F, parts, target.V, target.F);
  const double plainError = farError(plain.V, target.V, a.skin.V);
  const double error = farError(articulated.registration.V, target.V, a.skin.V);
  std::cout << "far half off the truth: plain " << plainError << " mm, articulated " << error << " mm (stage 4 alone "
            << farError(articulated.articulated, target.V, a.skin.V) << " mm), scale "
            << articulated.partTransforms[1].scale << "\n";
  EXPECT_LT(error, 2.5);
  EXPECT_LT(error, 0.4 * plainError);
  EXPECT_NEAR(articulated.partTransforms[1].scale, 1.15, 0.05);
  EXPECT_LT(articulated.registration.finalMeanDistance, 1.0);
}

TEST(ArticulatedRegistration, RejectsPartsThatDoNotFitAndBadOptions) {
  const ReferenceAnatomy a = limb();
  SkinParts parts = skinPartsFromBones(a);
  SkinParts shorter = parts;
  shorter.partOfVertex.pop_back();
  EXPECT_THROW(registerSkinArticulated(a.skin.V, a.skin.F, shorter, a.skin.V, a.skin.F), BadInput);
  SkinParts unknown = parts;
  unknown.partOfVertex[0] = 7;
  EXPECT_THROW(registerSkinArticulated(a.skin.V, a.skin.F, unknown, a.skin.V, a.skin.F), BadInput);
  ArticulatedRegistrationOptions o;
  o.passes = -1;
  EXPECT_THROW(registerSkinArticulated(a.skin.V, a.skin.F, parts, a.skin.V, a.skin.F, o), UsageError);
}
