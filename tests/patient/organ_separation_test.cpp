// Fitted organs that touch, separated (patient::separateOrgans, Wang et al. 2021, §4.1.4). The liver and the right
// kidney, whose labels touch on the shipped CT (the kidney's upper pole against the liver's underside: 231
// liver voxels with a kidney voxel among their 26 neighbours), on two patients made from that CT by smooth
// warps that scale both organs and shift them toward each other (warped_patient.h), so the kidney template
// never meets the label it was made from. Both organs are fitted to their labels one at a time
// (patient::fitOrganToLabel, coarse settings, no refits), so they overlap where the labels meet; then
// separated. Measured independently of the method: the depth of each fitted surface's vertices inside the
// other's surface (generalized winding number, distance to the closest triangle), and each organ's Dice
// against its label before and after. (The spleen and the left kidney touch on this CT only across voxel
// edges and corners, 21 voxels; their fits do not overlap, so they are no test of the separation.)
//
// The promise: afterwards no boundary vertex of either organ lies inside the other, up to the
// separation's clearance (organ_separation.h), and each organ's Dice against its own label falls by at
// most 0.01 (a point of Dice is about 1 % of the organ's volume moved out of its label; the contact
// regions move by about the overlap's depth, a voxel or less, and mostly along the surface elsewhere).
#include "test_data.h"
#include "test_tets.h"
#include "warped_patient.h"

#include "vesalius/core/error.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/meshing/mesh_volume.h"
#include "vesalius/meshing/winding_number.h"
#include "vesalius/patient/organ_fit.h"
#include "vesalius/patient/organ_separation.h"
#include "vesalius/segmentation/label_ops.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace vesalius::test {
namespace {

const std::string kTemplates = std::string(VESALIUS_TESTDATA) + "/../templates/organs";

struct TouchingPair {
  std::string first, second;  // fitted in this order
  std::vector<OrganWarp> warps;
};

// Each organ scaled more along two axes than the third and shifted by 10–20 mm toward the other, so that
// they press on each other; the liver, cut by the CT's top slice, without a downward shift that would pull
// its cut into the scan.
const std::vector<TouchingPair>& touchingPairs() {
  static const std::vector<TouchingPair> pairs = {
      {"liver", "kidney_right",
       {{"liver", {1.15, 1.15, 1.0}, {0, 10, 0}}, {"kidney_right", {1.15, 1.0, 1.15}, {0, -10, 10}}}},
      {"liver", "kidney_right",
       {{"liver", {0.9, 0.85, 0.85}, {4, 12, 10}}, {"kidney_right", {0.85, 0.9, 0.85}, {-6, -8, 14}}}},
  };
  return pairs;
}

// Voxels of label a with a voxel of label b among their 26 neighbours.
long touchingVoxels(const LabelMap& map, Label a, Label b) {
  const Grid<Label>& l = map.labels;
  const Eigen::Vector3i n = l.geometry.size;
  long touching = 0;
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i) {
        if (l.at(i, j, k) != a) continue;
        bool found = false;
        for (int dk = -1; dk <= 1 && !found; ++dk)
          for (int dj = -1; dj <= 1 && !found; ++dj)
            for (int di = -1; di <= 1 && !found; ++di) {
              const Eigen::Vector3i q(i + di, j + dj, k + dk);
              found = (q.array() >= 0).all() && (q.array() < n.array()).all() && l.at(q.x(), q.y(), q.z()) == b;
            }
        touching += found;
      }
  return touching;
}

struct Depth {
  long vertices = 0;    // of `a` inside `b`
  double max = 0, mean = 0;  // mm below b's surface
};

// Vertices of surface a inside closed surface b, and how deep.
Depth depthInside(const TriMesh& a, const TriMesh& b) {
  const Eigen::VectorXd w = meshing::windingNumbers(b.V, b.F, a.V);
  const TriangleTree tree(b.V, b.F);
  Depth d;
  for (Eigen::Index v = 0; v < a.V.rows(); ++v) {
    if (w(v) <= 0.5) continue;
    const double depth = std::sqrt(tree.closest(Eigen::Vector3d(a.V.row(v).transpose())).squaredDistance);
    ++d.vertices;
    d.max = std::max(d.max, depth);
    d.mean += depth;
  }
  if (d.vertices > 0) d.mean /= double(d.vertices);
  return d;
}

std::ostream& operator<<(std::ostream& out, const Depth& d) {
  return out << d.vertices << " vertices, deepest " << d.max << " mm (mean " << d.mean << ")";
}

class OrganSeparation : public ::testing::TestWithParam<int> {};

