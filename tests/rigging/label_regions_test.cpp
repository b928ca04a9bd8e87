// Region surfaces of a label map for TetGen (rigging/label_regions.h) when a label keeps handles that
// decimation may not remove: a "rib cage" of nine rings on a column (genus 9, 3 mm voxels) and a block
// beside it, nested in a body. With LabelRegionOptions::closeOverBudget the cage is closed until its
// surface is within twice its share of labelFaces; the block keeps its shape (its surface encloses the
// same volume) and no surface crosses another or encloses a point of another label's surface.
#include "vesalius/rigging/label_regions.h"

#include "vesalius/core/mesh_measures.h"
#include "vesalius/meshing/tetrahedralize.h"
#include "vesalius/meshing/winding_number.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

namespace vesalius::rigging {
namespace {

constexpr Label kCage = 1, kBlock = 2, kBody = 3;

LabelMap cageInBody() {
  GridGeometry g;
  g.size = {64, 64, 64};
  g.spacing = {3, 3, 3};
  LabelMap map;
  map.labels = Grid<Label>(g, 0);
  map.table.add({kCage, "cage", {230, 220, 200}});
  map.table.add({kBlock, "block", {200, 200, 230}});
  map.table.add({kBody, "body", {200, 150, 130}});
  for (int k = 4; k < 60; ++k)
    for (int j = 4; j < 60; ++j)
      for (int i = 4; i < 60; ++i) {
        Label l = kBody;
        const int dx = std::abs(2 * i - 63), dy = std::abs(2 * j - 63);  // twice the distance from the axis
        const bool ringLevel = k >= 10 && k <= 50 && (k - 10) % 5 < 2;
        const bool ring = ringLevel && std::max(dx, dy) >= 31 && std::max(dx, dy) <= 35;
        const bool column = k >= 8 && k <= 52 && dx <= 3 && j >= 47 && j <= 50;
        if (ring || column) l = kCage;
        if (i >= 53 && i <= 57 && j >= 28 && j <= 36 && k >= 20 && k <= 40) l = kBlock;
        map.labels.at(i, j, k) = l;
      }
  return map;
}

LabelRegionOptions options(bool close) {
  LabelRegionOptions o;
  o.body = kBody;
  o.largestBodyPartOnly = true;
  o.bodySurface.targetFaces = 1000;
  o.labelFaces = 100;
  o.closeOverBudget = close;
  return o;
}

const meshing::RegionSurface& region(const std::vector<meshing::RegionSurface>& regions, Label id) {
  for (const meshing::RegionSurface& r : regions)
    if (r.label == int(id)) return r;
  throw std::runtime_error("no region " + std::to_string(id));
}

TEST(LabelRegions, ACageThatDecimationCannotTakeIsClosedUntilItsSurfaceFits) {
  const LabelMap map = cageInBody();
  const std::vector<Label> ids{kBlock, kCage};
  const auto open = labelRegionSurfaces(map, ids, options(false), "cage");
  const auto closed = labelRegionSurfaces(map, ids, options(true), "cage");
  const TriMesh& cageOpen = region(open, kCage).surface;
  const TriMesh& cage = region(closed, kCage).surface;
  std::cout << "cage: " << cageOpen.F.rows() << " faces as it is, " << cage.F.rows() << " closed; labelFaces "
            << options(true).labelFaces << '\n';
  // The premise: its nine handles keep the cage's decimated surface above twice the labels' whole budget.
  ASSERT_GT(cageOpen.F.rows(), 2 * options(false).labelFaces);
  EXPECT_LE(cage.F.rows(), 2 * options(true).labelFaces);
  EXPECT_GT(enclosedVolume(cage.V, cage.F), enclosedVolume(cageOpen.V, cageOpen.F));
  const EdgeCounts edges = countEdges(cage.F);
  EXPECT_EQ(edges.boundary, 0);
  EXPECT_EQ(edges.nonManifold, 0);

  // The block beside it keeps its volume, and the regions stay apart: no crossing, no block vertex inside
  // the closed cage, every label inside the body.
  const TriMesh& blockOpen = region(open, kBlock).surface;
  const TriMesh& block = region(closed, kBlock).surface;
  const double before = enclosedVolume(blockOpen.V, blockOpen.F), after = enclosedVolume(block.V, block.F);
  std::cout << "block: " << before << " mm^3 beside the cage as it is, " << after << " beside it closed\n";
  EXPECT_NEAR(after, before, 1e-6 * before);
  EXPECT_FALSE(meshing::surfacesCross(closed));
  const Eigen::VectorXd inCage = meshing::windingNumbers(cage.V, cage.F, block.V);
  EXPECT_LT(inCage.maxCoeff(), 0.5);
  const TriMesh& body = region(closed, kBody).surface;
  for (const TriMesh* label : {&cage, &block})
    EXPECT_GT(meshing::windingNumbers(body.V, body.F, label->V).minCoeff(), 0.5);
}

}  // namespace
}  // namespace vesalius::rigging
