// The organ templates of templates/organs fitted by patient::fitOrganToLabel (Wang et al.'s plastic strains)
// to test patients that are not the templates' subjects: the shipped CT and its labels warped by a smooth,
// invertible field that scales chosen organs by up to ±15 % about their centroids and shifts them by
// 10–20 mm (warped_patient.h), so the kidney templates, made from this CT's labels, never meet their own
// label (the liver's is SOFA's, the spleen's the Visible Human Male's). Each fitted surface is voxelized
// on the warped grid and scored against the warped label, the ground truth: the Dice ≥ 0.90 and a
// mean distance from the label's boundary (inside the scan) to the fitted surface within one voxel. The
// settings are coarser than `vesalius patient`'s (fewer markers and tets) to keep the suite short.
#include "test_data.h"
#include "warped_patient.h"

#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/meshing/mesh_volume.h"
#include "vesalius/meshing/surface_samples.h"
#include "vesalius/patient/organ_fit.h"
#include "vesalius/segmentation/label_edit.h"
#include "vesalius/segmentation/label_ops.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

namespace vesalius::test {
namespace {

namespace fs = std::filesystem;

const std::string kTemplates = std::string(VESALIUS_TESTDATA) + "/../templates/organs";

struct TestPatient {
  std::string name;
  std::vector<OrganWarp> warps;
};

// Two patients that differ from the CT's subject in opposite ways, each organ scaled more along two axes
// than the third (so no similarity maps the template onto it). Shifts are 10–20 mm long. The CT cuts the
// liver and the spleen at its top slice: a shrunk one is shifted up enough, and none is shifted down, to
// keep that cut on the scan's face (where the warp pulled a label down from it, the label would end in a
// flat face inside the scan, which no organ has).
const std::vector<TestPatient>& testPatients() {
  static const std::vector<TestPatient> patients = {
      {"enlarged",
       {{"liver", {1.15, 1.05, 1.15}, {12, 0, 15}},
        {"kidney_right", {1.15, 1.15, 1.02}, {-10, 8, -10}},
        {"kidney_left", {1.02, 1.15, 1.15}, {10, 8, 10}},
        {"spleen", {1.15, 1.15, 1.02}, {8, 12, 0}}}},
      {"shrunk",
       {{"liver", {0.85, 0.95, 0.85}, {-12, 10, 8}},
        {"kidney_right", {0.85, 0.85, 0.98}, {8, -10, 12}},
        {"kidney_left", {0.98, 0.85, 0.85}, {-8, -10, 12}},
        {"spleen", {0.85, 0.85, 0.98}, {6, -10, 12}}}},

  };
  return patients;
}

// The organs of the template library, as `vesalius patient` finds them: every <organ>.obj.
std::vector<std::string> libraryOrgans() {
  std::vector<std::string> organs;
  for (const fs::directory_entry& e : fs::directory_iterator(kTemplates))
    if (e.path().extension() == ".obj") organs.push_back(e.path().stem().string());
  std::sort(organs.begin(), organs.end());
  return organs;
}

std::int64_t voxelsOf(const LabelMap& map, const std::string& organ) {
  return segmentation::countVoxels(segmentation::maskOf(map.labels, map.table.resolve(organ)));
}

TEST(WarpedPatient, AnOrgansCoreIsScaledAboutItsCentroidAndShiftedExactly) {
  const LabelMap labels = io::readLabelMap(kCtLabels, kCtLabelTable);
  const Label id = labels.table.resolve("kidney_left");
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  long n = 0;
  const GridGeometry& g = labels.labels.geometry;
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i)
        if (labels.labels.at(i, j, k) == id) c += g.indexToWorld(Eigen::Vector3d(i, j, k)), ++n;
  c /= double(n);
  const Eigen::Vector3d s(1.15, 0.9, 1.05), t(-6, 10, 12);
  const WarpField field(labels, {{"kidney_left", s, t}});
  // Points a few mm from the centroid stay where the weight is 1 all along their path.
  for (const Eigen::Vector3d& d : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(3, -2, 1), Eigen::Vector3d(-1, 4, -3)}) {
    const Eigen::Vector3d expected = c + s.cwiseProduct(d) + t;
    EXPECT_LT((field.forward(c + d) - expected).norm(), 1e-6) << d.transpose();
    EXPECT_LT((field.backward(expected) - (c + d)).norm(), 1e-6) << d.transpose();
  }
  // Far from the organ nothing moves.
  const Eigen::Vector3d far = c + Eigen::Vector3d(400, 0, 0);
  EXPECT_EQ(field.forward(far), far);
}

