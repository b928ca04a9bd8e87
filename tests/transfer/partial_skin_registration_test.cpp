// Registration of the whole neutral MakeHuman skin onto another MakeHuman body cropped to an abdomen-pelvis
// box, as a CT's field of view crops a patient (partial_skin_registration.h). The crop is capped where the
// box cut it and the caps are marked as the cut, as patient::scanSkin marks a CT's. The bodies share one
// topology, so outside the box the uncropped body (which the registration never sees) shows how far the
// continuation is from that person; it is printed, not asserted: a scan says nothing of the body beyond it.
// What is asserted is what the method promises: inside the box the skin within one voxel of the shipped
// CT (3 mm, testdata/ct-abdomen-pelvis) of the target, and everywhere a smooth continuation without folds.
#include "vesalius/transfer/partial_skin_registration.h"

#include "vesalius/core/error.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/io/body_axes.h"
#include "vesalius/io/mesh_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <map>
#include <numeric>

using namespace vesalius;
using namespace vesalius::transfer;

namespace {

const std::string kData = VESALIUS_TESTDATA;
constexpr double kVoxelMm = 3.0;  // the shipped CT's voxel

TriMesh body(const std::string& name) {
  TriMesh m = io::readTriMesh(kData + "/body/shapes/mh_" + name + "_body.obj");
  m.V = io::transformPoints(m.V, io::yUpToLps(), 100.0);  // decimetres, +Y up -> mm, LPS
  return m;
}

struct Cropped {
  TriMesh skin;           // the box's part of the body (its largest piece), capped
  std::vector<int> cut;   // the caps' vertices
  std::vector<int> kept;  // per cropped vertex (before the caps), the body's vertex
};

// The faces of `whole` with every corner in the S range [low, high] (and |L| <= halfWidth), their largest
// edge-connected piece, each boundary loop closed by a fan around its centroid; the loops' vertices and
// centroids are the cut.
Cropped cropToBox(const TriMesh& whole, double low, double high, double halfWidth) {
  const auto inside = [&](int v) {
    return whole.V(v, 2) >= low && whole.V(v, 2) <= high && std::abs(whole.V(v, 0)) <= halfWidth;
  };
  std::vector<Eigen::Index> faces;
  for (Eigen::Index f = 0; f < whole.F.rows(); ++f)
    if (inside(whole.F(f, 0)) && inside(whole.F(f, 1)) && inside(whole.F(f, 2))) faces.push_back(f);
  // Largest piece: union-find over the faces' vertices.
  std::vector<int> parent(std::size_t(whole.V.rows()));
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int v) {
    while (parent[std::size_t(v)] != v) v = parent[std::size_t(v)] = parent[std::size_t(parent[std::size_t(v)])];
    return v;
  };
  for (const Eigen::Index f : faces)
    for (int k = 1; k < 3; ++k) parent[std::size_t(find(whole.F(f, 0)))] = find(whole.F(f, k));
  std::map<int, int> size;
  for (const Eigen::Index f : faces) ++size[find(whole.F(f, 0))];
  const int largest = std::max_element(size.begin(), size.end(), [](auto& a, auto& b) { return a.second < b.second; })->first;
  Cropped c;
  std::vector<int> index(std::size_t(whole.V.rows()), -1);
  std::vector<Eigen::Vector3i> F;
  for (const Eigen::Index f : faces) {
    if (find(whole.F(f, 0)) != largest) continue;
    Eigen::Vector3i t;
    for (int k = 0; k < 3; ++k) {
      int& i = index[std::size_t(whole.F(f, k))];
      if (i < 0) {
        i = int(c.kept.size());
        c.kept.push_back(whole.F(f, k));
      }
      t[k] = i;
    }
    F.push_back(t);
  }
  // Boundary edges: directed edges whose reverse is absent; each loop walked by its next edge.
  std::map<std::pair<int, int>, int> directed;
  for (const Eigen::Vector3i& t : F)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  std::map<int, int> next;
  for (const auto& [e, count] : directed)
    if (!directed.count({e.second, e.first})) next[e.first] = e.second;
  std::vector<Eigen::RowVector3d> V;
  for (const int v : c.kept) V.push_back(whole.V.row(v));
  std::vector<char> used(V.size(), 0);
  for (const auto& [start, unused] : next) {
    if (used[std::size_t(start)]) continue;
    std::vector<int> loop;
    for (int v = start; !used[std::size_t(v)];) {
      used[std::size_t(v)] = 1;
      loop.push_back(v);
      const auto after = next.find(v);
      if (after == next.end()) break;
      v = after->second;
    }
    Eigen::RowVector3d centre = Eigen::RowVector3d::Zero();
    for (const int v : loop) centre += V[std::size_t(v)];
    const int middle = int(V.size());
    V.push_back(centre / double(loop.size()));
    for (std::size_t i = 0; i < loop.size(); ++i) {
      // The cap's triangle runs the boundary edge backwards, so it faces outwards as its neighbour does.
      F.push_back(Eigen::Vector3i(loop[(i + 1) % loop.size()], loop[i], middle));
      c.cut.push_back(loop[i]);
    }
    c.cut.push_back(middle);
  }
  c.skin.V.resize(Eigen::Index(V.size()), 3);
  for (std::size_t v = 0; v < V.size(); ++v) c.skin.V.row(Eigen::Index(v)) = V[v];
  c.skin.F.resize(Eigen::Index(F.size()), 3);
  for (std::size_t f = 0; f < F.size(); ++f) c.skin.F.row(Eigen::Index(f)) = F[f].transpose();
  std::sort(c.cut.begin(), c.cut.end());
  return c;
}

