// The anatomical rules of Dicko et al. 2013 (§3) measured on an anatomy (anatomy_rules.h), on synthetic anatomies
// where each rule must fire and must not: a tissue pushed out of the skin, an inverting field, a trunk
// pair moved off the sagittal plane, a bent long bone, two spheres overlapping.
#include "vesalius/transfer/anatomy_rules.h"

#include "vesalius/meshing/body_distance.h"
#include "vesalius/meshing/mesh_volume.h"
#include "test_shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace vesalius;
using namespace vesalius::transfer;

namespace {

TriMesh ellipsoid(int levels, const Eigen::Vector3d& radii, const Eigen::Vector3d& centre) {
  TriMesh m = test::sphere(levels);
  m.V = (m.V * radii.asDiagonal()).rowwise() + centre.transpose();
  return m;
}

// A body: a skin sphere of radius 80 mm about the origin, sagittal plane x = 0, no tissues.
ReferenceAnatomy emptyBody() {
  ReferenceAnatomy body;
  body.name = "synthetic";
  body.skin = test::sphere(5, 80.0);
  body.sagittal = {Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX()};
  return body;
}

ReferenceTissue tissue(const std::string& name, TissueKind kind, const TriMesh& mesh, const std::string& group = "",
                       bool symmetric = false) {
  return {name, kind, group, symmetric, mesh};
}

AnatomyRulesOptions only(bool outside, bool symmetry, bool straightness, bool interpenetration) {
  AnatomyRulesOptions o;
  o.outside = outside, o.symmetry = symmetry, o.straightness = straightness, o.interpenetration = interpenetration;
  return o;
}

}  // namespace

// R5, R6: a sphere of radius r whose outermost vertex (on the +L axis, as the skin has one there) lies
// `depth` mm outside the skin reads `depth` (the body's 2 mm signed-distance grid, exact at its voxel
// centres, trilinear between); one 2 mm inside reads nothing outside. Against the reference, where it
// lay 4 mm inside, its vertices outside are pushed out, and deep (deepMm 3).
TEST(AnatomyRules, ATissuePushedOutOfTheSkinReadsHowFar) {
  // Both skins are the same: their body is made once and given (the rule's own is tested below).
  const meshing::BodyDistance body = meshing::bodySignedDistance(emptyBody().skin);
  AnatomyRulesOptions options = only(true, false, false, false);
  options.skinDistance = options.referenceSkinDistance = &body.signedDistance;
  options.skinCavities = options.referenceSkinCavities = &body.cavities;
  for (const double radius : {6.0, 15.0})
    for (const double depth : {-2.0, 1.0, 3.0, 5.0}) {
      ReferenceAnatomy reference = emptyBody(), moved = emptyBody();
      reference.tissues.push_back(tissue("organ", TissueKind::Organ, test::sphere(3, radius, {80.0 - 4.0 - radius, 0, 0})));
      moved.tissues.push_back(tissue("organ", TissueKind::Organ, test::sphere(3, radius, {80.0 + depth - radius, 0, 0})));
      const AnatomyRules rules = checkAnatomyRules(reference, moved, nullptr, options);
      const OutsideRule& o = rules.outside;
      std::printf("radius %4.1f mm, outermost vertex %+4.1f mm out: %ld of %ld outside, worst %.3f mm; pushed out %ld "
                  "(deep %ld), outside the reference %ld\n",
                  radius, depth, o.outside, o.vertices, o.worstMm, o.pushedOut, o.pushedOutDeep, o.referenceOutside);
      EXPECT_EQ(o.vertices, moved.tissues[0].mesh.V.rows());
      EXPECT_EQ(o.referenceOutside, 0);
      if (depth < 0) {
        EXPECT_EQ(o.outside, 0);
        EXPECT_TRUE(o.holds);
        continue;
      }
      EXPECT_GT(o.outside, 0);
      EXPECT_NEAR(o.worstMm, depth, 0.1);
      EXPECT_EQ(o.worstTissue, 0);
      EXPECT_NEAR(o.worstAt.x(), 80.0 + depth, 1e-9);
      EXPECT_EQ(o.pushedOut, o.outside);
      EXPECT_EQ(o.pushedOutDeep, o.outside);  // every vertex was at least 4 mm inside
      EXPECT_NEAR(o.pushedOutWorstMm, o.worstMm, 1e-12);
      EXPECT_EQ(rules.tissues[0].outside, o.outside);
      EXPECT_FALSE(o.holds);
      EXPECT_FALSE(rules.holds());
    }
}

