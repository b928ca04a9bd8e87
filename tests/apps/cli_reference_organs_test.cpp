// The full-body reference's organs and muscles (templates/reference-organs/, `vesalius reference organs`;
// patient/reference_organs.h) in the reference and in the virtual patient (issue 30, item 3):
//  - `reference full-body --organ-meshes` holds them inside its skin (every vertex, by winding number); how
//    deep they reach into the reference's bones (interpenetration as transfer::checkAnatomyRules measures
//    it) is printed, not bounded: the muscles lie on the CT's own hip bones, not on OpenSim's
//    (docs/virtual-patient.md, "Not yet");
//  - with --reference-organs and without --organs on the shipped CT the model holds the reference's organs
//    and gluteal muscles; the reference's liver voxelized on the CT's grid is scored against the CT's liver
//    label and the Dice printed, never bounded: the reference's liver was made from this very CT;
//  - with --organs (and --reference-organs) on the CT cut below its liver (a scan of the pelvis), the organ map's tissues are the
//    patient's, the reference's organs the map lacks (the liver, the spleen) are in the model, and no
//    tissue is there twice;
//  - the shipped organs in another MakeHuman body's skin are refused (they were made for the neutral body).
#include "fit_ct_support.h"

#include "vesalius/io/reference_anatomy_io.h"
#include "vesalius/meshing/winding_mask.h"
#include "vesalius/meshing/winding_number.h"
#include "vesalius/segmentation/label_ops.h"
#include "vesalius/transfer/anatomy_rules.h"

#include <gtest/gtest.h>

#include <iostream>
#include <set>

