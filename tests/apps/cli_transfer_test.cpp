// `vesalius reference torso` and `vesalius transfer` on the test CT (Dicko et al. 2013): the torso reference built
// from TotalSegmentator's labels, carried into its own body, into the same body with 8 mm more fat, and
// into a wider, flatter body made from the same scan. The rules as numbers: tissues inside the target
// (R5, R6), the same bones under extra fat (R3), long bones straight (R1), the trunk symmetric (R2), a
// field that folds nowhere.
#include "run_command.h"
#include "test_ct_bodies.h"
#include "test_remeshed_surface.h"

#include "vesalius/core/triangle_tree.h"
#include "vesalius/io/body_axes.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/marker_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/reference_anatomy_io.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <iostream>
#include <limits>

namespace vesalius::test {
namespace {

namespace fs = std::filesystem;

const std::string kCt = std::string(VESALIUS_TESTDATA) + "/ct-abdomen-pelvis/";

std::string freshDir(const std::string& test) {
  const fs::path d = fs::path(VESALIUS_TEST_OUTPUT) / "transfer" / test;
  fs::remove_all(d);
  fs::create_directories(d);
  return d.string();
}

std::string buildReference(const std::string& dir) {
  const std::string out = dir + "/reference";
  const CommandResult r = runVesalius({"reference", "torso", "--scan", kCt + "example_ct.nii.gz", "--labels",
                                       kCt + "example_seg_total_v1_for_example_ct.nii.gz", "--label-table",
                                       kCt + "labels_total_v1.tsv", "--out", out, "--progress", "none"});
  EXPECT_EQ(r.exitCode, 0) << r.err;
  return out;
}

// The body of the test CT surfaced after `dilateMm` of extra tissue, its spacing scaled by `stretch`.
std::string bodySurface(const std::string& dir, double dilateMm, const Eigen::Vector3d& stretch) {
  return ctBodySurface(kCt + "example_ct.nii.gz", dir, dilateMm, stretch);
}

// `fat`: as `--fat` takes it, a thickness in mm or a file.
nlohmann::json transfer(const std::string& reference, const std::string& target, const std::string& out,
                        const std::string& fat, const std::vector<std::string>& more = {}) {
  std::vector<std::string> args{"transfer", "--reference", reference, "--target-skin", target, "--fat",
                                fat, "--voxel-size", "4", "--out", out, "--report",
                                out + ".json", "--progress", "none"};
  args.insert(args.end(), more.begin(), more.end());
  const CommandResult r = runVesalius(args);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  std::ifstream in(out + ".json");
  return nlohmann::json::parse(in);
}

// Mean distance (mm) from the vertices of each bone in `a` to the same bone's surface in `b`, the largest
// over the bones.
double worstBoneDistance(const ReferenceAnatomy& a, const ReferenceAnatomy& b) {
  double worst = 0;
  for (std::size_t t = 0; t < a.tissues.size(); ++t) {
    if (a.tissues[t].kind != TissueKind::Bone) continue;
    const TriangleTree tree(b.tissues[t].mesh.V, b.tissues[t].mesh.F);
    double sum = 0;
    for (const ClosestPoint& c : tree.closest(a.tissues[t].mesh.V)) sum += std::sqrt(c.squaredDistance);
    worst = std::max(worst, sum / double(a.tissues[t].mesh.V.rows()));
  }
  return worst;
}

// R2: the trunk no less symmetric than the reference (by 1 mm).
void expectSymmetric(const nlohmann::json& boneGroups) {
  for (const nlohmann::json& group : boneGroups) {
    if (!group.contains("mirror_asymmetry_mm")) continue;
    const nlohmann::json& d = group["mirror_asymmetry_mm"];
    EXPECT_LT(d["registered"].get<double>(), d["reference"].get<double>() + 1.0) << group["group"];
  }
}

// R1: long bones (the report measures their centre lines only) no more bent than the reference's (by 1 %
// of their length); R2 (expectSymmetric). Returns how many long bones were checked.
int expectStraightAndSymmetric(const nlohmann::json& boneGroups) {
  int longBones = 0;
  for (const nlohmann::json& group : boneGroups) {
    if (!group.contains("centre_line_deviation")) continue;
    for (const auto& [bone, d] : group["centre_line_deviation"].items()) {
      EXPECT_LT(d["registered"].get<double>(), d["reference"].get<double>() + 0.01) << bone;
      ++longBones;
    }
  }
  expectSymmetric(boneGroups);
  return longBones;
}

// R5, R6 on the torso CT, cut at the top and bottom of the scan: the tissues flush with a cut cross it by
// up to a voxel (lungs, liver, spleen at the top slice, the femurs at the bottom one), in the reference
// (measured 1,023 of 66,400 vertices, by at most 1.2 mm) and so in the target, but none leaves through the
// skin.
void expectNoneOutsideThroughTheSkin(const nlohmann::json& m) {
  std::cout << "outside the reference " << m["reference_outside_vertices"] << " (at a cut "
            << m["reference_outside_at_cut_vertices"] << "), outside the target " << m["target_outside_vertices"]
            << " (at a cut " << m["target_outside_at_cut_vertices"] << ")\n";
  EXPECT_GT(m["target_outside_at_cut_vertices"].get<long>(), 0);  // the check sees the cut
  EXPECT_EQ(m["reference_outside_vertices"].get<long>(), m["reference_outside_at_cut_vertices"].get<long>());
  EXPECT_EQ(m["target_outside_vertices"].get<long>(), m["target_outside_at_cut_vertices"].get<long>());
}

}  // namespace

TEST(CliTransfer, TorsoReferenceFromTheLabelledCt) {
  const std::string dir = freshDir("reference");
  const ReferenceAnatomy reference = io::readReferenceAnatomy(buildReference(dir));
  EXPECT_EQ(reference.tissues.size(), 59u);
  int bones = 0, symmetric = 0;
  for (const ReferenceTissue& t : reference.tissues) bones += t.kind == TissueKind::Bone, symmetric += t.symmetric;
  EXPECT_EQ(bones, 24);
  EXPECT_EQ(symmetric, 22);  // the trunk: 7 vertebrae, 12 ribs, the pelvis (both hips, sacrum); not the femurs
  // The sagittal plane from the left/right pairs: within 3° of the scan's L axis, through the spine.
  EXPECT_GT(reference.sagittal.normal.x(), std::cos(3.0 * M_PI / 180));
  const io::TriMeshSummary skin = io::summarize(reference.skin);
  EXPECT_EQ(skin.boundaryEdges, 0);
}

// A label map without a left/right pair (the tissue classes `segment` gives the 3-slice CT) has no sagittal
// plane: refused in one line naming it, with nothing written.
TEST(CliTransfer, TorsoReferenceWithoutALeftRightPairIsRefused) {
  const std::string dir = freshDir("no-pairs");
  const std::string ct = std::string(VESALIUS_TESTDATA) + "/dicom/ct-3slice-dcmqi/ct-3slice";
  const std::string classes = dir + "/classes.nii.gz", out = dir + "/reference";
  ASSERT_EQ(runVesalius({"segment", "--scan", ct, "--out", classes, "--progress", "none"}).exitCode, 0);
  const CommandResult r =
      runVesalius({"reference", "torso", "--scan", ct, "--labels", classes, "--out", out, "--progress", "none"});
  std::cout << r.err;
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_EQ(r.err, "vesalius: " + classes + ": no left/right pair of labels to find the sagittal plane from\n");
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliTransfer, TheSameBodyGivesTheSameAnatomy) {
  const std::string dir = freshDir("same");
  const std::string reference = buildReference(dir);
  const nlohmann::json report = transfer(reference, reference + "/skin.obj", dir + "/out", "0");
  const ReferenceAnatomy a = io::readReferenceAnatomy(reference), b = io::readReferenceAnatomy(dir + "/out");
  EXPECT_LT(worstBoneDistance(b, a), 0.05);
  EXPECT_GT(report["metrics"]["jacobian_min"].get<double>(), 0.99);
  expectNoneOutsideThroughTheSkin(report["metrics"]);
}

// R3 as Dicko et al. 2013 states it: the same body with more fat has the same skeleton. The lean body is the
// test CT's body surfaced anew; the fat one is its mask dilated by 8 mm, surfaced the same way. The fat
// layer, the distance from each reference skin vertex out to the fat body, is what a forest would measure
// on such a scan (a dilation on 3 mm voxels is 6.9 mm at the median, not 8); the transfer is given it per
// vertex.
TEST(CliTransfer, ExtraFatKeepsTheBones) {
  const std::string dir = freshDir("fat");
  const std::string reference = buildReference(dir);
  const ReferenceAnatomy a = io::readReferenceAnatomy(reference);
  fs::create_directories(dir + "/lean");
  fs::create_directories(dir + "/fat");
  transfer(reference, bodySurface(dir + "/lean", 0.0, Eigen::Vector3d::Ones()), dir + "/lean/out", "0");
  const std::string target = bodySurface(dir + "/fat", 8.0, Eigen::Vector3d::Ones());
  writeFatLayer(a.skin, target, dir + "/fat.txt");
  const nlohmann::json report = transfer(reference, target, dir + "/fat/out", dir + "/fat.txt");
  const ReferenceAnatomy lean = io::readReferenceAnatomy(dir + "/lean/out"), fatter = io::readReferenceAnatomy(dir + "/fat/out");
  // The eroded fat body should be the lean body's skin again.
  const TriMesh eroded = io::readTriMesh(dir + "/fat/out/eroded_skin.obj");
  const TriangleTree skin(lean.skin.V, lean.skin.F);
  double sum = 0;
  for (const ClosestPoint& c : skin.closest(eroded.V)) sum += std::sqrt(c.squaredDistance);
  const double erodedToLean = sum / double(eroded.V.rows());
  std::cout << "eroded skin to the lean skin: " << erodedToLean << " mm; worst bone: " << worstBoneDistance(fatter, lean)
            << " mm; Jacobian min " << report["metrics"]["jacobian_min"] << " at " << report["metrics"]["jacobian_min_at"] << "\n";
  EXPECT_LT(erodedToLean, 1.0);
  // Measured 0.68 mm (eroded skin 0.78 mm from the lean one). Before the reference was registered again
  // onto the eroded skin, 1.15 mm: erosion moved the registered skin back along its normals only, and the
  // registration onto the fatter body had scaled and stretched it along the surface, which carried into
  // the bones by about 1 % (docs/methods/anatomy-transfer.md).
  EXPECT_LT(worstBoneDistance(fatter, lean), 1.0);
  // The field folds nowhere (measured: det min 0.22; before, one cell at the skin shell, det −0.09).
  EXPECT_GT(report["metrics"]["jacobian_min"].get<double>(), 0.0);
  EXPECT_GT(report["metrics"]["jacobian_interior_min"].get<double>(), 0.0);
  expectNoneOutsideThroughTheSkin(report["metrics"]);
}

// §4's optional landmark initialisation: the reference's own skin turned 150° about the body's long axis
// is a target that the alignment from the centroids and similarity ICP turns the wrong way; six landmarks
// (the skin vertices at the body's extremes and their turned places) start it right, and the transfer
// gives the turned anatomy.
TEST(CliTransfer, LandmarksStartTheRegistrationOnATurnedBody) {
  const std::string dir = freshDir("turned");
  const std::string reference = buildReference(dir);
  const ReferenceAnatomy a = io::readReferenceAnatomy(reference);
  const Eigen::RowVector3d centre = a.skin.V.colwise().mean();
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(150.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const auto turned = [&](const MatrixX3d& V) -> MatrixX3d {
    return ((V.rowwise() - centre) * turn.transpose()).rowwise() + centre;
  };
  TriMesh target = a.skin;
  target.V = turned(a.skin.V);
  io::writeTriMesh(dir + "/turned.obj", target);
  const auto landmark = [](const std::string& label, const Eigen::Vector3d& position) {
    Marker m;  // a defined landmark
    m.label = label;
    m.position = position;
    return m;
  };
  MarkerSet onReference, onTarget;
  for (int axis = 0; axis < 3; ++axis)
    for (const bool largest : {false, true}) {
      Eigen::Index v = 0;
      if (largest) a.skin.V.col(axis).maxCoeff(&v);
      else a.skin.V.col(axis).minCoeff(&v);
      const std::string label = "extreme-" + std::to_string(axis) + (largest ? "+" : "-");
      onReference.markers.push_back(landmark(label, a.skin.V.row(v).transpose()));
      onTarget.markers.push_back(landmark(label, target.V.row(v).transpose()));
    }
  io::writeMarkers(dir + "/reference.mrk.json", onReference);
  io::writeMarkers(dir + "/target.mrk.json", onTarget);
  transfer(reference, dir + "/turned.obj", dir + "/without", "0");
  const nlohmann::json guided =
      transfer(reference, dir + "/turned.obj", dir + "/with", "0",
               {"--reference-landmarks", dir + "/reference.mrk.json", "--target-landmarks", dir + "/target.mrk.json"});
  ReferenceAnatomy expected = a;
  for (ReferenceTissue& t : expected.tissues) t.mesh.V = turned(t.mesh.V);
  const double without = worstBoneDistance(io::readReferenceAnatomy(dir + "/without"), expected),
               with = worstBoneDistance(io::readReferenceAnatomy(dir + "/with"), expected);
  std::cout << "worst bone from the turned anatomy: " << without << " mm without landmarks, " << with
            << " mm with them (landmarks " << guided["metrics"]["landmark_mean_error_mm"] << " mm from their places)\n";
  // Measured 284 mm without, 2.9 mm with (unturned, TheSameBodyGivesTheSameAnatomy: under 0.05 mm; the
  // registration from a turned start slides the skin a little along itself).
  EXPECT_GT(without, 100.0);
  EXPECT_LT(with, 5.0);
  EXPECT_EQ(guided["metrics"]["landmarks"].get<long>(), 6);
  EXPECT_LT(guided["metrics"]["landmark_mean_error_mm"].get<double>(), 2.0);
  // A label without a partner, or landmarks on one side only, are refused in one line, and nothing is
  // written.
  MarkerSet extra = onReference;
  extra.markers.push_back(landmark("lonely", a.skin.V.row(0).transpose()));
  io::writeMarkers(dir + "/extra.mrk.json", extra);
  const std::vector<std::string> base{"transfer", "--reference", reference, "--target-skin", dir + "/turned.obj",
                                      "--out", dir + "/refused", "--progress", "none"};
  std::vector<std::string> unpaired = base, oneSided = base;
  unpaired.insert(unpaired.end(), {"--reference-landmarks", dir + "/extra.mrk.json", "--target-landmarks",
                                   dir + "/target.mrk.json"});
  oneSided.insert(oneSided.end(), {"--reference-landmarks", dir + "/reference.mrk.json"});
  const CommandResult refused = runVesalius(unpaired), alone = runVesalius(oneSided);
  EXPECT_NE(refused.exitCode, 0);
  EXPECT_NE(refused.err.find("extra.mrk.json"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("'lonely' has no partner"), std::string::npos) << refused.err;
  EXPECT_NE(alone.exitCode, 0);
  EXPECT_NE(alone.err.find("--target-landmarks"), std::string::npos) << alone.err;
  EXPECT_FALSE(fs::exists(dir + "/refused"));
}

TEST(CliTransfer, AWiderFlatterBody) {
  const std::string dir = freshDir("wider");
  const std::string reference = buildReference(dir);
  const nlohmann::json report =
      transfer(reference, bodySurface(dir, 0, {1.12, 0.92, 1.0}), dir + "/out", "0", {"--png", dir + "/wider.png"});
  // The renders of the result and the reference are PNGs with a picture in them: an empty 800 x 800
  // background compresses to a few kB, the anatomy to far more.
  for (const char* png : {"/wider.png", "/wider_reference.png"}) {
    std::ifstream in(dir + png, std::ios::binary);
    std::string signature(8, '\0');
    in.read(signature.data(), 8);
    EXPECT_EQ(signature, std::string("\x89PNG\r\n\x1a\n", 8)) << png;
    EXPECT_GT(fs::file_size(dir + png), 40000u) << png;
  }
  const nlohmann::json& m = report["metrics"];
  EXPECT_GT(m["jacobian_min"].get<double>(), 0.0);
  EXPECT_GT(m["jacobian_interior_min"].get<double>(), 0.0);
  // R2; the test CT shows the femurs' heads and necks only (83-97 mm, 1.6-1.8 times as long as wide): no
  // long bone's shaft is in view for R1.
  EXPECT_EQ(expectStraightAndSymmetric(m["bone_groups"]), 0);
  // R5, R6: what was inside the reference skin by a field voxel or more stays inside the target's; the
  // tissues flush with the scan's cuts (lungs, liver, spleen at the top slice) may cross a cut by less than
  // a field voxel, as cut skin fixes nothing (measured: 1,124 of 66,400 vertices, by at most 2.9 mm).
  std::cout << m["pushed_out_vertices"] << " of " << m["tissue_vertices"] << " vertices pushed out, worst by "
            << m["pushed_out_worst_mm"] << " mm, " << m["pushed_out_deep_vertices"] << " of them deep\n";
  EXPECT_EQ(m["pushed_out_deep_vertices"].get<long>(), 0);
  EXPECT_LT(m["pushed_out_worst_mm"].get<double>(), 4.0);
  expectNoneOutsideThroughTheSkin(m);
}

// The full-body reference (MakeHuman's neutral skin with Rajagopal's OpenSim bones placed inside by the
// GRAPP 2012 paper's skeleton alignment, then each moved inside the skin) written to dir/reference.
ReferenceAnatomy fullBodyReference(const std::string& dir) {
  const std::string body = std::string(VESALIUS_TESTDATA) + "/body/";
  const CommandResult made = runVesalius({"reference", "full-body", "--skin", body + "shapes/mh_neutral_body.obj",
                                          "--skeleton", body + "default.mhskel", "--model",
                                          std::string(VESALIUS_TESTDATA) + "/skeleton-opensim/Rajagopal2016.osim",
                                          "--out", dir + "/reference", "--progress", "none"});
  EXPECT_EQ(made.exitCode, 0) << made.err;
  return io::readReferenceAnatomy(dir + "/reference");
}

// A MakeHuman body of testdata/body/shapes in LPS mm.
TriMesh makeHumanShape(const std::string& shape) {
  TriMesh m = io::readTriMesh(std::string(VESALIUS_TESTDATA) + "/body/shapes/" + shape);
  m.V = io::transformPoints(m.V, io::yUpToLps(), 100.0);
  return m;
}

// dir/reference carried into the body surface `target` (in `space`) at 6 mm, as a user runs it: the
// report's metrics.
nlohmann::json fullBodyTransfer(const std::string& dir, const std::string& target, const std::string& space) {
  const CommandResult r = runVesalius({"transfer", "--reference", dir + "/reference", "--target-skin", target,
                                       "--space", space, "--voxel-size", "6", "--out", dir + "/out", "--report",
                                       dir + "/out.json", "--progress", "none"});
  EXPECT_EQ(r.exitCode, 0) << r.err;
  std::ifstream in(dir + "/out.json");
  const nlohmann::json m = nlohmann::json::parse(in)["metrics"];
  EXPECT_LT(m["registration_mean_distance_mm"].get<double>(), 1.0);
  for (const nlohmann::json& group : m["bone_groups"]) EXPECT_GT(group["determinant"].get<double>(), 0.3) << group["group"];
  std::cout << "interior folds " << m["jacobian_interior_nonpositive_cells"] << ", vertices outside the reference "
            << m["reference_outside_vertices"] << ", outside the target " << m["target_outside_vertices"]
            << ", deep vertices pushed out " << m["pushed_out_deep_vertices"] << "\n";
  // R6 for the reference itself, its skin's cavities (mouth, eye sockets) counted as inside, every unit of
  // bones moved inside by a similarity change and what is still outside then bent inside, at a limb's reach
  // and then a toe's: none of its 30,751 tissue vertices outside its own skin. The cavities measure 264 ml
  // (mouth 230 ml, eye sockets 2 x 12 ml at the grid's 2.5 mm voxels).
  EXPECT_EQ(m["reference_outside_vertices"].get<long>(), 0);
  EXPECT_LE(m.value("reference_outside_vertices_hat_skull", 0L) + m.value("reference_outside_vertices_hat_jaw", 0L), 20);
  EXPECT_NEAR(m["reference_skin_cavities_ml"].get<double>(), 264.0, 30.0);
  // In the target's cavities: the skull and jaw in the mouth (measured 1,938-1,971 vertices) and a few
  // others where the target's skin makes a pocket (toes 26-89, the spine 5-11, ribs in the muscular body's
  // left armpit 5).
  const long headInCavities = m.value("target_in_cavities_vertices_hat_skull", 0L) +
                              m.value("target_in_cavities_vertices_hat_jaw", 0L);
  EXPECT_GT(headInCavities, 1700);
  EXPECT_LE(m["target_in_cavities_vertices"].get<long>() - headInCavities, 130);
  return m;
}

// R7: muscle path points on a bone (within 0.5 mm of its surface) stay on it (within 1 mm); returns how
// many were on a bone.
int expectPointsStayOnTheirBones(const ReferenceAnatomy& reference, const ReferenceAnatomy& out) {
  EXPECT_EQ(out.points.size(), reference.points.size());
  std::map<std::string, int> tissueIndex;
  for (int t = 0; t < int(reference.tissues.size()); ++t) tissueIndex[reference.tissues[t].name] = t;
  int onBone = 0;
  for (std::size_t p = 0; p < std::min(reference.points.size(), out.points.size()); ++p) {
    const auto it = tissueIndex.find(reference.points[p].tissue);
    if (it == tissueIndex.end()) continue;
    const TriMesh& before = reference.tissues[it->second].mesh;
    const TriMesh& after = out.tissues[it->second].mesh;
    if (TriangleTree(before.V, before.F).closest(reference.points[p].position).squaredDistance > 0.25) continue;
    ++onBone;
    EXPECT_LT(std::sqrt(TriangleTree(after.V, after.F).closest(out.points[p].position).squaredDistance), 1.0)
        << reference.points[p].name;
  }
  return onBone;
}

// The joint centres (points named joint/BODY, fixed to the body's bone) carried with their bones: how far
// each is from the nearest bone of another group (the joint's other side) before and after; returns the
// widest opening (after − before, mm) and checks that all 21 of Rajagopal's came through.
double widestJointOpening(const ReferenceAnatomy& reference, const ReferenceAnatomy& out) {
  const auto otherSide = [](const ReferenceAnatomy& a, const ReferencePoint& joint) {
    std::string group;
    for (const ReferenceTissue& t : a.tissues)
      if (t.name == joint.tissue) group = t.group;
    double nearest = std::numeric_limits<double>::infinity();
    for (const ReferenceTissue& t : a.tissues)
      if (t.kind == TissueKind::Bone && t.group != group)
        nearest = std::min(nearest, std::sqrt(TriangleTree(t.mesh.V, t.mesh.F).closest(joint.position).squaredDistance));
    return nearest;
  };
  int joints = 0;
  double widest = -std::numeric_limits<double>::infinity();
  for (std::size_t p = 0; p < std::min(reference.points.size(), out.points.size()); ++p) {
    if (reference.points[p].name.rfind("joint/", 0) != 0) continue;
    ++joints;
    const double before = otherSide(reference, reference.points[p]), after = otherSide(out, out.points[p]);
    std::cout << reference.points[p].name << ": " << before << " -> " << after << " mm from the other side\n";
    widest = std::max(widest, after - before);
  }
  EXPECT_EQ(joints, 21);
  return widest;
}

// Mean distance (mm) of the transferred skin's hand and forearm vertices (those whose closest reference
// bone is in a hand, or a radius or ulna group) to their true places `truth`. The MakeHuman bodies share
// the neutral's topology, so reference skin vertex i belongs at the body's vertex i: the transfer never
// sees that, only this check uses it.
std::pair<double, double> handAndForearmSkinErrors(const ReferenceAnatomy& reference, const std::string& out,
                                                   const TriMesh& truth) {
  TriMesh bones;
  std::vector<int> kindOfFace;  // 1 hand, 2 forearm, 0 other
  for (const ReferenceTissue& t : reference.tissues) {
    if (t.kind != TissueKind::Bone) continue;
    const int kind = t.group.rfind("hand_", 0) == 0 ? 1 : t.group.rfind("radius_", 0) == 0 || t.group.rfind("ulna_", 0) == 0 ? 2 : 0;
    bones = bones.V.rows() ? concatenate(bones, t.mesh) : t.mesh;
    kindOfFace.insert(kindOfFace.end(), std::size_t(t.mesh.F.rows()), kind);
  }
  const MatrixX3d registered = io::readReferenceAnatomy(out).skin.V;
  EXPECT_EQ(registered.rows(), truth.V.rows());
  if (registered.rows() != truth.V.rows()) return {0, 0};
  const std::vector<ClosestPoint> closest = TriangleTree(bones.V, bones.F).closest(reference.skin.V);
  double sum[3] = {0, 0, 0};
  int count[3] = {0, 0, 0};
  for (std::size_t v = 0; v < closest.size(); ++v) {
    const int kind = kindOfFace[std::size_t(closest[v].face)];
    sum[kind] += (registered.row(Eigen::Index(v)) - truth.V.row(Eigen::Index(v))).norm();
    ++count[kind];
  }
  std::cout << "skin off its true place: hands " << sum[1] / count[1] << " mm, forearms " << sum[2] / count[2]
            << " mm, the rest " << sum[0] / count[0] << " mm\n";
  return {sum[1] / count[1], sum[2] / count[2]};
}

// The full-body reference carried into the thin MakeHuman body (its own mesh, registered, not taken by
// vertex index). What holds: long bones stay straight and the trunk symmetric (R1, R2), every bone maps
// with a positive determinant, points on bones move with them (R7), and the skin registration, with its
// articulated stage, puts the hands' and forearms' skin near its true place; every bone inside the skin
// (R5, R6) and the field unfolded inside the body.
TEST(CliTransfer, FullBodyIntoTheThinBody) {
  const std::string dir = freshDir("full-body");
  const ReferenceAnatomy reference = fullBodyReference(dir);
  EXPECT_EQ(reference.tissues.size(), 81u);
  EXPECT_EQ(reference.points.size(), 288u + 21u);  // muscle path points, joint centres
  // MakeHuman's uv come with the skin, so the fat editor can write its texture (Dicko et al. 2013, §5-6): 0.4 of the
  // 50 mm maximum over the pelvis, nothing where no bone was given an amount.
  EXPECT_EQ(reference.skin.FUV.rows(), reference.skin.F.rows());
  { std::ofstream(dir + "/amounts.json") << R"({"pelvis": 0.4})"; }
  const CommandResult edited = runVesalius({"fat", "edit", "--reference", dir + "/reference", "--amounts",
                                            dir + "/amounts.json", "--out", dir + "/fat.nrrd", "--progress", "none"});
  ASSERT_EQ(edited.exitCode, 0) << edited.err;
  const Image texture = io::readScan(dir + "/fat.nrrd");
  const auto [least, most] = std::minmax_element(texture.values.begin(), texture.values.end());
  EXPECT_GE(*least, 0.0f);
  EXPECT_NEAR(*most, 20.0f, 0.5f);
  const std::string thin = "mh_male_young_thin_body.obj";
  const nlohmann::json m = fullBodyTransfer(dir, std::string(VESALIUS_TESTDATA) + "/body/shapes/" + thin, "makehuman");
  // R1 for the 22 long bones (limbs 12, metacarpals II-V 8, ring fingers' proximal phalanges 2), R2.
  EXPECT_EQ(expectStraightAndSymmetric(m["bone_groups"]), 22);
  EXPECT_GT(expectPointsStayOnTheirBones(reference, io::readReferenceAnatomy(dir + "/out")), 20);
  // The joints stay together: where two bone groups' maps differ, a joint opens (measured at most 4.8 mm,
  // the elbow's radius from the humerus; the knee's patella closes by 6.6 mm).
  EXPECT_LT(widestJointOpening(reference, io::readReferenceAnatomy(dir + "/out")), 7.0);
  // The registration's articulated stage brings the hands within 5 mm of their true place (MakeHuman's
  // vertex i) and the forearms within 12 mm; ICP and shape matching alone leave 60 mm and 35 mm.
  const auto [hands, forearms] = handAndForearmSkinErrors(reference, dir + "/out", makeHumanShape(thin));
  EXPECT_LT(hands, 5.0);
  EXPECT_LT(forearms, 12.0);
  // Rules R5, R6 and the field's folds (Dicko et al. 2013, §7-8): no folded cell, fixed shells included (the final
  // field's fixed cells at folds are freed); none of the 30,751 tissue vertices outside the target's skin
  // (what the bone maps leave outside is bent inside); no vertex a voxel or more inside the reference skin
  // pushed out of the target's.
  EXPECT_EQ(m["jacobian_interior_nonpositive_cells"].get<long>(), 0);
  EXPECT_EQ(m["jacobian_nonpositive_cells"].get<long>(), 0);  // the fixed shells' too
  EXPECT_EQ(m["target_outside_vertices"].get<long>(), 0);
  EXPECT_LE(m["pushed_out_deep_vertices"].get<long>(), 2);
}

// The same reference into the muscular MakeHuman body, whose chest is larger: the trunk's map grows
// (determinant about 2); the skull is kept out of it (in it, the trunk's map would carry the skull into the
// face). The same rules as for the thin body: no folded cell, no tissue vertex outside the target's skin, no
// deep vertex pushed out. R1 holds because the long bones' maps keep their width to their length
// (fitLongBoneMap): an arm's affine map would take in the muscle (determinants 2.5-3.4) and bow the forearm
// bones' centre lines beyond the reference's.
TEST(CliTransfer, FullBodyIntoTheMuscularBody) {
  const std::string dir = freshDir("full-body-muscular");
  const ReferenceAnatomy reference = fullBodyReference(dir);
  const std::string muscular = "mh_male_young_muscular_body.obj";
  const nlohmann::json m =
      fullBodyTransfer(dir, std::string(VESALIUS_TESTDATA) + "/body/shapes/" + muscular, "makehuman");
  EXPECT_EQ(expectStraightAndSymmetric(m["bone_groups"]), 22);
  EXPECT_GT(expectPointsStayOnTheirBones(reference, io::readReferenceAnatomy(dir + "/out")), 20);
  EXPECT_LT(widestJointOpening(reference, io::readReferenceAnatomy(dir + "/out")), 7.0);  // measured 5.4 mm
  const auto [hands, forearms] = handAndForearmSkinErrors(reference, dir + "/out", makeHumanShape(muscular));
  EXPECT_LT(hands, 4.0);
  EXPECT_LT(forearms, 13.0);
  EXPECT_EQ(m["jacobian_interior_nonpositive_cells"].get<long>(), 0);
  EXPECT_EQ(m["jacobian_nonpositive_cells"].get<long>(), 0);  // the fixed shells' too
  EXPECT_EQ(m["target_outside_vertices"].get<long>(), 0);
  EXPECT_LE(m["pushed_out_deep_vertices"].get<long>(), 2);
}

// The thin body voxelized at 4 mm and surfaced anew, a target of its own topology (about 15,000 vertices):
// the registration, articulated stage included, sees only its surface. The thin body's vertex i is still
// the truth for the check. The same rules as on the thin body's own mesh: no folded cell, no tissue vertex
// outside the target's skin, no deep vertex pushed out.
TEST(CliTransfer, FullBodyIntoARemeshedThinBody) {
  const std::string dir = freshDir("full-body-remeshed");
  const ReferenceAnatomy reference = fullBodyReference(dir);
  const TriMesh thin = makeHumanShape("mh_male_young_thin_body.obj");
  const TriMesh target = test::remeshedSurface(thin, 4.0, 30000);
  ASSERT_NE(target.V.rows(), thin.V.rows());
  io::writeTriMesh(dir + "/target.obj", target);
  const nlohmann::json m = fullBodyTransfer(dir, dir + "/target.obj", "lps");
  // R1 for the 22 long bones (the tali, about as long as they are wide, read 26.2% of their length in the
  // reference and 27.3% here, and are not measured), R2.
  EXPECT_EQ(expectStraightAndSymmetric(m["bone_groups"]), 22);
  const auto [hands, forearms] = handAndForearmSkinErrors(reference, dir + "/out", thin);
  // ICP with shape matching alone (Dicko et al. 2013, §4) on the same target, for comparison: the articulated
  // stage, which turns the limbs about their joints first, brings the hands at least twice as near their true
  // place, the forearms nearer. (How near depends on the target's triangulation where the 4 mm voxels fused
  // the fingers: 4.7 to 21 mm for the hands over three surfacings of this body.)
  const CommandResult plain =
      runVesalius({"transfer", "--reference", dir + "/reference", "--target-skin", dir + "/target.obj", "--space",
                   "lps", "--voxel-size", "6", "--registration", "plain", "--out", dir + "/plain", "--progress", "none"});
  ASSERT_EQ(plain.exitCode, 0) << plain.err;
  const auto [plainHands, plainForearms] = handAndForearmSkinErrors(reference, dir + "/plain", thin);
  EXPECT_LT(hands, 0.5 * plainHands);
  EXPECT_LT(forearms, plainForearms);
  EXPECT_EQ(m["jacobian_interior_nonpositive_cells"].get<long>(), 0);
  EXPECT_EQ(m["jacobian_nonpositive_cells"].get<long>(), 0);  // the fixed shells' too
  EXPECT_EQ(m["target_outside_vertices"].get<long>(), 0);
  EXPECT_LE(m["pushed_out_deep_vertices"].get<long>(), 2);
}

}  // namespace vesalius::test
