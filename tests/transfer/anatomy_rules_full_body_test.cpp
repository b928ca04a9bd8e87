// The anatomical rules (anatomy_rules.h) on the full-body reference (MakeHuman's neutral skin with
// Rajagopal's OpenSim bones, `vesalius reference full-body`: 81 bone meshes) and on it transferred
// (Dicko et al. 2013, §7-8) into MakeHuman's thin and muscular bodies. Those share the neutral skin's topology, so
// reference skin vertex i lands at the body's vertex i: the transfer runs without a skin registration,
// on the correspondence the bodies were made with.
#include "vesalius/transfer/anatomy_rules.h"

#include "vesalius/core/triangle_tree.h"
#include "vesalius/io/body_axes.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/reference_anatomy_io.h"
#include "vesalius/meshing/body_distance.h"
#include "vesalius/meshing/mesh_volume.h"
#include "vesalius/meshing/winding_number.h"
#include "vesalius/transfer/anatomy_transfer.h"

#include "full_body_reference.h"

#include <gtest/gtest.h>


#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using namespace vesalius;
using namespace vesalius::transfer;

namespace {

const std::string kData = VESALIUS_TESTDATA;

using vesalius::test::fullBodyReference;

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void print(const ReferenceAnatomy& anatomy, const AnatomyRules& r) {
  const auto name = [&](int t) { return t >= 0 ? anatomy.tissues[std::size_t(t)].name : std::string("-"); };
  std::printf("  outside: %ld of %ld vertices (at a cut %ld), worst %.2f mm (%s); pushed out %ld (deep %ld); in "
              "cavities %ld\n",
              r.outside.outside, r.outside.vertices, r.outside.outsideAtCut, r.outside.worstMm,
              name(r.outside.worstTissue).c_str(), r.outside.pushedOut, r.outside.pushedOutDeep, r.outside.inCavities);
  if (r.folds.measured)
    std::printf("  folds: det min %.3f, %lld folded of %lld cells\n", r.folds.jacobian.minimum,
                (long long)r.folds.jacobian.nonPositiveCells, (long long)r.folds.jacobian.measuredCells);
  for (const SymmetricGroup& g : r.symmetry.groups)
    std::printf("  symmetry: %s (%zu meshes) %.3f mm, reference %.3f mm\n", g.group.c_str(), g.tissues.size(),
                g.asymmetryMm, g.referenceAsymmetryMm);
  std::printf("  straightness: %zu long bones, worst excess %.4f of the length (%s)\n", r.straightness.bones.size(),
              r.straightness.worstExcess, name(r.straightness.worstTissue).c_str());
  std::printf("  interpenetration: %zu open, %zu skipped, %ld box pairs, %zu pairs touching, worst %.2f mm, excess %.2f mm\n",
              r.interpenetration.openTissues.size(), r.interpenetration.skippedTissues.size(), r.interpenetration.boxPairs,
              r.interpenetration.pairs.size(), r.interpenetration.worstMm, r.interpenetration.worstExcessMm);
  for (std::size_t p = 0; p < std::min<std::size_t>(r.interpenetration.pairs.size(), 14); ++p) {
    const Interpenetration& i = r.interpenetration.pairs[p];
    std::printf("    %s / %s: %.2f mm (reference %.2f), %ld vertices\n", name(i.a).c_str(), name(i.b).c_str(), i.depthMm,
                i.referenceDepthMm, i.vertices);
  }
  for (const auto& [stage, seconds] : r.stageSeconds) std::printf("  %s: %.2f s\n", stage.c_str(), seconds);
}

// The deepest vertex of either tissue inside the other, over all their vertices, by the exact winding
// number (every triangle summed) and the exact distance: what the rule finds with its boxes and the fast
// winding number, measured without either.
double exactInterpenetration(const TriMesh& a, const TriMesh& b) {
  double deepest = 0;
  for (const auto& [inner, outer] : {std::pair{&a, &b}, std::pair{&b, &a}}) {
    const Eigen::VectorXd w = meshing::windingNumbers(outer->V, outer->F, inner->V, meshing::WindingNumberOptions{0.0});
    const TriangleTree tree(outer->V, outer->F);
    for (Eigen::Index r = 0; r < inner->V.rows(); ++r)
      if (w[r] >= 0.5)
        deepest = std::max(deepest, std::sqrt(tree.closest(Eigen::Vector3d(inner->V.row(r).transpose())).squaredDistance));
  }
  return deepest;
}

// The five largest overlaps the rule found, each measured again by exactInterpenetration.
void expectExactOverlaps(const ReferenceAnatomy& anatomy, const InterpenetrationRule& rule) {
  for (std::size_t p = 0; p < std::min<std::size_t>(rule.pairs.size(), 5); ++p) {
    const Interpenetration& i = rule.pairs[p];
    const double exact = exactInterpenetration(anatomy.tissues[std::size_t(i.a)].mesh, anatomy.tissues[std::size_t(i.b)].mesh);
    EXPECT_NEAR(i.depthMm, exact, 1e-9) << anatomy.tissues[std::size_t(i.a)].name << " / " << anatomy.tissues[std::size_t(i.b)].name;
  }
}

}  // namespace