double percentile(std::vector<double> values, double p) {
  std::sort(values.begin(), values.end());
  return values[std::size_t(p * double(values.size() - 1))];
}

Eigen::Vector3d faceNormal(const MatrixX3d& V, const MatrixX3i& F, Eigen::Index f) {
  const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
  return (b - a).cross(c - a);
}

// The box of an abdomen-pelvis CT on a standing body: from the upper thighs to the lower ribs, as
// fractions of the body's height from its foot; wide enough for the trunk, not for the arms.
constexpr double kBoxLow = 0.46, kBoxHigh = 0.66, kBoxHalfWidthMm = 200;

}  // namespace

// Targets of other shapes than the source (thin: 81 mm taller; muscular), each cropped to the box.
class PartialSkinRegistrationBodies : public ::testing::TestWithParam<const char*> {};

TEST_P(PartialSkinRegistrationBodies, FitsTheBoxAndContinuesSmoothlyBeyondIt) {
  const TriMesh source = body("neutral"), whole = body(GetParam());
  const double foot = whole.V.col(2).minCoeff(), height = whole.V.col(2).maxCoeff() - foot;
  const Cropped target = cropToBox(whole, foot + kBoxLow * height, foot + kBoxHigh * height, kBoxHalfWidthMm);
  ASSERT_GT(target.cut.size(), 0u);
  ASSERT_LT(target.skin.V.rows(), whole.V.rows() / 2);

  PartialSkinRegistrationOptions options;
  options.registration.iterations = 20;
  const PartialSkinRegistration r =
      registerSkinToPartialTarget(source.V, source.F, target.skin.V, target.skin.F, target.cut, options);
  ASSERT_EQ(r.V.rows(), source.V.rows());
  ASSERT_EQ(r.pulled.size(), std::size_t(source.V.rows()));

  // Inside the box: the target's skin (not its caps) to the completed skin.
  std::vector<char> cut(std::size_t(target.skin.V.rows()), 0);
  for (const int v : target.cut) cut[std::size_t(v)] = 1;
  std::vector<Eigen::Index> skinRows;
  for (Eigen::Index v = 0; v < target.skin.V.rows(); ++v)
    if (!cut[std::size_t(v)]) skinRows.push_back(v);
  std::vector<double> toCompleted;
  for (const ClosestPoint& c : TriangleTree(r.V, source.F).closest(MatrixX3d(target.skin.V(skinRows, Eigen::all))))
    toCompleted.push_back(std::sqrt(c.squaredDistance));
  const double mean = std::accumulate(toCompleted.begin(), toCompleted.end(), 0.0) / double(toCompleted.size());
  const double p95 = percentile(toCompleted, 0.95);

  // The true correspondence of the body's vertices inside the box and outside it.
  std::vector<char> inBox(std::size_t(whole.V.rows()), 0);
  for (std::size_t i = 0; i < target.kept.size(); ++i)
    if (!cut[i]) inBox[std::size_t(target.kept[i])] = 1;
  double insideError = 0, outsideError = 0;
  long insideCount = 0, outsideCount = 0, pulled = 0, pulledOutsideBox = 0;
  const std::vector<ClosestPoint> toTruth = TriangleTree(whole.V, whole.F).closest(r.V);
  double outsideSurface = 0;
  for (Eigen::Index v = 0; v < whole.V.rows(); ++v) {
    const double e = (r.V.row(v) - whole.V.row(v)).norm();
    pulled += r.pulled[std::size_t(v)];
    pulledOutsideBox += r.pulled[std::size_t(v)] && !inBox[std::size_t(v)];
    if (inBox[std::size_t(v)]) {
      insideError += e;
      ++insideCount;
    } else {
      outsideError += e;
      outsideSurface += std::sqrt(toTruth[std::size_t(v)].squaredDistance);
      ++outsideCount;
    }
  }

    // Flipped: turned against the source's own triangle, moved as the alignment and continuation moved it.
  // The continuation (faces with a vertex no pair reached) must turn none; the registered part no more
  // than §4's registration of the whole source onto the whole body turns there (its own folds, which the
  // partial target does not add to).
  const auto turned = [&](const MatrixX3d& X, const MatrixX3d& reference, Eigen::Index f) {
    return faceNormal(X, source.F, f).dot(faceNormal(reference, source.F, f)) < 0;
  };
  const MatrixX3d moved = r.continuation.apply(MatrixX3d(source.V * r.alignmentLinear.transpose()));
  const SkinRegistration wholeRegistration = registerSkin(source.V, source.F, whole.V, whole.F, options.registration);
  const MatrixX3d wholeMoved = wholeRegistration.alignment.apply(source.V);
  long flippedContinued = 0, flippedPulled = 0, flippedWhole = 0;
  double smallestRatio = 1e9, largestRatio = 0;
  for (Eigen::Index f = 0; f < source.F.rows(); ++f) {
    const bool allPulled = r.pulled[std::size_t(source.F(f, 0))] && r.pulled[std::size_t(source.F(f, 1))] &&
                           r.pulled[std::size_t(source.F(f, 2))];
    (allPulled ? flippedPulled : flippedContinued) += turned(r.V, moved, f);
    flippedWhole += turned(wholeRegistration.V, wholeMoved, f);
    // No edge of the continuation (both ends unreached) more than halved or doubled from the source: the bodies differ in girth
    // by far less, and a continuation that stretches an edge twofold tears or folds the skin.
    for (int k = 0; k < 3 && !allPulled; ++k) {
      const int a = source.F(f, k), b = source.F(f, (k + 1) % 3);
      const double rest = (source.V.row(a) - source.V.row(b)).norm();
      if (rest <= 1e-9 || r.pulled[std::size_t(a)] || r.pulled[std::size_t(b)]) continue;
      const double ratio = (r.V.row(a) - r.V.row(b)).norm() / rest;
      smallestRatio = std::min(smallestRatio, ratio);
      largestRatio = std::max(largestRatio, ratio);
    }
  }

  std::cout << GetParam() << ": target " << target.skin.V.rows() << " vertices (" << target.cut.size()
            << " on the cut); alignment " << r.alignmentMeanDistance << " mm, girth scale " << r.girthScale
            << "; skin inside the box to the completed skin: mean " << mean << " mm, 95th percentile " << p95
            << " mm, max " << r.skinMaxDistance << " mm; pulled " << pulled << " source vertices (" << pulledOutsideBox
            << " outside the box); true correspondence error inside " << insideError / double(insideCount)
            << " mm, outside " << outsideError / double(outsideCount) << " mm (to the true surface "
            << outsideSurface / double(outsideCount) << " mm); flipped triangles: continuation " << flippedContinued << ", registered part " << flippedPulled
            << " (whole-body registration " << flippedWhole << "); continuation's edge ratios " << smallestRatio
            << " .. " << largestRatio << "\n";
  EXPECT_LE(mean, kVoxelMm);
  EXPECT_LE(p95, kVoxelMm);
  EXPECT_EQ(flippedContinued, 0);
  EXPECT_LE(flippedPulled, flippedWhole);
  EXPECT_GE(smallestRatio, 0.5);
  EXPECT_LE(largestRatio, 2.0);
}

