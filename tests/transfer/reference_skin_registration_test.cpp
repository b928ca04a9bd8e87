// The reference skin's registration as `vesalius transfer` runs it (reference_skin_registration.h): the
// landmarks snapped to the skin's nearest vertices, and the articulated or plain registration chosen by
// the options, each the same as the method it names.
#include "vesalius/transfer/reference_skin_registration.h"

#include "vesalius/core/error.h"
#include "test_shapes.h"

#include <gtest/gtest.h>

#include <iostream>

using namespace vesalius;
using namespace vesalius::transfer;

namespace {

TEST(ReferenceSkinRegistration, LandmarksTakeTheNearestVertex) {
  for (const int levels : {1, 2, 3}) {
    const TriMesh skin = test::sphere(levels, 100.0);
    // Every 7th vertex, each point pulled 10 % of the way towards the sphere's centre: nearer to that
    // vertex than to any other.
    std::vector<int> expected;
    MatrixX3d onSkin(0, 3), onTarget(0, 3);
    for (Eigen::Index v = 0; v < skin.V.rows(); v += 7) {
      expected.push_back(int(v));
      onSkin.conservativeResize(onSkin.rows() + 1, 3);
      onTarget.conservativeResize(onTarget.rows() + 1, 3);
      onSkin.row(onSkin.rows() - 1) = 0.9 * skin.V.row(v);
      onTarget.row(onTarget.rows() - 1) = skin.V.row(v) + Eigen::RowVector3d(5, -3, 2);
    }
    const std::vector<SkinLandmark> landmarks = landmarksAtNearestVertices(skin.V, onSkin, onTarget);
    ASSERT_EQ(landmarks.size(), expected.size());
    int right = 0;
    for (std::size_t l = 0; l < landmarks.size(); ++l) {
      right += landmarks[l].sourceVertex == expected[l];
      EXPECT_EQ(landmarks[l].target, onTarget.row(Eigen::Index(l)).transpose());
    }
    std::cout << skin.V.rows() << " vertices: " << right << " of " << landmarks.size() << " landmarks on their vertex\n";
    EXPECT_EQ(right, int(landmarks.size()));
  }
  EXPECT_THROW(landmarksAtNearestVertices(test::sphere(1).V, MatrixX3d::Zero(2, 3), MatrixX3d::Zero(3, 3)),
               UsageError);
  EXPECT_TRUE(landmarksAtNearestVertices(test::sphere(1).V, MatrixX3d(0, 3), MatrixX3d(0, 3)).empty());
}

// A body: an ellipsoid skin with a trunk bone and a free limb bone; the target: the skin scaled and moved.
TEST(ReferenceSkinRegistration, OptionsChooseTheArticulatedOrThePlainRegistration) {
  ReferenceAnatomy reference;
  reference.skin = test::sphere(3, 1.0);
  reference.skin.V = reference.skin.V * Eigen::Vector3d(60, 40, 150).asDiagonal();
  TriMesh spine = test::sphere(2, 1.0);
  spine.V = (spine.V * Eigen::Vector3d(8, 8, 60).asDiagonal()).rowwise() + Eigen::RowVector3d(0, 0, 40);
  TriMesh leg = test::sphere(2, 1.0);
  leg.V = (leg.V * Eigen::Vector3d(8, 8, 40).asDiagonal()).rowwise() + Eigen::RowVector3d(20, 0, -90);
  reference.tissues.push_back({"spine", TissueKind::Bone, "trunk_bones", true, spine});
  reference.tissues.push_back({"femur_l", TissueKind::Bone, "", false, leg});
  MatrixX3d Vt = (reference.skin.V * 1.1).rowwise() + Eigen::RowVector3d(3, -2, 5);
  const SkinParts parts = skinPartsFromBones(reference);

  ReferenceSkinRegistrationOptions options;
  options.registration.registration.iterations = 5;
  options.articulated = false;
  const SkinRegistration plain = registerReferenceSkin(reference, parts, Vt, reference.skin.F, options);
  const SkinRegistration plainDirect =
      registerSkin(reference.skin.V, reference.skin.F, Vt, reference.skin.F, options.registration.registration);
  EXPECT_EQ(plain.V, plainDirect.V);
  options.articulated = true;
  const SkinRegistration articulated = registerReferenceSkin(reference, parts, Vt, reference.skin.F, options);
  const SkinRegistration articulatedDirect =
      registerSkinArticulated(reference.skin.V, reference.skin.F, parts, Vt, reference.skin.F, options.registration)
          .registration;
  EXPECT_EQ(articulated.V, articulatedDirect.V);
  std::cout << "mean distance to the target: plain " << plain.finalMeanDistance << " mm, articulated "
            << articulated.finalMeanDistance << " mm\n";
  // The target is the skin a similarity apart: both land on it (2 mm: 5 % of the smallest half-axis).
  EXPECT_LT(plain.finalMeanDistance, 2.0);
  EXPECT_LT(articulated.finalMeanDistance, 2.0);
}

}  // namespace