namespace vesalius::test {
namespace {

namespace fs = std::filesystem;

const std::string kReferenceOrgans = std::string(VESALIUS_TESTDATA) + "/../templates/reference-organs";

std::string fresh(const std::string& name) {
  const std::string dir = outputPath("reference_organs", name);
  fs::remove_all(dir);
  return dir;
}

const ReferenceTissue* find(const ReferenceAnatomy& a, const std::string& name) {
  for (const ReferenceTissue& t : a.tissues)
    if (t.name == name) return &t;
  return nullptr;
}

// Every tissue name once: a label's tissue takes the reference's place, it is not added beside it.
void expectNamesOnce(const ReferenceAnatomy& a) {
  std::set<std::string> names;
  for (const ReferenceTissue& t : a.tissues) EXPECT_TRUE(names.insert(t.name).second) << t.name << " twice";
}

// Organ and muscle vertices outside the skin (winding number below 1/2), of how many.
std::pair<long, long> softOutsideSkin(const ReferenceAnatomy& a) {
  long outside = 0, all = 0;
  for (const ReferenceTissue& t : a.tissues) {
    if (t.kind != TissueKind::Organ && t.kind != TissueKind::Muscle) continue;
    const Eigen::VectorXd w = meshing::windingNumbers(a.skin.V, a.skin.F, t.mesh.V);
    outside += long((w.array() < 0.5).count());
    all += long(w.size());
  }
  return {outside, all};
}

// Slices [k0, k1) of a grid along k: the same voxels, the origin moved to slice k0.
template <class T>
Grid<T> slices(const Grid<T>& g, int k0, int k1) {
  GridGeometry geometry = g.geometry;
  geometry.size.z() = k1 - k0;
  geometry.origin = g.geometry.indexToWorld(Eigen::Vector3d(0, 0, k0));
  Grid<T> out(geometry);
  for (int k = k0; k < k1; ++k)
    for (int j = 0; j < geometry.size.y(); ++j)
      for (int i = 0; i < geometry.size.x(); ++i) out.at(i, j, k - k0) = g.at(i, j, k);
  return out;
}

bool isSoft(const ReferenceTissue& t) { return t.kind == TissueKind::Organ || t.kind == TissueKind::Muscle; }

TEST(CliReferenceOrgans, InsideTheReferenceSkinAndOffItsBones) {
  const std::string out = fresh("full_body");
  const std::string body = std::string(VESALIUS_TESTDATA) + "/body/";
  const CommandResult r = runVesalius({"reference", "full-body", "--skin", body + "shapes/mh_neutral_body.obj",
                                       "--skeleton", body + "default.mhskel", "--model",
                                       std::string(VESALIUS_TESTDATA) + "/skeleton-opensim/Rajagopal2016.osim",
                                       "--organ-meshes", kReferenceOrgans, "--out", out, "--progress", "none"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const ReferenceAnatomy reference = io::readReferenceAnatomy(out);
  expectNamesOnce(reference);
  for (const char* name : {"liver", "kidney_left", "kidney_right", "spleen", "gluteus_maximus_left", "gluteus_maximus_right"})
    EXPECT_NE(find(reference, name), nullptr) << name;
  const auto [outside, all] = softOutsideSkin(reference);
  std::cout << "organ and muscle vertices outside the reference's skin: " << outside << " of " << all << '\n';
  EXPECT_GT(all, 0);
  EXPECT_EQ(outside, 0);
  // Interpenetration of each organ or muscle with each bone (no reference pair: measured against 0);
  // Dicko et al.'s 1 mm is not met yet (docs/virtual-patient.md, "Not yet").
  ReferenceAnatomy bones = reference;
  bones.tissues.erase(std::remove_if(bones.tissues.begin(), bones.tissues.end(), isSoft), bones.tissues.end());
  transfer::AnatomyRulesOptions options;
  options.outside = options.folds = options.symmetry = options.straightness = false;
  const transfer::AnatomyRules rules = transfer::checkAnatomyRules(bones, reference, nullptr, options);
  int pairs = 0, deeper = 0;
  for (const transfer::Interpenetration& p : rules.interpenetration.pairs) {
    const ReferenceTissue &a = reference.tissues[std::size_t(p.a)], &b = reference.tissues[std::size_t(p.b)];
    if (isSoft(a) == isSoft(b)) continue;
    std::cout << a.name << " / " << b.name << ": " << p.depthMm << " mm\n";
    ++pairs;
    deeper += p.depthMm > options.interpenetrationToleranceMm;
  }
  std::cout << pairs << " organ-bone pairs touching, " << deeper << " deeper than "
            << options.interpenetrationToleranceMm << " mm\n";
}

TEST(CliReferenceOrgans, PatientWithoutOrgansHoldsTheReferences) {
  const std::string out = fresh("without_organs");
  const CommandResult r = runVesalius({"patient", "--scan", kCtScan, "--reference-organs", "--out", out, "--progress", "none"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const ReferenceAnatomy model = io::readReferenceAnatomy(out + "/anatomy");
  expectNamesOnce(model);
  for (const auto& [name, kind] : std::vector<std::pair<std::string, TissueKind>>{
           {"liver", TissueKind::Organ}, {"kidney_left", TissueKind::Organ}, {"kidney_right", TissueKind::Organ},
           {"spleen", TissueKind::Organ}, {"urinary_bladder", TissueKind::Organ},
           {"gluteus_maximus_left", TissueKind::Muscle}, {"gluteus_maximus_right", TissueKind::Muscle}}) {
    const ReferenceTissue* t = find(model, name);
    ASSERT_NE(t, nullptr) << name;
    EXPECT_EQ(t->kind, kind) << name;
  }
  const auto [outside, all] = softOutsideSkin(model);
  std::cout << "organ and muscle vertices outside the model's skin: " << outside << " of " << all << '\n';
  // Reported, no bound: the reference's liver came from this CT's liver label.
  const LabelMap labels = io::readLabelMap(kCtLabels, kCtLabelTable);
  const Grid<std::uint8_t> liver = meshing::windingNumberMask(find(model, "liver")->mesh, labels.labels.geometry);
  const double dice = segmentation::diceCoefficient(liver, segmentation::maskOf(labels.labels, labels.table.resolve("liver")));
  std::cout << "the reference's liver in the patient against the CT's liver label: Dice " << dice << '\n';
  EXPECT_GT(segmentation::countVoxels(liver), 0);
}

TEST(CliReferenceOrgans, LabelledOrgansTakeTheReferencesPlace) {
  // The CT cut below its liver's lowest slice, on the side of the hips: a pelvic scan without liver voxels.
  const Image ct = io::readScan(kCtScan);
  const LabelMap labels = io::readLabelMap(kCtLabels, kCtLabelTable);
  const Label liverId = labels.table.resolve("liver"), hipId = labels.table.resolve("hip_left");
  int liverLow = ct.geometry.size.z(), liverHigh = -1, hipLow = ct.geometry.size.z();
  for (int k = 0; k < ct.geometry.size.z(); ++k)
    for (int j = 0; j < ct.geometry.size.y(); ++j)
      for (int i = 0; i < ct.geometry.size.x(); ++i) {
        const Label l = labels.labels.at(i, j, k);
        if (l == liverId) liverLow = std::min(liverLow, k), liverHigh = std::max(liverHigh, k);
        if (l == hipId) hipLow = std::min(hipLow, k);
      }
  const bool hipsBelow = hipLow < liverLow;
  const int k0 = hipsBelow ? 0 : liverHigh + 1, k1 = hipsBelow ? liverLow : ct.geometry.size.z();
  ASSERT_GT(k1 - k0, 20);
  const std::string dir = fresh("pelvis_inputs");
  fs::create_directories(dir);
  Image cropped;
  static_cast<Grid<float>&>(cropped) = slices(static_cast<const Grid<float>&>(ct), k0, k1);
  cropped.fileType = ct.fileType;
  LabelMap croppedLabels{slices(labels.labels, k0, k1), labels.table};
  io::writeScan(dir + "/ct.nii.gz", cropped);
  io::writeLabelMap(dir + "/labels.nii.gz", croppedLabels);
  std::cout << "slices " << k0 << " to " << k1 << " of " << ct.geometry.size.z() << '\n';

  const std::string out = fresh("pelvis");
  const CommandResult r = runVesalius({"patient", "--scan", dir + "/ct.nii.gz", "--organs", dir + "/labels.nii.gz",
                                       "--organ-table", kCtLabelTable, "--reference-organs", "--refits", "0",
                                       "--organ-tets", "2000", "--out", out, "--progress", "none"});  // coarse fits
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const ReferenceAnatomy model = io::readReferenceAnatomy(out + "/anatomy");
  const ReferenceAnatomy scan = io::readReferenceAnatomy(out + "/scan_anatomy");
  const nlohmann::json m = readJson(out + "/report.json")["metrics"];
  expectNamesOnce(model);
  // The map has no liver: the model's liver is the reference's, the report maps no label to it.
  ASSERT_EQ(find(scan, "liver"), nullptr);
  ASSERT_NE(find(model, "liver"), nullptr);
  EXPECT_FALSE(m["label_tissues"].contains("liver"));
  // The map's muscles and organs are the patient's label surfaces, in place of the reference's.
  int patients = 0;
  for (const ReferenceTissue& t : scan.tissues) {
    if (t.kind != TissueKind::Organ && t.kind != TissueKind::Muscle) continue;
    const ReferenceTissue* inModel = find(model, t.name);
    ASSERT_NE(inModel, nullptr) << t.name;
    EXPECT_EQ(inModel->mesh.V.rows(), t.mesh.V.rows()) << t.name;
    EXPECT_TRUE(inModel->mesh.V.isApprox(t.mesh.V, 1e-9)) << t.name;
    ++patients;
  }
  std::cout << patients << " organs and muscles of the map in the model; " << model.tissues.size() << " tissues\n";
  EXPECT_NE(find(scan, "gluteus_maximus_left"), nullptr);
}

TEST(CliReferenceOrgans, RefusedInAnotherBody) {
  const std::string out = fresh("thin");
  const std::string body = std::string(VESALIUS_TESTDATA) + "/body/";
  const CommandResult r = runVesalius({"reference", "full-body", "--skin", body + "shapes/mh_male_young_thin_body.obj",
                                       "--skeleton", body + "default.mhskel", "--model",
                                       std::string(VESALIUS_TESTDATA) + "/skeleton-opensim/Rajagopal2016.osim",
                                       "--organ-meshes", kReferenceOrgans, "--out", out, "--progress", "none"});
  EXPECT_EQ(r.exitCode, 3) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  expectContains(r.err, "reference-organs");
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace vesalius::test