INSTANTIATE_TEST_SUITE_P(MakeHuman, PartialSkinRegistrationBodies,
                         ::testing::Values("male_young_thin", "male_young_muscular"));

// Every vertex on the cut: nothing pulls. Bad options and indices are refused.
TEST(PartialSkinRegistration, RejectsBadInputAndOptions) {
  const TriMesh source = body("neutral");
  const TriMesh whole = body("male_young_thin");
  std::vector<int> all(std::size_t(whole.V.rows()));
  std::iota(all.begin(), all.end(), 0);
  EXPECT_THROW(registerSkinToPartialTarget(source.V, source.F, whole.V, whole.F, all), BadInput);
  EXPECT_THROW(registerSkinToPartialTarget(source.V, source.F, whole.V, whole.F, {int(whole.V.rows())}), BadInput);
  EXPECT_THROW(registerSkinToPartialTarget(source.V, source.F, whole.V, whole.F, {-1}), BadInput);
  PartialSkinRegistrationOptions o;
  o.alignmentStarts = 0;
  EXPECT_THROW(registerSkinToPartialTarget(source.V, source.F, whole.V, whole.F, {}, o), UsageError);
  o = {};
  o.startsFrom = 0.9;
  o.startsTo = 0.1;
  EXPECT_THROW(registerSkinToPartialTarget(source.V, source.F, whole.V, whole.F, {}, o), UsageError);
  o = {};
  o.registration.iterations = 0;
  EXPECT_THROW(registerSkinToPartialTarget(source.V, source.F, whole.V, whole.F, {}, o), UsageError);
  o = {};
  o.refinedStarts = 0;
  EXPECT_THROW(registerSkinToPartialTarget(source.V, source.F, whole.V, whole.F, {}, o), UsageError);
  o = {};
  o.settledMm = 0;
  EXPECT_THROW(registerSkinToPartialTarget(source.V, source.F, whole.V, whole.F, {}, o), UsageError);
}