// The reference by its own rules: `reference full-body` moves every bone inside the skin (its cavities
// counted inside) and keeps the trunk's groups symmetric (R2, within the rule's 1 mm); against itself
// nothing exceeds the reference. Its OpenSim bones overlap at the joints (printed).
TEST(AnatomyRulesFullBody, TheReferenceItself) {
  const ReferenceAnatomy& reference = fullBodyReference();
  ASSERT_EQ(reference.tissues.size(), 81u);
  const auto start = std::chrono::steady_clock::now();
  const AnatomyRules rules = checkAnatomyRules(reference, reference, nullptr);
  std::printf("the full-body reference, %zu tissues: %.2f s, its body made by the rules\n", reference.tissues.size(),
              secondsSince(start));
  print(reference, rules);
  EXPECT_EQ(rules.outside.vertices, 30751);
  EXPECT_EQ(rules.outside.outside, 0);
  EXPECT_GT(rules.outside.inCavities, 1000);  // the skull and jaw in the mouth
  EXPECT_EQ(rules.symmetry.groups.size(), 3u);  // pelvis, torso, skull
  for (const SymmetricGroup& g : rules.symmetry.groups) EXPECT_LT(g.asymmetryMm, 1.0) << g.group;
  EXPECT_EQ(rules.straightness.bones.size(), 22u);
  EXPECT_EQ(rules.straightness.worstExcess, 0.0);
  EXPECT_GT(rules.interpenetration.pairs.size(), 10u);
  EXPECT_EQ(rules.interpenetration.worstExcessMm, 0.0);
  EXPECT_TRUE(rules.holds());
  expectExactOverlaps(reference, rules.interpenetration);
}

// The reference transferred into the thin and the muscular body (6 mm field, the bones kept inside the
// target's skin) by the rules the transfer keeps: no folded cell, the trunk as symmetric as the
// reference's within 1 mm (R2), the long bones as straight within 1 % of their length (R1), no vertex a
// field voxel or more inside the reference's skin outside the target's (R5, R6). Interpenetration is
// printed, not asserted: where two bone groups' maps meet at a joint the transfer lets them overlap more
// than in the reference (docs/methods/anatomy-transfer.md, "Validation").
TEST(AnatomyRulesFullBody, TransferredIntoMakeHumanBodies) {
  const ReferenceAnatomy& reference = fullBodyReference();
  const meshing::BodyDistance referenceBody = meshing::bodySignedDistance(reference.skin);
  constexpr double kVoxelMm = 6;
  for (const char* shape : {"mh_male_young_thin_body.obj", "mh_male_young_muscular_body.obj"}) {
    TriMesh target = io::readTriMesh(kData + "/body/shapes/" + shape);
    target.V = io::transformPoints(target.V, io::yUpToLps(), 100.0);
    ASSERT_EQ(target.V.rows(), reference.skin.V.rows());
    const meshing::BodyDistance targetBody = meshing::bodySignedDistance(target);
    meshing::CoveringGridOptions grid;
    grid.voxelSizeMm = kVoxelMm;
    grid.marginMm = 3 * kVoxelMm;
    std::vector<const TriMesh*> meshes{&reference.skin};
    for (const ReferenceTissue& t : reference.tissues) meshes.push_back(&t.mesh);
    const Grid<std::uint8_t> inside = meshing::meshInsideMask(reference.skin, meshing::coveringGrid(meshes, grid));
    AnatomyTransferOptions options;
    options.targetSkinDistance = &targetBody.signedDistance;
    options.referenceSkinDistance = &referenceBody.signedDistance;
    const TransferredAnatomy result = transferAnatomy(reference, target.V, inside, options);
    ReferenceAnatomy transferred = reference;
    transferred.skin.V = target.V;
    transferred.sagittal = result.sagittal;
    for (std::size_t t = 0; t < transferred.tissues.size(); ++t) transferred.tissues[t].mesh.V = result.tissues[t];

    AnatomyRulesOptions rulesOptions;
    rulesOptions.deepMm = kVoxelMm;
    rulesOptions.skinDistance = &targetBody.signedDistance;
    rulesOptions.skinCavities = &targetBody.cavities;
    rulesOptions.referenceSkinDistance = &referenceBody.signedDistance;
    rulesOptions.referenceSkinCavities = &referenceBody.cavities;
    const auto start = std::chrono::steady_clock::now();
    const AnatomyRules rules = checkAnatomyRules(reference, transferred, &result.finalField, rulesOptions);
    std::printf("%s: %.2f s, the bodies given\n", shape, secondsSince(start));
    print(transferred, rules);
    EXPECT_EQ(rules.outside.referenceVertices, 30751) << shape;
    EXPECT_EQ(rules.outside.pushedOutDeep, 0) << shape;
    EXPECT_TRUE(rules.folds.holds) << shape;
    EXPECT_EQ(rules.symmetry.groups.size(), 3u) << shape;
    EXPECT_LE(rules.symmetry.worstExcessMm, 1.0) << shape;
    EXPECT_TRUE(rules.symmetry.holds) << shape;
    EXPECT_EQ(rules.straightness.bones.size(), 22u) << shape;
    EXPECT_LE(rules.straightness.worstExcess, 0.01) << shape;
    EXPECT_TRUE(rules.straightness.holds) << shape;
    expectExactOverlaps(transferred, rules.interpenetration);
  }
}
