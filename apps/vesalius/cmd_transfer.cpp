// vesalius transfer: a reference anatomy carried into a target body surface (Dicko et al. 2013): skin registration
// (§4), erosion by the fat thickness (§5) and registration of the lean reference onto the eroded skin,
// Laplace interpolation (§7), bone registration (§8), final interpolation; with the anatomical rules
// measured in the report.
#include "bone_fat_amounts.h"
#include "command_runner.h"
#include "common.h"
#include "landmark_pairs.h"
#include "thickness_input.h"
#include "transfer_outputs.h"

#include "vesalius/core/error.h"
#include "vesalius/io/body_axes.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/reference_anatomy_io.h"
#include "vesalius/meshing/body_distance.h"
#include "vesalius/patient/transfer_into_body.h"
#include "vesalius/transfer/anatomy_rules.h"
#include "vesalius/transfer/anatomy_transfer.h"
#include "vesalius/transfer/reference_skin_registration.h"
#include "vesalius/transfer/skin_registration.h"
#include "vesalius/transfer/transfer_rules.h"
#include "vesalius/viz/surface_render.h"

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
  return transfer::landmarksAtNearestVertices(skin.V, pairs.first, pairs.second);
}

// The bar's shares of the skin registration and of the transfer after it, as runs on the test CT's torso
// reference (4 mm voxels, tests/apps/cli_transfer_test.cpp) time them: 3.1 to 4.4 s and 4.8 to 11.9 s.
const StagePlan kTransferStages{{"register", 3.3}, {"transfer", 6.0}};

void runTransfer(const TransferOptions& o, CommandRun& run) {
  if (fs::weakly_canonical(o.out) == fs::weakly_canonical(o.reference))
    throw UsageError("transfer: --out must not be the reference folder (inputs are never overwritten)");
  if (!o.png.empty() && !viz::canRenderSurfaces()) throw UsageError("transfer: --png needs a display (run under xvfb-run)");
  checkOutputFolder(o.out, o.common.writeOptions());  // before the work; written whole at the end
  run.report.input("reference", o.reference);
  run.report.input("target_skin", o.targetSkin);
  run.report.parameter("fat", o.fatAmounts.empty() ? o.fat : o.fatAmounts);
  run.report.parameter("voxel_size_mm", o.voxelSize);
  run.report.parameter("registration_iterations", o.registrationIterations);
  run.report.parameter("registration", o.registration);
  run.report.parameter("laplace_solver", o.laplaceSolver);
  ReferenceAnatomy reference;
  TriMesh target;
  {
    auto timer = run.report.time("reading");
    reference = io::readReferenceAnatomy(o.reference);
    target = readTarget(o);
  }
  // The fat first, so that a bad file fails before the registration's work. --fat-amounts takes `fat
  // edit`'s defaults: 15 mm voxels, 50 mm per unit amount, 0 for the bones it does not name.
  std::string fatKind = "bone amounts";
  const Eigen::VectorXd fat = o.fatAmounts.empty()
                                  ? readThickness(o.fat, reference.skin, o.reference + "/" + "skin.obj", fatKind)
                                  : boneFatAtSkin(reference, o.reference, o.fatAmounts, {}, run.report);
  run.report.parameter("fat_kind", fatKind);

  run.progress.begin("register", "skin registration (ICP with shape matching)");
  const transfer::SkinParts parts = transfer::skinPartsFromBones(reference);
  run.report.metric("registration_parts", o.registration == "plain" ? 1 : long(parts.order.size()));
  const std::vector<transfer::SkinLandmark> landmarks = readSkinLandmarks(o, reference.skin);
  transfer::ReferenceSkinRegistrationOptions registration;
  registration.registration.registration.iterations = o.registrationIterations;
  registration.articulated = o.registration != "plain";
  const transfer::SkinRegistration registered = [&] {
    auto timer = run.report.time("skin registration");
    return transfer::registerReferenceSkin(reference, parts, target.V, target.F, registration, landmarks);
  }();
  run.progress.end();
  run.report.metric("registration_mean_distance_mm", registered.finalMeanDistance);
  run.report.metric("registration_max_distance_mm", registered.finalMaxDistance);
  if (!landmarks.empty()) {
    double sum = 0;
    for (const transfer::SkinLandmark& l : landmarks) sum += (registered.V.row(l.sourceVertex).transpose() - l.target).norm();
    run.report.metric("landmarks", long(landmarks.size()));
    run.report.metric("landmark_mean_error_mm", sum / double(landmarks.size()));
  }

  run.report.metric("registration_scale", registered.alignment.scale);

  patient::TransferIntoBodyOptions pipeline;
  pipeline.registration.registration.iterations = o.registrationIterations;
  pipeline.articulated = o.registration != "plain";
  pipeline.voxelSizeMm = o.voxelSize;
  pipeline.transfer.field.laplace.solver =
      o.laplaceSolver == "cg" ? transfer::LaplaceSolver::ConjugateGradient : transfer::LaplaceSolver::MultigridCG;
  const patient::TransferIntoBody into = patient::transferIntoBody(reference, registered.V, fat, parts, pipeline, &run.progress);
  for (const auto& [stage, seconds] : into.stageSeconds) run.report.stage(stage, seconds);
  if (into.eroded) {
    run.report.metric("erosion_mean_mm", into.erosionMeanMm);
    run.report.metric("erosion_limited_vertices", into.erosionLimited);
    run.report.metric("erosion_new_self_intersections", into.erosionNewSelfIntersections);
    run.report.metric("sub_fat_registration_mean_distance_mm", into.subFatMeanDistanceMm);
    run.report.metric("sub_fat_registration_scale", into.subFatScale);
  }
  const transfer::TransferredAnatomy& result = into.transferred;
  const GridGeometry& grid = into.grid;
  run.report.metric("grid", {grid.size.x(), grid.size.y(), grid.size.z()});
  const auto iterations = [](const transfer::DisplacementField& f) {
    return nlohmann::json{f.solves[0].iterations, f.solves[1].iterations, f.solves[2].iterations};
  };
  run.report.metric("laplace_iterations", {{"skin_field", iterations(result.skinField)}, {"final_field", iterations(result.finalField)}});
  run.report.metric("unfold_passes", result.finalField.unfoldPasses);
  run.report.metric("unfold_released_cells", result.finalField.releasedCells);
  const transfer::TransferRules checked = [&] {
    auto timer = run.report.time("checks");
    // The rules on the body the pipeline made of the registered skin (with its cavities): the eroded one
    // is that unless fat was eroded; a vertex one field voxel inside the reference's skin counts as deep.
    const meshing::BodyDistance body =
        into.eroded ? meshing::bodySignedDistance(into.anatomy.skin) : into.erodedBody;
    transfer::AnatomyRulesOptions rulesOptions;
    rulesOptions.skinDistance = &body.signedDistance;
    rulesOptions.skinCavities = &body.cavities;
    rulesOptions.referenceSkinDistance = &into.referenceBody.signedDistance;
    rulesOptions.referenceSkinCavities = &into.referenceBody.cavities;
    rulesOptions.deepMm = o.voxelSize;
    transfer::TransferRules c = transfer::checkTransferRules(reference, into.anatomy, result, rulesOptions);
    reportTransferRules(reference, into, c, body, o.voxelSize, run.report);
    return c;
  }();
  const transfer::AnatomyRules& rules = checked.rules;
  {
    auto timer = run.report.time("writing");
    writeTransferOutputs(reference, into, o.out, o.png, o.common.writeOptions(), run.report);
  }
  std::cout << std::fixed << std::setprecision(2) << o.out << ": " << reference.tissues.size()
            << " tissues transferred; skin registered to " << registered.finalMeanDistance << " mm (mean), "
            << result.boneGroups.size() << " bone groups, Jacobian min " << rules.folds.jacobian.minimum << ", "
            << rules.outside.pushedOut << " tissue vertices pushed out of the skin\n";
}

}  // namespace