// A skin cut (a scan's field of view): a tissue outside the body next to the cut vertices counts at the
// cut, and the rule holds; the same tissue beside skin that is not cut does not.
TEST(AnatomyRules, OutsideThroughACutIsNotThroughTheSkin) {
  ReferenceAnatomy body = emptyBody();
  body.tissues.push_back(tissue("lung", TissueKind::Organ, test::sphere(3, 10.0, {0, 0, 72.0})));  // 2 mm out at the top
  const AnatomyRules uncut = checkAnatomyRules(body, body, nullptr, only(true, false, false, false));
  for (Eigen::Index v = 0; v < body.skin.V.rows(); ++v)
    if (body.skin.V(v, 2) > 70.0) body.skinCutVertices.push_back(int(v));
  const AnatomyRules cut = checkAnatomyRules(body, body, nullptr, only(true, false, false, false));
  std::printf("outside %ld, at a cut %ld (without the cut: %ld, %ld)\n", cut.outside.outside, cut.outside.outsideAtCut,
              uncut.outside.outside, uncut.outside.outsideAtCut);
  EXPECT_GT(uncut.outside.outside, 0);
  EXPECT_EQ(uncut.outside.outsideAtCut, 0);
  EXPECT_FALSE(uncut.outside.holds);
  EXPECT_EQ(cut.outside.outside, uncut.outside.outside);
  EXPECT_EQ(cut.outside.outsideAtCut, cut.outside.outside);
  EXPECT_EQ(cut.outside.referenceOutsideAtCut, cut.outside.referenceOutside);
  EXPECT_TRUE(cut.outside.holds);
}

// The field's folds: the skin moved by u = 0.2 x, whose harmonic extension grows the body (det 1.2³ but
// for the splat's first-order error at the skin), folds nowhere; u = −2 x (x ↦ −x, det −1) folds. Without a
// field the rule is not measured.
TEST(AnatomyRules, AnInvertingFieldFolds) {
  const ReferenceAnatomy body = emptyBody();
  meshing::CoveringGridOptions grid;
  grid.voxelSizeMm = 6;
  grid.marginMm = 12;
  const Grid<std::uint8_t> inside = meshing::meshInsideMask(body.skin, meshing::coveringGrid({&body.skin}, grid));
  const AnatomyRulesOptions options = only(false, false, false, false);
  for (const double scale : {0.2, -2.0}) {
    const DisplacementField field = interpolateDisplacements(inside, body.skin.V, scale * body.skin.V);
    const AnatomyRules rules = checkAnatomyRules(body, body, &field, options);
    std::printf("u = %.1f x: det min %.3f, %lld of %lld cells folded\n", scale, rules.folds.jacobian.minimum,
                (long long)rules.folds.jacobian.nonPositiveCells, (long long)rules.folds.jacobian.measuredCells);
    EXPECT_TRUE(rules.folds.measured);
    EXPECT_EQ(rules.folds.holds, scale > 0);
    if (scale > 0) {
      EXPECT_GT(rules.folds.jacobian.minimum, 1.0);
    } else {
      EXPECT_GT(rules.folds.jacobian.nonPositiveCells, rules.folds.jacobian.measuredCells / 2);
    }
  }
  const AnatomyRules none = checkAnatomyRules(body, body, nullptr, options);
  EXPECT_FALSE(none.folds.measured);
  EXPECT_TRUE(none.folds.holds);
}