class OrganFitWarped : public ::testing::TestWithParam<int> {};

TEST_P(OrganFitWarped, LibraryOrgansFitTheWarpedLabels) {
  const TestPatient& patient = testPatients()[std::size_t(GetParam())];
  const Image ct = io::readScan(kCtScan);
  const LabelMap labels = io::readLabelMap(kCtLabels, kCtLabelTable);
  const WarpedPatient warped = warpPatient(ct, labels, patient.warps);
  const GridGeometry& g = warped.labels.labels.geometry;
  const double voxel = g.spacing.maxCoeff();

  // The field: invertible with a positive Jacobian, and its inverse is the one the images were resampled by.
  std::cout << patient.name << ": Jacobian of the warp " << warped.minJacobian << " … " << warped.maxJacobian << '\n';
  EXPECT_GT(warped.minJacobian, 0.0);
  const WarpField field(labels, patient.warps);
  double roundTrip = 0;
  for (int k = 0; k < g.size.z(); k += 7)
    for (int j = 0; j < g.size.y(); j += 7)
      for (int i = 0; i < g.size.x(); i += 7) {
        const Eigen::Vector3d y = g.indexToWorld(Eigen::Vector3d(i, j, k));
        roundTrip = std::max(roundTrip, (field.forward(field.backward(y)) - y).norm());
      }
  std::cout << patient.name << ": greatest |φ(φ⁻¹(y)) - y| " << roundTrip << " mm\n";
  EXPECT_LT(roundTrip, 0.01);

  // Each warped organ grew or shrank as its scale says; the CT moved with the labels (an organ's mean HU
  // changes only by the partial-volume voxels at its rim).
  const bool enlarged = patient.warps.front().scale.x() > 1;
  for (const OrganWarp& w : patient.warps) {
    const double ratio = double(voxelsOf(warped.labels, w.organ)) / double(voxelsOf(labels, w.organ));
    const auto meanHu = [](const Image& image, const LabelMap& map, const std::string& organ) {
      const Label id = map.table.resolve(organ);
      double sum = 0;
      long n = 0;
      for (std::size_t v = 0; v < image.values.size(); ++v)
        if (map.labels.values[v] == id) sum += image.values[v], ++n;
      return sum / double(n);
    };
    const double huBefore = meanHu(ct, labels, w.organ), huAfter = meanHu(warped.ct, warped.labels, w.organ);
    // An organ the scan cuts at its top slice is still cut there, not ended by a flat face inside the scan.
    const auto topSlice = [&](const LabelMap& map) {
      const Label id = map.table.resolve(w.organ);
      long n = 0;
      for (int j = 0; j < g.size.y(); ++j)
        for (int i = 0; i < g.size.x(); ++i) n += map.labels.at(i, j, g.size.z() - 1) == id;
      return n;
    };
    const long topBefore = topSlice(labels), topAfter = topSlice(warped.labels);
    std::cout << patient.name << " " << w.organ << ": voxels x" << ratio << ", mean HU " << huBefore << " -> "
              << huAfter << ", on the top slice " << topBefore << " -> " << topAfter << '\n';
    if (topBefore > 0) { EXPECT_GT(topAfter, topBefore / 2) << w.organ; }
    if (enlarged) { EXPECT_GT(ratio, 1.0) << w.organ; }
    else EXPECT_LT(ratio, 1.0) << w.organ;
    EXPECT_NEAR(huAfter, huBefore, 10.0) << w.organ;
  }

  // Every organ of the library that this patient warps, fitted to its warped label and scored against it
  // (an organ left in place could meet the scan its template was made from).
  std::vector<std::string> organs;
  for (const std::string& organ : libraryOrgans())
    for (const OrganWarp& w : patient.warps)
      if (w.organ == organ) organs.push_back(organ);
  for (const char* required : {"liver", "kidney_left", "kidney_right", "spleen"})
    ASSERT_NE(std::find(organs.begin(), organs.end(), required), organs.end()) << required;
  patient::OrganFitOptions options;
  options.markers = 200;
  options.targetTets = 2000;
  options.refits = 3;
  for (const std::string& organ : organs) {
    SCOPED_TRACE(patient.name + " " + organ);
    const LabelEntry* entry = warped.labels.table.find(organ);
    ASSERT_NE(entry, nullptr);
    const TriMesh templ = io::readTriMesh(kTemplates + "/" + organ + ".obj");
    const auto start = std::chrono::steady_clock::now();
    const patient::OrganFit fit = patient::fitOrganToLabel(templ, warped.labels, entry->id, options, "warped labels");
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    const segmentation::Mask truth = segmentation::maskOf(warped.labels.labels, entry->id);
    const double dice = segmentation::diceCoefficient(meshing::meshInsideMask(fit.surface, g), truth);
    // The label's boundary inside the scan (not the cap where the scan cuts it), sampled evenly.
    const TriMesh boundary = meshing::withinScan(meshing::labelSurface(warped.labels, entry->id), g);
    const MatrixX3d samples = meshing::spreadSurfacePoints(boundary, 2000, 7);
    const TriangleTree tree(fit.surface.V, fit.surface.F);
    double distance = 0;
    for (const ClosestPoint& c : tree.closest(samples)) distance += std::sqrt(c.squaredDistance);
    distance /= double(samples.rows());
    std::cout << patient.name << " " << organ << ": Dice " << dice << ", label boundary " << distance
              << " mm from the fitted surface (voxel " << voxel << " mm), markers " << fit.errorBefore.mean()
              << " -> " << fit.errorAfter.mean() << " mm (rounds:";
    for (const double e : fit.meanErrorPerRound) std::cout << ' ' << e;
    std::cout << "), tets " << fit.tetsPerRound.front() << ", " << seconds
              << " s\n";
    EXPECT_GE(dice, 0.90);
    EXPECT_LT(distance, voxel);
  }
}

