// vesalius transfer: a reference anatomy carried into a target body surface (seed 000): skin registration
// (§4), erosion by the fat thickness (§5) and registration of the lean reference onto the eroded skin,
// Laplace interpolation (§7), bone registration (§8), final interpolation; with the anatomical rules
// measured in the report.
#include "bone_fat_amounts.h"
#include "common.h"
#include "landmark_pairs.h"
#include "thickness_input.h"

#include "vesalius/core/error.h"
#include "vesalius/io/body_axes.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/reference_anatomy_io.h"
#include "vesalius/meshing/body_distance.h"
#include "vesalius/patient/transfer_into_body.h"
#include "vesalius/transfer/anatomy_rules.h"
#include "vesalius/transfer/anatomy_transfer.h"
#include "vesalius/transfer/articulated_registration.h"
#include "vesalius/transfer/skin_registration.h"
#include "vesalius/viz/surface_render.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace vesalius::cli {

namespace {

struct TransferOptions {
  std::string reference, targetSkin, out, space = "lps", png, fat = "0", fatAmounts, laplaceSolver = "mg",
              registration = "articulated", referenceLandmarks, targetLandmarks;
  double voxelSize = 3;
  int registrationIterations = transfer::SkinRegistrationOptions{}.iterations;
  CommonOptions common;
};

TriMesh readTarget(const TransferOptions& o) {
  TriMesh skin = io::readTriMesh(o.targetSkin);
  if (o.space == "makehuman") skin.V = io::transformPoints(skin.V, io::yUpToLps(), 100.0);
  else if (o.space != "lps") throw UsageError("transfer: --space must be lps or makehuman");
  return skin;
}

// --reference-landmarks and --target-landmarks paired by label (§4's optional manual initialisation), each
// reference point taken as the reference skin vertex nearest to it.
std::vector<transfer::SkinLandmark> readSkinLandmarks(const TransferOptions& o, const TriMesh& skin) {
  if (o.referenceLandmarks.empty()) return {};
  const LandmarkPairs pairs = pairLandmarks(o.referenceLandmarks, o.targetLandmarks);
  if (pairs.labels.empty()) throw BadInput(o.referenceLandmarks, "holds no defined landmark with a partner");
  std::vector<transfer::SkinLandmark> landmarks;
  for (Eigen::Index p = 0; p < pairs.first.rows(); ++p) {
    Eigen::Index vertex = 0;
    (skin.V.rowwise() - pairs.first.row(p)).rowwise().squaredNorm().minCoeff(&vertex);
    landmarks.push_back({int(vertex), pairs.second.row(p).transpose()});
  }
  return landmarks;
}

// The reference skin onto a target skin: §4's ICP with shape matching, after the articulated stage unless
// --registration plain (articulated_registration.h), with the landmarks if any.
transfer::SkinRegistration registerReferenceSkin(const ReferenceAnatomy& reference, const transfer::SkinParts& parts,
                                                 const MatrixX3d& Vt, const MatrixX3i& Ft, const TransferOptions& o,
                                                 const std::vector<transfer::SkinLandmark>& landmarks = {}) {
  transfer::ArticulatedRegistrationOptions options;
  options.registration.iterations = o.registrationIterations;
  if (o.registration == "plain")
    return transfer::registerSkin(reference.skin.V, reference.skin.F, Vt, Ft, options.registration, landmarks);
  return transfer::registerSkinArticulated(reference.skin.V, reference.skin.F, parts, Vt, Ft, options, landmarks)
      .registration;
}

// Per tissue, the metric `prefix` + NAME where a count is not zero.
template <class Count>
void perTissue(const ReferenceAnatomy& anatomy, const transfer::AnatomyRules& rules, const std::string& prefix,
               Count count, io::Report& report) {
  for (std::size_t t = 0; t < rules.tissues.size(); ++t)
    if (const long n = count(rules.tissues[t])) report.metric(prefix + anatomy.tissues[t].name, n);
}

// The anatomical rules (transfer/anatomy_rules.h) in the report: the transferred anatomy against the
// reference, each measured on the body the pipeline made of its skin (`body`: the registered skin's, with
// its cavities), `deepMm` one field voxel; R1 and R2 also for the interpolated bones (the skin's field
// alone, the seed's Fig. 4 left), beside each bone group's map.
transfer::AnatomyRules reportRules(const ReferenceAnatomy& reference, const patient::TransferIntoBody& into,
                                   const meshing::BodyDistance& body, double deepMm, io::Report& report) {
  const transfer::TransferredAnatomy& result = into.transferred;
  transfer::AnatomyRulesOptions options;
  options.skinDistance = &body.signedDistance;
  options.skinCavities = &body.cavities;
  options.referenceSkinDistance = &into.referenceBody.signedDistance;
  options.referenceSkinCavities = &into.referenceBody.cavities;
  options.deepMm = deepMm;
  const transfer::AnatomyRules rules = transfer::checkAnatomyRules(reference, into.anatomy, &result.finalField, options);
  ReferenceAnatomy interpolated = into.anatomy;
  for (std::size_t t = 0; t < interpolated.tissues.size(); ++t) interpolated.tissues[t].mesh.V = result.interpolated[t];
  transfer::AnatomyRulesOptions bones;
  bones.outside = bones.folds = bones.interpenetration = false;
  const transfer::AnatomyRules step1 = transfer::checkAnatomyRules(reference, interpolated, nullptr, bones);

  // R5, R6.
  const transfer::OutsideRule& o = rules.outside;
  report.metric("reference_skin_cavities_ml", into.referenceBody.cavitiesMl);
  report.metric("target_skin_cavities_ml", body.cavitiesMl);
  report.metric("tissue_vertices", o.vertices);
  report.metric("reference_outside_vertices", o.referenceOutside);
  report.metric("target_outside_vertices", o.outside);
  report.metric("target_outside_worst_mm", o.worstMm);
  report.metric("reference_outside_at_cut_vertices", o.referenceOutsideAtCut);
  report.metric("target_outside_at_cut_vertices", o.outsideAtCut);
  report.metric("reference_in_cavities_vertices", o.referenceInCavities);
  report.metric("target_in_cavities_vertices", o.inCavities);
  report.metric("pushed_out_vertices", o.pushedOut);
  report.metric("pushed_out_worst_mm", o.pushedOutWorstMm);
  report.metric("pushed_out_deep_vertices", o.pushedOutDeep);
  report.metric("deep_means_mm", deepMm);
  using Row = transfer::TissueRules;
  perTissue(reference, rules, "reference_outside_vertices_", [](const Row& r) { return r.referenceOutside; }, report);
  perTissue(reference, rules, "reference_in_cavities_vertices_", [](const Row& r) { return r.referenceInCavities; }, report);
  perTissue(reference, rules, "target_in_cavities_vertices_", [](const Row& r) { return r.inCavities; }, report);
  perTissue(reference, rules, "pushed_out_vertices_", [](const Row& r) { return r.pushedOut; }, report);
  perTissue(reference, rules, "pushed_out_deep_vertices_", [](const Row& r) { return r.pushedOutDeep; }, report);

  // The final field's folds.
  const transfer::JacobianSummary& jacobian = rules.folds.jacobian;
  const auto point = [](const Eigen::Vector3d& p) { return nlohmann::json{p.x(), p.y(), p.z()}; };
  report.metric("jacobian_min", jacobian.minimum);
  report.metric("jacobian_nonpositive_cells", jacobian.nonPositiveCells);
  report.metric("jacobian_min_at", point(jacobian.whereMinimum));
  report.metric("jacobian_interior_min", jacobian.interiorMinimum);
  report.metric("jacobian_interior_min_at", point(jacobian.whereInteriorMinimum));
  report.metric("jacobian_interior_nonpositive_cells", jacobian.interiorNonPositiveCells);

  // R1, R2 per bone group, with its map and bend.
  nlohmann::json groups = nlohmann::json::array();
  for (const transfer::BoneGroupMap& group : result.boneGroups) {
    nlohmann::json g{{"group", group.group}, {"symmetric", group.symmetric}, {"rms_to_attractor_mm", group.rmsToAttractorMm},
                     {"determinant", group.map.A.determinant()}, {"bent_vertices", group.bend.outsideBefore},
                     {"bend_largest_mm", group.bend.largestMoveMm}, {"outside_after_bend", group.bend.outsideAfter}};
    for (std::size_t s = 0; s < rules.symmetry.groups.size(); ++s)
      if (rules.symmetry.groups[s].group == group.group)
        g["mirror_asymmetry_mm"] = {{"reference", rules.symmetry.groups[s].referenceAsymmetryMm},
                                    {"interpolated", step1.symmetry.groups[s].asymmetryMm},
                                    {"registered", rules.symmetry.groups[s].asymmetryMm}};
    for (const int t : group.tissues)
      if (!std::isnan(rules.tissues[std::size_t(t)].centreLineDeviation))
        g["centre_line_deviation"][reference.tissues[std::size_t(t)].name] = {
            {"reference", rules.tissues[std::size_t(t)].referenceCentreLineDeviation},
            {"interpolated", step1.tissues[std::size_t(t)].centreLineDeviation},
            {"registered", rules.tissues[std::size_t(t)].centreLineDeviation}};
    groups.push_back(g);
  }
  report.metric("bone_groups", groups);

  // Tissues into one another, beyond the reference's own overlap.
  const transfer::InterpenetrationRule& p = rules.interpenetration;
  nlohmann::json pairs = nlohmann::json::array();
  for (const transfer::Interpenetration& pair : p.pairs)
    pairs.push_back({{"tissues", {reference.tissues[std::size_t(pair.a)].name, reference.tissues[std::size_t(pair.b)].name}},
                     {"depth_mm", pair.depthMm}, {"reference_depth_mm", pair.referenceDepthMm},
                     {"vertices", pair.vertices}, {"at", point(pair.at)}});
  report.metric("interpenetrating_pairs", pairs);
  report.metric("interpenetration_worst_mm", p.worstMm);
  report.metric("interpenetration_worst_excess_mm", p.worstExcessMm);
  report.metric("rules_hold", {{"outside", o.holds}, {"folds", rules.folds.holds}, {"symmetry", rules.symmetry.holds},
                               {"straightness", rules.straightness.holds}, {"interpenetration", p.holds}});
  return rules;
}

void renderPng(const ReferenceAnatomy& anatomy, const std::vector<MatrixX3d>& tissueVertices, const TriMesh& skin,
               const std::string& path, const WriteOptions& write) {
  std::vector<TriMesh> meshes;
  for (std::size_t t = 0; t < anatomy.tissues.size(); ++t) {
    meshes.push_back(anatomy.tissues[t].mesh);
    meshes.back().V = tissueVertices[t];
  }
  std::vector<viz::SurfaceLayer> layers;
  for (std::size_t t = 0; t < meshes.size(); ++t) {
    layers.push_back({&meshes[t], tissueKindColour(anatomy.tissues[t].kind), 1.0});
  }
  layers.push_back({&skin, kSkinColour, 0.2});
  viz::SurfaceRenderOptions options;
  options.write = write;
  viz::writeSurfacesPng(layers, path, options);
}

void runTransfer(const TransferOptions& o) {
  if (fs::weakly_canonical(o.out) == fs::weakly_canonical(o.reference))
    throw UsageError("transfer: --out must not be the reference folder (inputs are never overwritten)");
  if (!o.png.empty() && !viz::canRenderSurfaces()) throw UsageError("transfer: --png needs a display (run under xvfb-run)");
  checkOutputFolder(o.out, o.common.writeOptions());  // before the work; written whole at the end
  io::Report report("transfer");
  report.input("reference", o.reference);
  report.input("target_skin", o.targetSkin);
  report.parameter("fat", o.fatAmounts.empty() ? o.fat : o.fatAmounts);
  report.parameter("voxel_size_mm", o.voxelSize);
  report.parameter("registration_iterations", o.registrationIterations);
  report.parameter("registration", o.registration);
  report.parameter("laplace_solver", o.laplaceSolver);
  Progress progress(o.common.progressStyle());
  auto start = std::chrono::steady_clock::now();
  const auto endStage = [&](const std::string& name) {
    report.stage(name, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    start = std::chrono::steady_clock::now();
  };
  const ReferenceAnatomy reference = io::readReferenceAnatomy(o.reference);
  const TriMesh target = readTarget(o);
  endStage("reading");
  // The fat first, so that a bad file fails before the registration's work. --fat-amounts takes `fat
  // edit`'s defaults: 15 mm voxels, 50 mm per unit amount, 0 for the bones it does not name.
  std::string fatKind = "bone amounts";
  const Eigen::VectorXd fat = o.fatAmounts.empty()
                                  ? readThickness(o.fat, reference.skin, o.reference + "/" + "skin.obj", fatKind)
                                  : boneFatAtSkin(reference, o.reference, o.fatAmounts, {}, report);
  report.parameter("fat_kind", fatKind);

  progress.begin("register", "skin registration (ICP with shape matching)");
  start = std::chrono::steady_clock::now();
  const transfer::SkinParts parts = transfer::skinPartsFromBones(reference);
  report.metric("registration_parts", o.registration == "plain" ? 1 : long(parts.order.size()));
  const std::vector<transfer::SkinLandmark> landmarks = readSkinLandmarks(o, reference.skin);
  const transfer::SkinRegistration registered = registerReferenceSkin(reference, parts, target.V, target.F, o, landmarks);
  endStage("skin registration");
  progress.end();
  report.metric("registration_mean_distance_mm", registered.finalMeanDistance);
  report.metric("registration_max_distance_mm", registered.finalMaxDistance);
  if (!landmarks.empty()) {
    double sum = 0;
    for (const transfer::SkinLandmark& l : landmarks) sum += (registered.V.row(l.sourceVertex).transpose() - l.target).norm();
    report.metric("landmarks", long(landmarks.size()));
    report.metric("landmark_mean_error_mm", sum / double(landmarks.size()));
  }

  report.metric("registration_scale", registered.alignment.scale);

  patient::TransferIntoBodyOptions pipeline;
  pipeline.registration.registration.iterations = o.registrationIterations;
  pipeline.articulated = o.registration != "plain";
  pipeline.voxelSizeMm = o.voxelSize;
  pipeline.transfer.field.laplace.solver =
      o.laplaceSolver == "cg" ? transfer::LaplaceSolver::ConjugateGradient : transfer::LaplaceSolver::MultigridCG;
  const patient::TransferIntoBody into = patient::transferIntoBody(reference, registered.V, fat, parts, pipeline, &progress);
  for (const auto& [stage, seconds] : into.stageSeconds) report.stage(stage, seconds);
  if (into.eroded) {
    report.metric("erosion_mean_mm", into.erosionMeanMm);
    report.metric("erosion_limited_vertices", into.erosionLimited);
    report.metric("erosion_new_self_intersections", into.erosionNewSelfIntersections);
    report.metric("sub_fat_registration_mean_distance_mm", into.subFatMeanDistanceMm);
    report.metric("sub_fat_registration_scale", into.subFatScale);
  }
  const transfer::TransferredAnatomy& result = into.transferred;
  const GridGeometry& grid = into.grid;
  TriMesh eroded = reference.skin;
  eroded.V = into.erodedSkin;
  start = std::chrono::steady_clock::now();
  report.metric("grid", {grid.size.x(), grid.size.y(), grid.size.z()});
  const auto iterations = [](const transfer::DisplacementField& f) {
    return nlohmann::json{f.solves[0].iterations, f.solves[1].iterations, f.solves[2].iterations};
  };
  report.metric("laplace_iterations", {{"skin_field", iterations(result.skinField)}, {"final_field", iterations(result.finalField)}});
  report.metric("unfold_passes", result.finalField.unfoldPasses);
  report.metric("unfold_released_cells", result.finalField.releasedCells);
  // The registered skin's body: the eroded one is that unless fat was eroded.
  const transfer::AnatomyRules rules = reportRules(
      reference, into, into.eroded ? meshing::bodySignedDistance(into.anatomy.skin) : into.erodedBody, o.voxelSize, report);
  endStage("checks");

  const ReferenceAnatomy& out = into.anatomy;
  // The sub-fat surface (the seed's Fig. 2.b) goes beside the anatomy: to look at, not part of it.
  io::writeReferenceAnatomy(o.out, out, o.common.writeOptions(), {{"eroded_skin.obj", eroded}});
  report.output("anatomy", o.out);
  report.output("eroded_skin", (fs::path(o.out) / "eroded_skin.obj").string());
  if (!o.png.empty()) {
    // The result, and the reference beside it under the same name with "_reference".
    renderPng(out, result.tissues, out.skin, o.png, o.common.writeOptions());
    std::vector<MatrixX3d> rest;
    for (const ReferenceTissue& t : reference.tissues) rest.push_back(t.mesh.V);
    const fs::path png(o.png);
    const std::string referencePng = (png.parent_path() / (png.stem().string() + "_reference" + png.extension().string())).string();
    renderPng(reference, rest, reference.skin, referencePng, o.common.writeOptions());
    report.output("png", o.png);
    report.output("png_reference", referencePng);
  }
  endStage("writing");
  std::cout << std::fixed << std::setprecision(2) << o.out << ": " << reference.tissues.size()
            << " tissues transferred; skin registered to " << registered.finalMeanDistance << " mm (mean), "
            << result.boneGroups.size() << " bone groups, Jacobian min " << rules.folds.jacobian.minimum << ", "
            << rules.outside.pushedOut << " tissue vertices pushed out of the skin\n";
  o.common.finish(report);
}

}  // namespace

void addTransferCommand(CLI::App& app) {
  auto o = std::make_shared<TransferOptions>();
  CLI::App* cmd = app.add_subcommand("transfer", "Carry a reference anatomy into a target body surface (seed 000)");
  cmd->add_option("--reference", o->reference, "Reference anatomy folder (from `vesalius reference`)")->required();
  cmd->add_option("--target-skin", o->targetSkin, "Closed body surface of the target (.obj .stl .vtp .ply .vtk)")->required();
  cmd->add_option("--space", o->space, "Space of the target skin: lps (mm) or makehuman (decimetres, +Y up)")
      ->capture_default_str();
  CLI::Option* fatOption = cmd->add_option("--fat", o->fat,
                  "Subcutaneous fat of the target, eroded from its skin: a thickness in mm, a texture on the "
                  "reference skin's uv (from 'fat texture'), a mesh with fat_thickness or a text file per "
                  "reference skin vertex")
      ->capture_default_str();
  cmd->add_option("--fat-amounts", o->fatAmounts,
                  "Fat from per-bone amounts instead (seed 000 §6): a JSON object as `fat edit --amounts` takes it, "
                  "with that command's defaults")
      ->excludes(fatOption);
  cmd->add_option("--voxel-size", o->voxelSize, "Voxel size of the displacement field's grid, mm")->capture_default_str();
  cmd->add_option("--laplace-solver", o->laplaceSolver,
                  "Solver of the two Laplace fields: mg (multigrid-preconditioned CG) or cg (Jacobi-preconditioned "
                  "CG, the seed's baseline, for benchmarks); both stop at the same relative residual")
      ->check(CLI::IsMember({"mg", "cg"}))
      ->capture_default_str();
  cmd->add_option("--registration-iterations", o->registrationIterations, "ICP iterations of the skin registration")
      ->capture_default_str();
  CLI::Option* referenceLandmarks =
      cmd->add_option("--reference-landmarks", o->referenceLandmarks,
                      "Landmarks on the reference skin (markups, LPS mm), paired by label with --target-landmarks: "
                      "they start the skin registration where the bodies are far apart or turned (seed 000 §4)");
  CLI::Option* targetLandmarks = cmd->add_option(
      "--target-landmarks", o->targetLandmarks, "Their partners on the target skin (markups, LPS mm, as the target is after --space)");
  referenceLandmarks->needs(targetLandmarks);
  targetLandmarks->needs(referenceLandmarks);
  cmd->add_option("--registration", o->registration,
                  "Skin registration: articulated (the reference skin cut into parts by its bones, limbs turned about "
                  "their joints before ICP with shape matching) or plain (ICP with shape matching alone, seed 000 §4)")
      ->check(CLI::IsMember({"articulated", "plain"}))
      ->capture_default_str();
  cmd->add_option("--png", o->png,
                  "Render of the transferred anatomy inside the translucent skin, and of the reference beside it "
                  "(NAME_reference.png); needs a display");
  cmd->add_option("--out", o->out, "Folder to write the transferred anatomy to (same form as a reference)")->required();
  addCommonOptions(*cmd, o->common);
  cmd->footer(
      "Example:\n  vesalius reference torso --scan ct.nii.gz --labels seg.nii.gz --label-table labels.tsv --out ref\n"
      "  vesalius transfer --reference ref --target-skin body.obj --fat 5 --out target --report transfer.json\n"
      "See docs/methods/anatomy-transfer.md for the steps and the checks in the report.");
  cmd->callback([o] { runTransfer(*o); });
}

}  // namespace vesalius::cli