// R2: a pelvis-like pair (two hip spheres of radius 20 mm, 40 mm either side of the sagittal plane, one
// symmetric group) reads 0; moved `shift` mm to the left as a whole, its mirror image lies 2·shift from
// it, and the mean distance of a sphere's points to the sphere shifted by 2·shift is shift (the mean of
// |cos| over a sphere is 1/2) to first order: it reads its shift. Against the reference pair the excess
// is the same; within 1 mm the rule holds. Tilted ellipsoids (a pelvis's wings) read 0 when mirrored.
TEST(AnatomyRules, ATrunkPairMovedOffTheSagittalPlaneReadsItsShift) {
  const auto pair = [](double shift, const Eigen::Vector3d& radii, double tilt) {
    ReferenceAnatomy body = emptyBody();
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitY()).toRotationMatrix();
    for (const double side : {1.0, -1.0}) {
      TriMesh hip = ellipsoid(4, radii, Eigen::Vector3d::Zero());
      Eigen::Matrix3d mirror = Eigen::Matrix3d::Identity();
      mirror(0, 0) = side;
      hip.V = hip.V * (mirror * turn * mirror).transpose();
      hip.V.rowwise() += Eigen::RowVector3d(side * 40.0 + shift, 0, -30);
      body.tissues.push_back(tissue(side > 0 ? "hip_l" : "hip_r", TissueKind::Bone, hip, "pelvis", true));
    }
    body.tissues.push_back(tissue("femur_l", TissueKind::Bone, ellipsoid(3, {7, 7, 40}, {40, 0, -30}), "", false));
    return body;
  };
  const AnatomyRulesOptions options = only(false, true, false, false);
  for (const double shift : {0.0, 0.5, 2.0, 4.0}) {
    const ReferenceAnatomy reference = pair(0.0, {20, 20, 20}, 0), moved = pair(shift, {20, 20, 20}, 0);
    const AnatomyRules rules = checkAnatomyRules(reference, moved, nullptr, options);
    ASSERT_EQ(rules.symmetry.groups.size(), 1u);  // the femur is not a trunk bone
    const SymmetricGroup& g = rules.symmetry.groups[0];
    std::printf("pelvis moved %.1f mm off the plane: asymmetry %.3f mm (reference %.3f mm)\n", shift, g.asymmetryMm,
                g.referenceAsymmetryMm);
    EXPECT_EQ(g.group, "pelvis");
    EXPECT_EQ(g.tissues.size(), 2u);
    EXPECT_LT(g.referenceAsymmetryMm, 1e-9);
    EXPECT_NEAR(g.asymmetryMm, shift, 0.05 * shift + 1e-9);
    EXPECT_NEAR(rules.symmetry.worstExcessMm, g.asymmetryMm - g.referenceAsymmetryMm, 1e-12);
    EXPECT_EQ(rules.symmetry.holds, shift <= 1.0);
    // A tissue of its own in the moved anatomy (no reference mesh) is measured against 0.
    ReferenceAnatomy renamed = moved;
    for (ReferenceTissue& t : renamed.tissues) t.name += "_patient";
    const AnatomyRules alone = checkAnatomyRules(reference, renamed, nullptr, options);
    EXPECT_TRUE(std::isnan(alone.symmetry.groups[0].referenceAsymmetryMm));
    EXPECT_NEAR(alone.symmetry.worstExcessMm, g.asymmetryMm, 1e-12);
  }
  for (const double tilt : {0.3, 0.6}) {
    const ReferenceAnatomy wings = pair(0.0, {25, 8, 30}, tilt);
    const AnatomyRules rules = checkAnatomyRules(wings, wings, nullptr, options);
    std::printf("tilted wings %.1f rad: asymmetry %.2e mm\n", tilt, rules.symmetry.groups[0].asymmetryMm);
    EXPECT_LT(rules.symmetry.groups[0].asymmetryMm, 1e-6);
    EXPECT_TRUE(rules.symmetry.holds);
  }
}

// R1: a long bone (half-axes 7, 7, 60 mm) moved rigidly and scaled reads its reference's deviation; bent
// into a parabola whose middle lies `bend` mm off the line through its ends it reads more, the more it
// is bent, and past 1 % of its length the rule fails. A short bone (a sphere) has no centre line.
TEST(AnatomyRules, ABentLongBoneReadsMoreThanTheStraightOne) {
  ReferenceAnatomy reference = emptyBody();
  reference.tissues.push_back(tissue("femur_l", TissueKind::Bone, ellipsoid(4, {7, 7, 60}, {30, 0, 0})));
  reference.tissues.push_back(tissue("patella_l", TissueKind::Bone, test::sphere(3, 8.0, {30, -20, -50})));
  const AnatomyRulesOptions options = only(false, false, true, false);
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 0).normalized()).toRotationMatrix();
  double previous = -1;
  for (const double bend : {0.0, 2.0, 5.0, 10.0}) {
    ReferenceAnatomy moved = reference;
    MatrixX3d& V = moved.tissues[0].mesh.V;
    for (Eigen::Index r = 0; r < V.rows(); ++r) V(r, 0) += bend * (1.0 - std::pow(V(r, 2) / 60.0, 2));
    V = ((1.1 * V) * turn.transpose()).rowwise() + Eigen::RowVector3d(5, -3, 8);
    const AnatomyRules rules = checkAnatomyRules(reference, moved, nullptr, options);
    ASSERT_EQ(rules.straightness.bones.size(), 1u);
    const StraightBone& b = rules.straightness.bones[0];
    std::printf("bent %4.1f mm: centre-line deviation %.4f of the length (reference %.4f), excess %.4f\n", bend,
                b.deviation, b.referenceDeviation, rules.straightness.worstExcess);
    EXPECT_EQ(b.tissue, 0);
    EXPECT_TRUE(std::isnan(rules.tissues[1].centreLineDeviation));
    if (bend == 0.0) {
      EXPECT_NEAR(b.deviation, b.referenceDeviation, 1e-9);
    } else {
      EXPECT_GT(b.deviation, previous + 0.005);
    }
    previous = b.deviation;
    EXPECT_EQ(rules.straightness.holds, rules.straightness.worstExcess <= 0.01);
    if (bend >= 5.0) {
      EXPECT_FALSE(rules.straightness.holds);
    }
    if (bend == 0.0) {
      EXPECT_TRUE(rules.straightness.holds);
    }
  }
}