// Each kidney of the warped patient with the scan cut through its middle (the grid kept from the kidney's
// centroid slice up), as a scan's field of view cuts an organ: the fit to the upper half is scored inside
// the cut scan as above, and the whole fitted kidney against the whole warped label, which the fit never
// saw: its volume and its Dice with the label on the uncut grid.
TEST_P(OrganFitWarped, AKidneyTheScanCutsKeepsItsSize) {
  const TestPatient& patient = testPatients()[std::size_t(GetParam())];
  const WarpedPatient warped =
      warpPatient(io::readScan(kCtScan), io::readLabelMap(kCtLabels, kCtLabelTable), patient.warps);
  const GridGeometry& g = warped.labels.labels.geometry;
  const double voxelVolume = g.spacing.prod();
  patient::OrganFitOptions options;
  options.markers = 200;
  options.targetTets = 2000;
  options.refits = 1;
  for (const char* organ : {"kidney_left", "kidney_right"}) {
    SCOPED_TRACE(patient.name + " " + organ);
    const Label id = warped.labels.table.resolve(organ);
    const segmentation::Mask truth = segmentation::maskOf(warped.labels.labels, id);
    const segmentation::VoxelBox bounds = segmentation::maskBounds(truth);
    segmentation::VoxelBox box;
    box.hi = g.size;
    box.lo.z() = (bounds.lo.z() + bounds.hi.z()) / 2;
    const LabelMap cut = segmentation::cropLabelMap(warped.labels, box);
    const TriMesh templ = io::readTriMesh(kTemplates + "/" + std::string(organ) + ".obj");
    const patient::OrganFit fit = patient::fitOrganToLabel(templ, cut, id, options, "cut labels");

    const double volume = enclosedVolume(fit.surface.V, fit.surface.F);
    const double labelVolume = double(segmentation::countVoxels(truth)) * voxelVolume;
    const double wholeDice = segmentation::diceCoefficient(meshing::meshInsideMask(fit.surface, g), truth);
    const segmentation::Mask cutTruth = segmentation::maskOf(cut.labels, id);
    const double cutDice =
        segmentation::diceCoefficient(meshing::meshInsideMask(fit.surface, cut.labels.geometry), cutTruth);
    std::cout << patient.name << " " << organ << " cut at slice " << box.lo.z() << " of " << bounds.lo.z() << " … "
              << bounds.hi.z() - 1 << ": Dice " << cutDice << " inside the cut scan, " << wholeDice
              << " with the whole label; volume " << volume / 1000 << " ml against the label's "
              << labelVolume / 1000 << " ml (x" << volume / labelVolume << "), markers " << fit.errorBefore.mean()
              << " -> " << fit.errorAfter.mean() << " mm\n";
    EXPECT_GE(cutDice, 0.90);
    EXPECT_NEAR(volume / labelVolume, 1.0, 0.2);
    EXPECT_GE(wholeDice, 0.85);
  }
}

INSTANTIATE_TEST_SUITE_P(TwoWarps, OrganFitWarped, ::testing::Values(0, 1),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return testPatients()[std::size_t(info.param)].name;
                         });

}  // namespace
}  // namespace vesalius::test
