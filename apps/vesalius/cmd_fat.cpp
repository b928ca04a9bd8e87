// vesalius fat: subcutaneous fat thickness from segmented skin and fat (Dicko et al. 2013, §5).
//   forest   the forest of shortest paths from the skin through the fat: a thickness image (mm on skin
//            voxels) and, given a skin surface, the thickness at its vertices as a point attribute.
//   erode    the skin surface moved inward by the thickness, along the forest's paths where given.
//   texture  the thickness at a skin surface's vertices rasterized into its uv texture.
//   edit     the fat editor (§6): per-bone fat amounts over bounded biharmonic weights of a reference's
//            bones, as a texture on the reference skin's uv and a picture of the body.
#include "bone_fat_amounts.h"
#include "command_runner.h"
#include "common.h"
#include "fat_outputs.h"
#include "thickness_input.h"

#include "vesalius/core/error.h"
#include "vesalius/fat/erode_skin.h"
#include "vesalius/fat/thickness_texture.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/reference_anatomy_io.h"
#include "vesalius/viz/surface_render.h"

#include <cmath>
#include <filesystem>
#include <memory>

namespace vesalius::cli {

namespace {

struct ForestOptions {
  ForestSource source;
  std::string out, surface, outMesh, png;
  CommonOptions common;
};

void runForest(const ForestOptions& o, CommandRun& run) {
  if (o.surface.empty() != o.outMesh.empty()) throw UsageError("fat forest: --surface and --out-mesh go together");
  checkOutputs({o.out, o.outMesh, o.png, o.common.report},
               {o.source.labels, o.source.fatMask, o.surface, o.source.table}, o.common.force);
  if (!o.surface.empty()) run.report.input("surface", o.surface);
  const LoadedForest l = loadForest(o.source, run.report, run.progress);
  writeForestOutputs(l, o.out, o.png, o.common.writeOptions(), run.report);
  if (!o.surface.empty())
    writeThicknessOnSurface(o.surface, o.outMesh, *l.forest, o.source.vertexRadius, o.common.writeOptions(), run.report);
}

void addForestCommand(CLI::App& fatCommand) {
  auto o = std::make_shared<ForestOptions>();
  CLI::App* cmd = fatCommand.add_subcommand(
      "forest", "Fat thickness under the skin by a forest of shortest paths from skin voxels through fat (Dicko et al. 2013, §5)");
  addForestSourceOptions(*cmd, o->source, true);
  cmd->add_option("--out", o->out, "Thickness image: float mm on skin voxels, 0 elsewhere (.nii.gz, .nrrd, .mha)")
      ->required();
  cmd->add_option("--surface", o->surface, "Skin surface mesh (LPS mm) to carry the thickness to");
  cmd->add_option("--out-mesh", o->outMesh,
                  "The surface with point attributes fat_thickness (mm) and fat_thickness_source "
                  "(1 measured, 2 filled from neighbours, 0 none); .vtp or .vtk keep them");
  cmd->add_option("--png", o->png, "Picture of the thickness on the skin over three orthogonal slices");
  addCommonOptions(*cmd, o->common);
  cmd->footer(
      "Example:\n  vesalius segment --scan testdata/ct-abdomen-pelvis/example_ct.nii.gz --modality ct --out ct.nii.gz\n"
      "  vesalius surface --labels ct.nii.gz --label skin --out skin.vtp\n"
      "  vesalius fat forest --labels ct.nii.gz --out thickness.nii.gz --surface skin.vtp --out-mesh skin_fat.vtp");
  cmd->callback([o] { runCommand("fat forest", o->common, [&](CommandRun& run) { runForest(*o, run); }); });
}

struct ErodeOptions {
  ForestSource source;
  std::string skin, thickness, out;
  double pathRadius = 0, maxFraction = 0.5;
  CommonOptions common;
};

// The bar's shares of the forest and the erosion, as a run on the test CT's skin and tissue classes
// (testdata/ct-abdomen-pelvis) times them: 0.1 s and 7.3 s.
const StagePlan kErodeStages{{"fat forest", 0.1}, {"erode", 7.3}};

void runErode(const ErodeOptions& o, CommandRun& run) {
  if (o.thickness.empty() && o.source.labels.empty()) throw UsageError("fat erode: give --thickness, --labels or both");
  checkOutputs({o.out, o.common.report}, {o.skin, o.thickness, o.source.labels, o.source.fatMask, o.source.table},
               o.common.force);
  run.report.input("skin", o.skin);
  TriMesh mesh = io::readTriMesh(o.skin);
  LoadedForest l;
  if (!o.source.labels.empty()) l = loadForest(o.source, run.report, run.progress);
  const Eigen::VectorXd t = vertexThickness(o.thickness, mesh, o.skin, l, o.source, run.report);

  fat::ErodeSkinOptions options;
  options.pathRadiusMm = o.pathRadius;
  options.maxFractionOfInnerRadius = o.maxFraction;
  options.source = o.thickness.empty() ? o.source.labels : o.thickness;
  run.report.parameter("path_radius_mm", o.pathRadius);
  run.report.parameter("max_fraction_of_inner_radius",
                       std::isfinite(o.maxFraction) ? nlohmann::json(o.maxFraction) : nullptr);
  fat::ErodedSkin e;
  {
    auto timer = run.report.time("erode");
    run.progress.begin("erode", "moving the skin inward by the fat thickness");
    e = fat::erodeSkin(mesh.V, mesh.F, t, l.forest.get(), options);
    run.progress.end();
  }
  writeErodedSkin(o.out, std::move(mesh), t, e, o.common.writeOptions(), run.report);
}

void addErodeCommand(CLI::App& fatCommand) {
  auto o = std::make_shared<ErodeOptions>();
  CLI::App* cmd = fatCommand.add_subcommand(
      "erode", "Move a skin surface inward by the fat thickness, along the forest's paths (Dicko et al. 2013, §5, Fig. 2.b)");
  cmd->add_option("--skin", o->skin, "Skin (body) surface mesh, closed, LPS mm")->required();
  cmd->add_option("--thickness", o->thickness,
                  "Fat thickness: a number (mm), a texture image read at the skin's uv (from 'fat texture'), a mesh "
                  "with point attribute fat_thickness, or a text file of one value per vertex; default: from "
                  "the forest of --labels");
  addForestSourceOptions(*cmd, o->source, false);
  cmd->add_option("--out", o->out,
                  "Eroded mesh, same topology, with point attributes fat_thickness, erosion_mm, inner_radius_mm "
                  "and erosion_direction (1 forest path, 2 normal, 0 none); .vtp or .vtk keep them")
      ->required();
  cmd->add_option("--path-radius", o->pathRadius,
                  "Skin voxels within this distance of a vertex offer their forest paths (mm); 0: two voxel diagonals")
      ->capture_default_str();
  cmd->add_option("--max-fraction", o->maxFraction,
                  "A vertex moves at most this fraction of the largest inner ball touching it (0 to 1; inf: no limit)")
      ->capture_default_str();
  addCommonOptions(*cmd, o->common);
  cmd->footer(
      "Example:\n  vesalius fat erode --skin body.vtp --labels ct.nii.gz --out eroded.vtp --report erode.json\n"
      "  vesalius fat erode --skin body.obj --thickness 5 --out eroded.obj");
  cmd->callback(
      [o] { runCommand("fat erode", o->common, [&](CommandRun& run) { runErode(*o, run); }, kErodeStages); });
}

struct TextureOptions {
  ForestSource source;
  std::string skin, thickness, out, png;
  int size = 1024;
  CommonOptions common;
};

// The bar's shares of the forest and the texture, as a run on the test CT's body with a uv (1024 texels,
// tests/fat/cli_fat_test.cpp) times them: 0.007 s and 0.32 s.
const StagePlan kTextureStages{{"fat forest", 0.007}, {"texture", 0.32}};

void runTexture(const TextureOptions& o, CommandRun& run) {
  if (o.thickness.empty() && o.source.labels.empty()) throw UsageError("fat texture: give --thickness or --labels");
  checkOutputs({o.out, o.png, o.common.report},
               {o.skin, o.thickness, o.source.labels, o.source.fatMask, o.source.table}, o.common.force);
  run.report.input("skin", o.skin);
  const TriMesh mesh = io::readTriMesh(o.skin);
  if (mesh.UV.rows() == 0) throw BadInput(o.skin, "the mesh has no texture coordinates (uv)");
  LoadedForest l;
  if (o.thickness.empty()) l = loadForest(o.source, run.report, run.progress);
  const Eigen::VectorXd t = vertexThickness(o.thickness, mesh, o.skin, l, o.source, run.report);

  fat::ThicknessTextureOptions options;
  options.width = options.height = o.size;
  run.report.parameter("size", o.size);
  fat::ThicknessTexture tex;
  {
    auto timer = run.report.time("texture");
    run.progress.begin("texture", "rasterizing the thickness over the uv charts");
    tex = fat::rasterizeThickness(mesh, t, options, o.skin);
    run.progress.end();
  }
  writeTextureOutputs(o.out, o.png, mesh, o.skin, t, tex, o.common.writeOptions(), run.report);
}

void addTextureCommand(CLI::App& fatCommand) {
  auto o = std::make_shared<TextureOptions>();
  CLI::App* cmd = fatCommand.add_subcommand(
      "texture", "Rasterize the fat thickness at a skin's vertices into its uv texture (Dicko et al. 2013, §5)");
  cmd->add_option("--skin", o->skin, "Skin surface mesh with texture coordinates (.obj, .vtp, .ply), LPS mm")
      ->required();
  cmd->add_option("--thickness", o->thickness,
                  "Fat thickness at the vertices instead of a forest: a number (mm), a mesh with point attribute "
                  "fat_thickness, or a text file of one value per vertex");
  addForestSourceOptions(*cmd, o->source, false);
  cmd->add_option("--size", o->size, "Texture width and height in texels")->capture_default_str()->check(
      CLI::Range(1, 16384));
  cmd->add_option("--out", o->out,
                  "Float texture (.nrrd, .nii.gz, .mha): W x H x 1, thickness in mm; physical space: the uv square")
      ->required();
  cmd->add_option("--png", o->png, "Picture of the texture (v up), filled texels at half brightness");
  addCommonOptions(*cmd, o->common);
  cmd->footer(
      "Example:\n"
      "  vesalius fat texture --skin skin_uv.obj --labels ct.nii.gz --size 1024 --out fat.nrrd --png fat.png\n"
      "  vesalius fat erode --skin other_skin_uv.obj --thickness fat.nrrd --out eroded.vtp");
  cmd->callback(
      [o] { runCommand("fat texture", o->common, [&](CommandRun& run) { runTexture(*o, run); }, kTextureStages); });
}

struct EditOptions {
  EditOutputs outputs;
  std::string reference, amounts;
  fat::BoneFatAmountsOptions fat;
  CommonOptions common;
};

void runEdit(const EditOptions& o, CommandRun& run) {
  const EditOutputs& out = o.outputs;
  if (out.out.empty() && out.outMesh.empty()) throw UsageError("fat edit: give --out, --out-mesh or both");
  if (!out.png.empty() && out.out.empty()) throw UsageError("fat edit: --png is a picture of the texture of --out");
  if (!out.bodyPng.empty() && !viz::canRenderSurfaces())
    throw UsageError("fat edit: --body-png needs a display (run under xvfb-run)");
  checkOutputs({out.out, out.outMesh, out.png, out.bodyPng, o.common.report}, {o.amounts}, o.common.force);
  run.report.input("reference", o.reference);
  run.report.input("amounts", o.amounts);
  TriMesh skin;
  Eigen::VectorXd t;
  {
    const ReferenceAnatomy reference = io::readReferenceAnatomy(o.reference);
    run.progress.begin("bone weights", "bounded biharmonic weights of the bones on a voxel grid");
    t = boneFatAtSkin(reference, o.reference, o.amounts, o.fat, run.report);
    run.progress.end();
    skin = reference.skin;
  }
  const std::string skinPath = (std::filesystem::path(o.reference) / "skin.obj").string();
  writeEditOutputs(out, std::move(skin), skinPath, t, o.common.writeOptions(), run.report);
}

void addEditCommand(CLI::App& fatCommand) {
  auto o = std::make_shared<EditOptions>();
  CLI::App* cmd = fatCommand.add_subcommand(
      "edit", "Fat editor: per-bone fat amounts over bounded biharmonic weights of a reference's bones (Dicko et al. 2013, §6)");
  cmd->add_option("--reference", o->reference, "Reference anatomy folder (from `vesalius reference`)")->required();
  cmd->add_option("--amounts", o->amounts,
                  "JSON object of bone (group) names and fat amounts, e.g. {\"pelvis\": 0.4, \"torso\": 0}; an amount "
                  "is a fraction of --max-thickness")
      ->required();
  cmd->add_option("--default-amount", o->fat.defaultAmount, "Amount of the bones the file does not name")->capture_default_str();
  cmd->add_option("--max-thickness", o->fat.maxThicknessMm, "Thickness an amount of 1 gives (mm)")->capture_default_str();
  cmd->add_option("--voxel-size", o->fat.voxelSizeMm, "Voxel size of the weights' grid (mm)")->capture_default_str();
  cmd->add_option("--out", o->outputs.out,
                  "Float texture on the reference skin's uv (.nrrd, .nii.gz, .mha), W x H x 1, mm; for `transfer --fat`");
  cmd->add_option("--size", o->outputs.size, "Texture width and height in texels")->capture_default_str()->check(CLI::Range(1, 16384));
  cmd->add_option("--png", o->outputs.png, "Picture of the texture (v up)");
  cmd->add_option("--out-mesh", o->outputs.outMesh,
                  "The reference skin with point attribute fat_thickness (mm; .vtp, .vtk); for `transfer --fat` "
                  "when the skin has no uv");
  cmd->add_option("--body-png", o->outputs.bodyPng, "Picture of the body coloured by thickness, from the front; needs a display");
  addCommonOptions(*cmd, o->common);
  cmd->footer(
      "Example:\n  echo '{\"pelvis\": 0.4, \"torso\": 0}' > amounts.json\n"
      "  vesalius fat edit --reference ref --amounts amounts.json --out fat.nrrd --png fat.png --body-png body.png\n"
      "  vesalius transfer --reference ref --target-skin body.obj --fat fat.nrrd --out target\n"
      "Bones are the reference's bone groups (a bone without a group by its name); see docs/methods/fat-thickness.md.");
  cmd->callback([o] { runCommand("fat edit", o->common, [&](CommandRun& run) { runEdit(*o, run); }); });
}

}  // namespace

void addFatCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "fat", "Subcutaneous fat: thickness from segmented skin and fat, erosion, texture (Dicko et al. 2013, §5), editor (§6)");
  cmd->require_subcommand(1);
  addForestCommand(*cmd);
  addErodeCommand(*cmd);
  addTextureCommand(*cmd);
  addEditCommand(*cmd);
}

}  // namespace vesalius::cli