// Two closed spheres of radius r, centres d apart (d < 2r), overlap by r + r − d: the vertex of each on
// the line of centres lies that deep inside the other (less the polyhedron's sag, under 0.3 % of r at
// 2,048 triangles). Apart, or overlapping by at most 1 mm, the rule holds. A muscle line (points, no
// triangles) has no inside and is skipped.
TEST(AnatomyRules, TwoOverlappingSpheresReadTheirOverlap) {
  const AnatomyRulesOptions options = only(false, false, false, true);
  for (const double r : {10.0, 25.0})
    for (const double overlap : {-5.0, 0.5, 3.0, 8.0}) {
      const double d = 2 * r - overlap;
      ReferenceAnatomy body = emptyBody();
      body.tissues.push_back(tissue("kidney", TissueKind::Organ, test::sphere(4, r, {-d / 2, 0, 0})));
      body.tissues.push_back(tissue("spleen", TissueKind::Organ, test::sphere(4, r, {d / 2, 0, 0})));
      body.tissues.push_back(tissue("liver", TissueKind::Organ, test::sphere(4, 10.0, {0, 0, 60})));
      TriMesh line;
      line.V = MatrixX3d::Zero(5, 3);
      line.V.col(0) = Eigen::VectorXd::LinSpaced(5, -r, r);
      body.tissues.push_back(tissue("muscle_line", TissueKind::Muscle, line));
      // Both spheres carried into another body unchanged, and as tissues of that body alone: the
      // reference's overlap is the pair's own, or there is none to compare with.
      ReferenceAnatomy own = body;
      for (ReferenceTissue& t : own.tissues) t.name += "_own";
      for (const ReferenceAnatomy* reference : {&body, &own}) {
        const AnatomyRules rules = checkAnatomyRules(*reference, body, nullptr, options);
        const InterpenetrationRule& p = rules.interpenetration;
        const bool carried = reference == &body;
        std::printf("r %4.1f mm, d %5.1f mm (r + r - d = %4.1f), %s: worst %.3f mm, excess %.3f mm, %zu pair(s), %ld "
                    "box pair(s)\n",
                    r, d, overlap, carried ? "carried" : "own", p.worstMm, p.worstExcessMm, p.pairs.size(), p.boxPairs);
        ASSERT_EQ(p.skippedTissues.size(), 1u);
        EXPECT_EQ(p.skippedTissues[0], 3);
        EXPECT_TRUE(p.openTissues.empty());
        EXPECT_TRUE(rules.tissues[0].closed);
        if (overlap < 0) {
          EXPECT_TRUE(p.pairs.empty());
          EXPECT_EQ(p.worstMm, 0.0);
          EXPECT_TRUE(p.holds);
          continue;
        }
        ASSERT_EQ(p.pairs.size(), 1u);
        EXPECT_EQ(p.pairs[0].a, 0);
        EXPECT_EQ(p.pairs[0].b, 1);
        EXPECT_NEAR(p.worstMm, overlap, 0.003 * r);
        EXPECT_LE(p.worstMm, overlap + 1e-9);
        EXPECT_NEAR(std::abs(p.pairs[0].at.x()), std::abs(d / 2 - r), 1e-9);  // a vertex on the line of centres
        EXPECT_EQ(rules.tissues[0].interpenetrates, 1);
        EXPECT_EQ(rules.tissues[1].interpenetrates, 0);
        EXPECT_EQ(rules.tissues[2].interpenetrates, -1);
        if (carried) {
          EXPECT_NEAR(p.pairs[0].referenceDepthMm, p.worstMm, 1e-12);
          EXPECT_NEAR(p.worstExcessMm, 0.0, 1e-12);
          EXPECT_TRUE(p.holds);
        } else {
          EXPECT_TRUE(std::isnan(p.pairs[0].referenceDepthMm));
          EXPECT_NEAR(p.worstExcessMm, p.worstMm, 1e-12);
          EXPECT_EQ(p.holds, overlap <= 1.0);
        }
      }
    }
}