TEST_P(OrganSeparation, TouchingFittedOrgansAreSeparatedKeepingTheirDice) {
  const TouchingPair& pair = touchingPairs()[std::size_t(GetParam())];
  const Image ct = io::readScan(kCtScan);
  const LabelMap labels = io::readLabelMap(kCtLabels, kCtLabelTable);
  const WarpedPatient warped = warpPatient(ct, labels, pair.warps);
  ASSERT_GT(warped.minJacobian, 0.0);
  const GridGeometry& g = warped.labels.labels.geometry;
  const Label ids[2] = {warped.labels.table.resolve(pair.first), warped.labels.table.resolve(pair.second)};
  const std::string names[2] = {pair.first, pair.second};
  const std::string tag = pair.first + " / " + pair.second;

  // The labels touch: the pair is one the separation has work on.
  const long touching = touchingVoxels(warped.labels, ids[0], ids[1]);
  std::cout << tag << ": " << touching << " voxels of " << names[0] << " touch " << names[1]
            << " (26-neighbours; the CT before the warp: "
            << touchingVoxels(labels, labels.table.resolve(pair.first), labels.table.resolve(pair.second)) << ")\n";
  ASSERT_GT(touching, 0);

  patient::OrganFitOptions options;
  options.markers = 200;
  options.targetTets = 2000;
  options.refits = 0;  // Wang et al.'s fit alone: less close than with refits, so the organs overlap more
  std::vector<patient::OrganFit> fits;
  for (int m = 0; m < 2; ++m)
    fits.push_back(patient::fitOrganToLabel(io::readTriMesh(kTemplates + "/" + names[m] + ".obj"), warped.labels,
                                            ids[m], options, "warped labels"));
  for (const patient::OrganFit& f : fits) {
    // The fit keeps its last round's tets, and its surface is their boundary.
    ASSERT_GT(f.tets.T.rows(), 0);
    ASSERT_EQ(tetBoundarySurface(f.tets.V, f.tets.T).V, f.surface.V);
  }

  const auto dice = [&](int m) {
    return segmentation::diceCoefficient(meshing::meshInsideMask(fits[std::size_t(m)].surface, g),
                                         segmentation::maskOf(warped.labels.labels, ids[m]));
  };
  const double diceBefore[2] = {dice(0), dice(1)};
  const Depth before[2] = {depthInside(fits[0].surface, fits[1].surface),
                           depthInside(fits[1].surface, fits[0].surface)};
  const Depth carriedBefore[2] = {depthInside(fits[0].carriedTemplate, fits[1].surface),
                                  depthInside(fits[1].carriedTemplate, fits[0].surface)};
  const patient::OrganFit unseparated[2] = {fits[0], fits[1]};
  std::cout << tag << ": before, " << names[0] << " in " << names[1] << ": " << before[0] << "; " << names[1]
            << " in " << names[0] << ": " << before[1] << '\n';
  // Fitted one at a time, the organs overlap where their labels meet (else this test would test nothing).
  ASSERT_GT(before[0].vertices + before[1].vertices, 0);

  const patient::OrganSeparationOptions separation;
  const std::vector<patient::OrganPairSeparation> report = patient::separateOrgans({&fits[0], &fits[1]}, separation);
  ASSERT_EQ(report.size(), 1u);
  const patient::OrganPairSeparation& r = report.front();
  std::cout << tag << ": separateOrgans: " << r.penetratingBefore << " -> " << r.penetratingAfter
            << " penetrating boundary vertices, deepest " << r.maxDepthBefore << " -> " << r.maxDepthAfter << " mm, "
            << r.rounds << " rounds, largest move " << r.maxDisplacement << " mm\n";

  const Depth after[2] = {depthInside(fits[0].surface, fits[1].surface), depthInside(fits[1].surface, fits[0].surface)};
  const Depth carriedAfter[2] = {depthInside(fits[0].carriedTemplate, fits[1].surface),
                                 depthInside(fits[1].carriedTemplate, fits[0].surface)};
  std::cout << tag << ": after, " << names[0] << " in " << names[1] << ": " << after[0] << "; " << names[1] << " in "
            << names[0] << ": " << after[1] << '\n';

  // The report measures what this test measures, on the tets.
  EXPECT_EQ(r.first, 0u);
  EXPECT_EQ(r.second, 1u);
  EXPECT_GT(r.penetratingBefore, 0);
  EXPECT_NEAR(r.maxDepthBefore, std::max(before[0].max, before[1].max), 1e-6);
  EXPECT_EQ(r.penetratingAfter, 0);
  EXPECT_EQ(r.maxDepthAfter, 0.0);
  for (int m = 0; m < 2; ++m) {
    SCOPED_TRACE(names[m]);
    const patient::OrganFit& f = fits[std::size_t(m)];
    // No vertex of either surface inside the other, beyond the clearance the vertices aim for.
    EXPECT_LE(after[m].max, separation.solver.clearance);
    // The surface is the moved tets' boundary.
    EXPECT_EQ(tetBoundarySurface(f.tets.V, f.tets.T).V, f.surface.V);
    const Eigen::VectorXd moved = (f.tets.V - unseparated[m].tets.V).rowwise().norm();
    const long movedVertices = long((moved.array() > 1e-9).count());
    const long movedTemplate =
        long(((f.carriedTemplate.V - unseparated[m].carriedTemplate.V).rowwise().norm().array() > 1e-9).count());
    const double diceAfter = dice(m);
    std::cout << tag << ": " << names[m] << ": " << movedVertices << " of " << f.tets.V.rows()
              << " tet vertices moved (largest " << moved.maxCoeff() << " mm), " << movedTemplate << " of "
              << f.carriedTemplate.V.rows() << " carried template vertices; carried template inside the other organ: "
              << carriedBefore[m] << " -> " << carriedAfter[m] << "; Dice " << diceBefore[m] << " -> " << diceAfter
              << '\n';
    EXPECT_EQ(f.carriedTemplate.F, unseparated[m].carriedTemplate.F);
    EXPECT_GE(diceAfter, diceBefore[m] - 0.01);
  }
}

