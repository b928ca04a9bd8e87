// vesalius fit: a template organ fitted to markers picked on a scan by plastic strains (fit/template_fit.h,
// Wang et al. 2021). Reads the template, markers, bone and embedded surface, runs the fit, writes the fitted tets and
// surfaces, the report (per-marker errors and their histogram, Fig. 16; the objective per iteration, Fig. 9;
// the minimum dihedral angles before and after, Fig. 17) and a picture: the fitted surface's contour over
// the scan's slices (Fig. 18) beside the error histogram.
#include "command_runner.h"
#include "common.h"
#include "fit_report.h"

#include "vesalius/core/error.h"
#include "vesalius/core/markers.h"
#include "vesalius/fit/template_fit.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/marker_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/viz/rgb_image.h"

#include <chrono>
#include <filesystem>
#include <iostream>

namespace vesalius::cli {

namespace {

struct FitCommandOptions {
  std::string templ, icp, templateLandmarks, scanLandmarks, attachTo, attachments;
  std::string out, surfaceOut, embed, embedOut, overlay, png;
  bool unattached = false;
  std::string method = "plastic", init = "similarity";
  double window = 400, level = 40;
  fit::TemplateFitOptions fit;
  CommonOptions common;
};

void checkOptions(const FitCommandOptions& o) {
  if (int(!o.attachTo.empty()) + int(!o.attachments.empty()) + int(o.unattached) != 1)
    throw UsageError(
        "fit: say how the organ is held, with exactly one of --attach-to BONE --attach-radius R, "
        "--attachments P and --unattached");
  if (o.attachTo.empty() != !(o.fit.attachRadius > 0))
    throw UsageError("fit: --attach-to and --attach-radius go together");
  if (!o.templateLandmarks.empty() && o.scanLandmarks.empty())
    throw UsageError("fit: --template-landmarks needs --scan-landmarks");
  if (o.embed.empty() != o.embedOut.empty()) throw UsageError("fit: --embed and --embed-out go together");
  if (o.overlay.empty() != o.png.empty()) throw UsageError("fit: --overlay and --png go together");
  if (o.fit.refit.refits > 0 && o.method != "plastic")
    throw UsageError("fit: --refits refits plastic strains; the elastic baseline has none");
  for (const std::string& out : {o.out, o.surfaceOut, o.embedOut, o.png, o.common.report})
    if (!out.empty() && !o.common.force && std::filesystem::exists(out))
      throw UsageError(out + ": exists; pass --force to replace it");
}

void reportInputs(const FitCommandOptions& o, io::Report& report) {
  const std::pair<const char*, const std::string*> inputs[] = {
      {"template", &o.templ}, {"icp", &o.icp}, {"template_landmarks", &o.templateLandmarks},
      {"scan_landmarks", &o.scanLandmarks}, {"attach_to", &o.attachTo}, {"attachments", &o.attachments},
      {"embed", &o.embed}, {"overlay", &o.overlay}};
  for (const auto& [name, path] : inputs)
    if (!path->empty()) report.input(name, *path);
  const fit::FitOptions& s = o.fit.solver;
  const std::pair<const char*, nlohmann::json> parameters[] = {
      {"method", o.method}, {"init", o.init}, {"attach_radius_mm", o.fit.attachRadius}, {"unattached", o.unattached},
      {"target_tets", o.fit.tets.targetTets}, {"template_faces", o.fit.tets.faces}, {"refits", o.fit.refit.refits},
      {"refit_icp_iterations", o.fit.refit.icpIterations}, {"icp_iterations", s.icpIterations},
      {"max_icp_error_mm", s.maxIcpError}, {"min_icp_gain", s.minIcpGain}, {"min_icp_gain_mm", s.minIcpGainMm},
      {"marker_weight", s.markerWeight}, {"attachment_weight", s.attachmentWeight}};
  for (const auto& [name, value] : parameters) report.parameter(name, value);
}

fit::TemplateFitInputs readInputs(const FitCommandOptions& o, io::Report& report) {
  fit::TemplateFitInputs in;
  in.templateSource = o.templ;
  in.fittedName = o.out;
  {
    auto timer = report.time("read template");
    const std::optional<io::MeshKind> kind = io::meshFileKind(o.templ);
    if (!kind)
      throw BadInput(o.templ, "not a mesh file: give a tet mesh (.vtu .vtk .msh .mesh .ele) or a closed surface");
    if (*kind == io::MeshKind::kTetrahedral)
      in.templateTets = io::readTetMesh(o.templ);
    else
      in.templateSurface = io::readTriMesh(o.templ);
  }
  auto timer = report.time("read markers");
  const auto read = [](const std::string& path, MarkerKind kind) {
    return fit::SourcedMarkers{io::readMarkers(path, io::MarkerReadOptions{kind}), path};
  };
  in.icp = read(o.icp, MarkerKind::IcpMarker);
  if (!o.templateLandmarks.empty()) in.templateLandmarks = read(o.templateLandmarks, MarkerKind::Landmark);
  if (!o.scanLandmarks.empty()) in.scanLandmarks = read(o.scanLandmarks, MarkerKind::Landmark);
  if (!o.attachments.empty()) in.attachments = read(o.attachments, MarkerKind::Attachment);
  if (!o.attachTo.empty()) in.bone = io::readTriMesh(o.attachTo);
  in.boneSource = o.attachTo;
  if (!o.embed.empty()) in.embed = io::readTriMesh(o.embed);
  return in;
}

void printNotes(const FitCommandOptions& o, const fit::TemplateFit& f) {
  if (f.repair)
    std::cerr << o.templ << ": not a closed 2-manifold (" << f.repair->boundaryEdges << " boundary edges, "
              << f.repair->nonManifoldEdges << " non-manifold edges, " << f.repair->crossingTrianglePairs
              << " crossing triangle pairs); closed by its winding number into " << f.repair->closedTriangles
              << " triangles, which are tetrahedralized and carried to --surface-out\n";
  // A whole bone also holds the organ where other tissue lies between them (fit/attachments.h).
  if (f.attachedToClosedBone)
    std::cerr << "vesalius: note: " << o.attachTo << " is closed (a whole bone): all "
              << f.markers.attachmentMaterial.rows() << " of its vertices within " << o.fit.attachRadius
              << " mm of the template hold it; to attach at the insertion only, give the bone's interface with the "
                 "organ (vesalius surface --label BONE --shared --touching ORGAN)\n";
}

void runFit(FitCommandOptions o, CommandRun& run) {
  const auto started = std::chrono::steady_clock::now();
  checkOptions(o);
  o.fit.method = o.method == "elastic" ? fit::FitMethod::Elastic : fit::FitMethod::Plastic;
  o.fit.placeBySimilarity = o.init == "similarity";
  reportInputs(o, run.report);
  const fit::TemplateFit f = fit::fitTemplate(readInputs(o, run.report), o.fit, &run.progress);
  for (const auto& [stage, seconds] : f.stageSeconds) run.report.stage(stage, seconds);
  printNotes(o, f);
  {
    auto timer = run.report.time("write meshes");
    const io::MeshWriteOptions write{o.common.writeOptions()};
    io::writeTetMesh(o.out, f.fitted, write);
    run.report.output("fitted", o.out);
    if (!o.surfaceOut.empty()) io::writeTriMesh(o.surfaceOut, f.surface, write);
    if (!o.surfaceOut.empty()) run.report.output("surface", o.surfaceOut);
    if (f.embedded) io::writeTriMesh(o.embedOut, *f.embedded, write);
    if (f.embedded) run.report.output("embedded", o.embedOut);
  }
  if (!o.png.empty()) {
    auto timer = run.report.time("picture");
    viz::writePng(o.png, fitPicture(io::readScan(o.overlay), f, o.window, o.level), o.common.writeOptions());
    run.report.output("png", o.png);
  }
  reportFit(f, run.report);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  printFitSummary(o.out, o.method, f, seconds);
}

}  // namespace

void addFitCommand(CLI::App& app) {
  auto o = std::make_shared<FitCommandOptions>();
  CLI::App* cmd =
      app.add_subcommand("fit", "Fit a template organ to markers picked on a scan (plastic strains, Wang et al. 2021)");
  cmd->add_option("--template", o->templ,
                  "Template: tet mesh (.vtu .vtk .msh .mesh .ele) or surface (.stl .obj .ply .vtp; one that is "
                  "open, non-manifold or self-crossing is closed by its winding number first), in its own "
                  "(template) space, mm")->required();
  cmd->add_option("--icp", o->icp,
                  "ICP markers on the organ's boundary in the scan (.mrk.json .fcsv .csv): every "
                  "defined point that is not a landmark or an attachment")->required();
  cmd->add_option("--template-landmarks", o->templateLandmarks, "Landmarks on the template, paired by label");
  cmd->add_option("--scan-landmarks", o->scanLandmarks,
                  "The same landmarks in the scan; alone, each must carry its template position");
  cmd->add_option("--attach-to", o->attachTo,
                  "Bone surface (world mm) the organ inserts on: the insertion itself (from labels: surface "
                  "--label BONE --shared --touching MUSCLE), since of a whole bone every vertex within "
                  "--attach-radius is attached");
  cmd->add_option("--attach-radius", o->fit.attachRadius,
                  "Bone vertices within this distance (mm) of the placed template are attached");
  cmd->add_option("--attachments", o->attachments,
                  "Attachment markers: position = bone point, template position = organ point");
  cmd->add_flag("--unattached", o->unattached, "The organ is free (a liver, a bone): no attachments (Wang et al. 2021, §3.6)");
  cmd->add_option("--out", o->out,
                  "Fitted tet mesh (.vtu ...): the template's tets and fields, plus "
                  "plastic_stretch_min and plastic_stretch_max per tet")->required();
  cmd->add_option("--surface-out", o->surfaceOut, "Fitted surface (.vtp .stl .obj .ply)");
  cmd->add_option("--embed", o->embed, "A surface in template space (e.g. textured) to carry along");
  cmd->add_option("--embed-out", o->embedOut, "Where the carried surface goes");
  cmd->add_option("--overlay", o->overlay, "Scan to draw the fitted contour on (with --png)");
  cmd->add_option("--png", o->png,
                  "Picture: the contour over three slices through the markers, and the error histogram");
  cmd->add_option("--window", o->window, "Grey window of the picture, scan units")->capture_default_str();
  cmd->add_option("--level", o->level, "Grey level of the picture, scan units")->capture_default_str();
  cmd->add_option("--method", o->method, "plastic (Wang et al. 2021) or elastic (the FEM baseline of its Fig. 2)")
      ->check(CLI::IsMember({"plastic", "elastic"}))->capture_default_str();
  cmd->add_option("--init", o->init,
                  "similarity: placed from landmark pairs (3 or more) or by ICP to the markers; "
                  "none: the template as it is")->check(CLI::IsMember({"similarity", "none"}))->capture_default_str();
  cmd->add_option("--iterations", o->fit.solver.icpIterations, "Most iterations of the ICP stage")
      ->check(CLI::Range(0, 1000))->capture_default_str();
  cmd->add_option("--max-icp-error", o->fit.solver.maxIcpError,
                  "The ICP stage stops when every marker is this close (mm)")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  cmd->add_option("--min-icp-gain", o->fit.solver.minIcpGain,
                  "The ICP stage stops when two iterations lower the mean ICP error by less than this fraction "
                  "of it (0: off)")->check(CLI::Range(0.0, 1.0))->capture_default_str();
  cmd->add_option("--min-icp-gain-mm", o->fit.solver.minIcpGainMm,
                  "The ICP stage stops when two iterations lower the mean ICP error by less than this (mm; 0: off)")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  cmd->add_option("--marker-weight", o->fit.solver.markerWeight,
                  "alpha of Wang et al.'s eq. 3 per mm^2: higher meets the markers more closely, lower keeps Fp smoother")
      ->check(CLI::PositiveNumber)->capture_default_str();
  cmd->add_option("--attachment-weight", o->fit.solver.attachmentWeight,
                  "beta of Wang et al.'s eq. 3 per mm^2: how much the attachments' elastic work counts")
      ->check(CLI::PositiveNumber)->capture_default_str();
  cmd->add_option("--target-tets", o->fit.tets.targetTets,
                  "About this many tets for a surface template (within twice it: a surface finer than that allows "
                  "is coarsened for TetGen, and its own triangles are carried to --surface-out)")
      ->check(CLI::Range(100L, 5000000L))->capture_default_str();
  cmd->add_option("--template-faces", o->fit.tets.faces,
                  "Coarsen a surface template to about this many triangles before tetrahedralizing it instead of "
                  "as --target-tets allows; the full surface is still carried to --surface-out. 0: as the target "
                  "allows")->check(CLI::Range(0, 100000000))->capture_default_str();
  cmd->add_option("--refits", o->fit.refit.refits,
                  "Fit again up to this many times, each from the fitted shape tetrahedralized afresh (about "
                  "--target-tets tets, or at --template-faces), while a marker is farther than --max-icp-error and the "
                  "fitted shape meshes within twice --target-tets: "
                  "for a template far from the organ, whose first fit crushes its tets and stalls. --out and "
                  "--surface-out then hold the last refit's tets and their boundary; --embed-out is carried "
                  "through every round (smoothly through the refits)")->check(CLI::Range(0, 20))->capture_default_str();
  cmd->add_option("--refit-iterations", o->fit.refit.icpIterations, "Most ICP iterations of each refit")
      ->check(CLI::Range(1, 1000))->capture_default_str();
  addCommonOptions(*cmd, o->common);
  cmd->footer(
      "Examples:\n  vesalius fit --template liver.vtu --icp liver_icp.mrk.json --unattached --out liver_fitted.vtu "
      "--overlay ct.nii.gz --png liver_fit.png --report liver_fit.json\n"
      "  vesalius fit --template liver.obj --icp liver_icp.mrk.json --unattached --refits 3 --out liver_fitted.vtu "
      "--surface-out liver_fitted.vtp\n"
      "  vesalius fit --template muscle.stl --icp icp.mrk.json --template-landmarks tl.mrk.json --scan-landmarks "
      "sl.mrk.json --attach-to insertion.vtp --attach-radius 5 --out muscle.vtu --surface-out muscle.vtp\n"
      "Landmarks pair by label; a label without a partner is refused (exit 3), a pair with an undefined point "
      "skipped.");
  cmd->callback([o] { runCommand("fit", o->common, [&](CommandRun& run) { runFit(*o, run); }); });
}

}  // namespace vesalius::cli