// Pushed 4 mm further into each other than in the reference, two spheres exceed the reference's overlap
// by 4 mm, or by their overlap if they were apart in it (measured against 0).
TEST(AnatomyRules, AnOverlapIsMeasuredAgainstTheReferences) {
  const AnatomyRulesOptions options = only(false, false, false, true);
  for (const double before : {-2.0, 0.0, 4.0}) {
    ReferenceAnatomy reference = emptyBody();
    reference.tissues.push_back(tissue("femur", TissueKind::Bone, test::sphere(4, 20.0, {-20.0 + before / 2, 0, 0})));
    reference.tissues.push_back(tissue("patella", TissueKind::Bone, test::sphere(4, 20.0, {20.0 - before / 2, 0, 0})));
    ReferenceAnatomy moved = reference;
    moved.tissues[1].mesh.V.col(0).array() -= 4.0;
    const AnatomyRules rules = checkAnatomyRules(reference, moved, nullptr, options);
    const InterpenetrationRule& p = rules.interpenetration;
    ASSERT_EQ(p.pairs.size(), 1u);
    std::printf("overlap %.1f mm in the reference, 4 mm more: %.3f mm (reference %.3f mm), excess %.3f mm\n", before,
                p.pairs[0].depthMm, p.pairs[0].referenceDepthMm, p.worstExcessMm);
    EXPECT_NEAR(p.pairs[0].referenceDepthMm, std::max(before, 0.0), 0.003 * 20);
    EXPECT_NEAR(p.pairs[0].depthMm, before + 4.0, 0.003 * 20);
    EXPECT_NEAR(p.worstExcessMm, before + 4.0 - std::max(before, 0.0), 0.006 * 20);
    EXPECT_FALSE(p.holds);
  }
}

// A sphere with a hole (one triangle taken out, as OpenSim's bone meshes have) still has its inside by
// the winding number: a closed sphere 2 mm into it on the side away from the hole reads 2 mm.
TEST(AnatomyRules, AMeshWithAHoleHasAnInside) {
  ReferenceAnatomy body = emptyBody();
  TriMesh holed = test::sphere(4, 15.0);
  Eigen::Index top = 0;
  holed.V.col(2).maxCoeff(&top);
  Eigen::Index drop = 0;
  for (Eigen::Index f = 0; f < holed.F.rows(); ++f)
    if ((holed.F.row(f).array() == int(top)).any()) drop = f;
  holed.F.row(drop) = holed.F.row(holed.F.rows() - 1);
  holed.F.conservativeResize(holed.F.rows() - 1, 3);
  body.tissues.push_back(tissue("tibia", TissueKind::Bone, holed));
  body.tissues.push_back(tissue("fibula", TissueKind::Bone, test::sphere(4, 5.0, {15.0 + 5.0 - 2.0, 0, 0})));
  const AnatomyRules rules = checkAnatomyRules(body, body, nullptr, only(false, false, false, true));
  const InterpenetrationRule& p = rules.interpenetration;
  std::printf("a sphere 2 mm into one with a hole: %.3f mm\n", p.worstMm);
  ASSERT_EQ(p.openTissues.size(), 1u);
  EXPECT_EQ(p.openTissues[0], 0);
  EXPECT_FALSE(rules.tissues[0].closed);
  ASSERT_EQ(p.pairs.size(), 1u);
  EXPECT_NEAR(p.worstMm, 2.0, 0.003 * 15);
}

// A tissue moved wholly inside another (an organ into a muscle) reads the depth of its deepest vertex: a
// sphere of radius 5 mm centred 10 mm off the centre of one of radius 30 mm has its nearest vertex to that
// centre 5 mm from it, 25 mm inside the outer surface. In the reference it lay outside.
TEST(AnatomyRules, ATissueInsideAnotherReadsItsDepth) {
  ReferenceAnatomy reference = emptyBody();
  reference.tissues.push_back(tissue("outer", TissueKind::Muscle, test::sphere(4, 30.0)));
  reference.tissues.push_back(tissue("inner", TissueKind::Organ, test::sphere(4, 5.0, {50, 0, 0})));
  ReferenceAnatomy moved = reference;
  moved.tissues[1].mesh.V.col(0).array() -= 40.0;
  const AnatomyRules rules = checkAnatomyRules(reference, moved, nullptr, only(false, false, false, true));
  std::printf("a 5 mm sphere 10 mm off the centre of a 30 mm one: deepest %.3f mm\n", rules.interpenetration.worstMm);
  EXPECT_NEAR(rules.interpenetration.worstMm, 25.0, 0.003 * 30.0);
  EXPECT_EQ(rules.interpenetration.pairs[0].referenceDepthMm, 0.0);
  EXPECT_FALSE(rules.interpenetration.holds);
}