INSTANTIATE_TEST_SUITE_P(TouchingPairs, OrganSeparation, ::testing::Values(0, 1),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return std::string(info.param == 0 ? "enlarged" : "shrunk") + "_" +
                                  touchingPairs()[std::size_t(info.param)].first + "_" +
                                  touchingPairs()[std::size_t(info.param)].second;
                         });

TetMesh shifted(TetMesh m, const Eigen::RowVector3d& by) {
  m.V.rowwise() += by;
  return m;
}

patient::OrganFit fitOf(const TetMesh& tets) {
  patient::OrganFit f;
  f.tets = tets;
  f.surface = tetBoundarySurface(tets.V, tets.T);
  f.carriedTemplate = f.surface;  // a template whose vertices are all tet corners is carried exactly
  return f;
}

// Three boxes: the second overlaps the first by 1 mm; the third touches neither.
TEST(OrganSeparation, MovesOnlyOrgansInContactAndCarriesTheirTemplates) {
  const TetMesh box = test::boxTets(6, 4, 4, 2.0);  // 12 x 8 x 8 mm
  patient::OrganFit a = fitOf(box), b = fitOf(shifted(box, {11.0, 0.5, 0.3})), c = fitOf(shifted(box, {0, 30, 0}));
  const patient::OrganFit cBefore = c;
  const std::vector<patient::OrganPairSeparation> report = patient::separateOrgans({&a, &b, &c});
  ASSERT_EQ(report.size(), 3u);  // (1,0), (2,0), (2,1)
  const patient::OrganPairSeparation& ab = report[0];
  std::cout << "boxes: " << ab.penetratingBefore << " -> " << ab.penetratingAfter << " penetrating vertices, deepest "
            << ab.maxDepthBefore << " -> " << ab.maxDepthAfter << " mm, largest move " << ab.maxDisplacement << " mm\n";
  EXPECT_EQ(ab.first, 0u);
  EXPECT_EQ(ab.second, 1u);
  EXPECT_GT(ab.penetratingBefore, 0);
  EXPECT_NEAR(ab.maxDepthBefore, 1.0, 1e-9);  // b's face 1 mm inside a
  EXPECT_EQ(ab.penetratingAfter, 0);
  EXPECT_EQ(ab.maxDepthAfter, 0.0);
  for (int p = 1; p < 3; ++p) {
    EXPECT_EQ(report[std::size_t(p)].penetratingBefore, 0);
    EXPECT_EQ(report[std::size_t(p)].penetratingAfter, 0);
  }
  for (const patient::OrganFit* f : {&a, &b}) {
    EXPECT_EQ(tetBoundarySurface(f->tets.V, f->tets.T).V, f->surface.V);
    EXPECT_LT((f->carriedTemplate.V - f->surface.V).cwiseAbs().maxCoeff(), 1e-9);
  }
  EXPECT_GT((a.surface.V - fitOf(box).surface.V).cwiseAbs().maxCoeff(), 0.1);
  EXPECT_EQ(c.tets.V, cBefore.tets.V);
  EXPECT_EQ(c.surface.V, cBefore.surface.V);
  EXPECT_EQ(c.carriedTemplate.V, cBefore.carriedTemplate.V);
}

TEST(OrganSeparation, RefusesAFitWithoutTets) {
  patient::OrganFit empty;
  patient::OrganFit* organs[] = {&empty, &empty};
  EXPECT_THROW(patient::separateOrgans({organs[0], organs[1]}), UsageError);
  EXPECT_THROW(patient::separateOrgans({organs[0], nullptr}), UsageError);
}

}  // namespace
}  // namespace vesalius::test