void addTransferCommand(CLI::App& app) {
  auto o = std::make_shared<TransferOptions>();
  CLI::App* cmd = app.add_subcommand("transfer", "Carry a reference anatomy into a target body surface (Dicko et al. 2013)");
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
                  "Fat from per-bone amounts instead (Dicko et al. 2013, §6): a JSON object as `fat edit --amounts` takes it, "
                  "with that command's defaults")
      ->excludes(fatOption);
  cmd->add_option("--voxel-size", o->voxelSize, "Voxel size of the displacement field's grid, mm")->capture_default_str();
  cmd->add_option("--laplace-solver", o->laplaceSolver,
                  "Solver of the two Laplace fields: mg (multigrid-preconditioned CG) or cg (Jacobi-preconditioned "
                  "CG, the paper's baseline, for benchmarks); both stop at the same relative residual")
      ->check(CLI::IsMember({"mg", "cg"}))
      ->capture_default_str();
  cmd->add_option("--registration-iterations", o->registrationIterations, "ICP iterations of the skin registration")
      ->capture_default_str();
  CLI::Option* referenceLandmarks =
      cmd->add_option("--reference-landmarks", o->referenceLandmarks,
                      "Landmarks on the reference skin (markups, LPS mm), paired by label with --target-landmarks: "
                      "they start the skin registration where the bodies are far apart or turned (Dicko et al. 2013, §4)");
  CLI::Option* targetLandmarks = cmd->add_option(
      "--target-landmarks", o->targetLandmarks, "Their partners on the target skin (markups, LPS mm, as the target is after --space)");
  referenceLandmarks->needs(targetLandmarks);
  targetLandmarks->needs(referenceLandmarks);
  cmd->add_option("--registration", o->registration,
                  "Skin registration: articulated (the reference skin cut into parts by its bones, limbs turned about "
                  "their joints before ICP with shape matching) or plain (ICP with shape matching alone, Dicko et al. 2013, §4)")
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
  cmd->callback(
      [o] { runCommand("transfer", o->common, [&](CommandRun& run) { runTransfer(*o, run); }, kTransferStages); });
}

}  // namespace vesalius::cli
