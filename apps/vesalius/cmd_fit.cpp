// vesalius fit: a template organ (tet mesh, or a surface tetrahedralized first, closed first if it is not)
// fitted to markers picked on a scan by plastic strains (seed 002): ICP markers and landmarks (§3.1),
// attachments to a bone (§3.3, §4.1.2) or none (§3.6), a surface embedded in the template carried along
// (§4.3). The report holds what the seed plots: per-marker errors and their histogram (Fig. 16), the
// objective per iteration (Fig. 9), the minimum dihedral angles before and after (Fig. 17); the picture
// shows the fitted surface's contour over the scan's slices (Fig. 18) beside the error histogram.
#include "common.h"

#include "landmark_pairs.h"

#include "vesalius/core/error.h"
#include "vesalius/core/markers.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/self_intersections.h"
#include "vesalius/core/tet_quality.h"
#include "vesalius/fem/plastic_fem.h"
#include "vesalius/fem/plastic_strain.h"
#include "vesalius/fit/attachments.h"
#include "vesalius/fit/embedding.h"
#include "vesalius/fit/initial_placement.h"
#include "vesalius/fit/plastic_fit.h"
#include "vesalius/fit/point_constraints.h"
#include "vesalius/fit/refit.h"
#include "vesalius/fit/surface_projection.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/marker_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/meshing/closed_surface.h"
#include "vesalius/meshing/mesh_volume.h"
#include "vesalius/meshing/tet_budget.h"
#include "vesalius/meshing/tetrahedralize.h"
#include "vesalius/segmentation/label_ops.h"
#include "vesalius/viz/slice_overlay.h"
#include "vesalius/viz/text.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>
#include <utility>

namespace vesalius::cli {

namespace {

struct FitCommandOptions {
  std::string templ, icp, templateLandmarks, scanLandmarks, attachTo, attachments;
  std::string out, surfaceOut, embed, embedOut, overlay, png;
  double attachRadius = 0;
  bool unattached = false;
  std::string method = "plastic", init = "similarity";
  long targetTets = 20000;
  int templateFaces = 0;  // coarsen a surface template to this many triangles first; 0: as targetTets allows
  double window = 400, level = 40;
  fit::FitOptions solver;
  fit::RefitOptions refit;  // refits: 0 is seed 002's fit alone
  CommonOptions common;
};

struct FitOutcome {
  long tets = 0;  // of the last round's mesh (the template's unless refitted)
  Eigen::VectorXd icpBefore, icpAfter;  // #icp marker distances to the surface, mm
  double seconds = 0;
};


namespace fs = std::filesystem;

constexpr double kIcpBinMm = 0.25;       // Fig. 16 histogram bins
constexpr double kDihedralBinDeg = 5.0;  // Fig. 17 histogram bins

// ---- Options ----

void refuseExisting(const FitCommandOptions& o, const std::vector<std::string>& outputs) {
  const std::vector<std::string> inputs{
      o.templ, o.icp, o.templateLandmarks, o.scanLandmarks, o.attachTo, o.attachments, o.embed, o.overlay};
  for (const std::string& out : outputs) {
    if (out.empty()) continue;
    std::error_code ec;
    for (const std::string& in : inputs)
      if (!in.empty() && fs::equivalent(in, out, ec))
        throw UsageError(out + ": is also an input; choose another output");
    if (!o.common.force && fs::exists(out)) throw UsageError(out + ": exists; pass --force to replace it");
  }
}

void checkOptions(const FitCommandOptions& o) {
  if (int(!o.attachTo.empty()) + int(!o.attachments.empty()) + int(o.unattached) != 1)
    throw UsageError(
        "fit: say how the organ is held, with exactly one of --attach-to BONE --attach-radius R, "
        "--attachments P and --unattached");
  if (o.attachTo.empty() != !(o.attachRadius > 0)) throw UsageError("fit: --attach-to and --attach-radius go together");
  if (!o.templateLandmarks.empty() && o.scanLandmarks.empty())
    throw UsageError("fit: --template-landmarks needs --scan-landmarks");
  if (o.embed.empty() != o.embedOut.empty()) throw UsageError("fit: --embed and --embed-out go together");
  if (o.overlay.empty() != o.png.empty()) throw UsageError("fit: --overlay and --png go together");
  if (o.refit.refits > 0 && o.method != "plastic")
    throw UsageError("fit: --refits refits plastic strains; the elastic baseline has none");
  refuseExisting(o, {o.out, o.surfaceOut, o.embedOut, o.png, o.common.report});
}

// ---- Template ----

struct Template {
  TetMesh tets;
  std::optional<TriMesh> surface;  // the surface a surface template was tetrahedralized from
};

// A surface template that is not a closed 2-manifold or whose triangles cross (OpenSim's bones are such)
// cannot be tetrahedralized: it is closed by its winding number (meshing/closed_surface.h) at
// --template-faces or, without it, its own face count, and stderr says so. nullopt when it needs nothing.
std::optional<TriMesh> closedTemplate(const FitCommandOptions& o, const TriMesh& surface, io::Report& report) {
  const EdgeCounts edges = countEdges(surface.F);
  const std::size_t crossings = surface.F.rows() ? selfIntersections(surface.V, surface.F).size() : 0;
  if (edges.boundary == 0 && edges.nonManifold == 0 && crossings == 0) return std::nullopt;
  meshing::ClosedSurfaceOptions options;
  options.targetFaces = o.templateFaces > 0 ? o.templateFaces : int(surface.F.rows());
  TriMesh closed;
  try {
    closed = meshing::closedSurface(surface, options);
  } catch (const BadInput& e) {
    throw BadInput(o.templ, e.problem());
  }
  std::cerr << o.templ << ": not a closed 2-manifold (" << edges.boundary << " boundary edges, " << edges.nonManifold
            << " non-manifold edges, " << crossings << " crossing triangle pairs); closed by its winding number into "
            << closed.F.rows() << " triangles, which are tetrahedralized and carried to --surface-out\n";
  report.metric("template_repair", {{"boundary_edges", edges.boundary},
                                    {"non_manifold_edges", edges.nonManifold},
                                    {"crossing_triangle_pairs", crossings},
                                    {"closed_triangles", closed.F.rows()}});
  return closed;
}

// A closed surface that encloses (next to) no volume has no inside for TetGen to fill, and TetGen
// searches for one for minutes; so it is refused first. A millionth of the cube of the bounding box's
// diagonal: a sphere encloses a tenth of it, a plate a hundredth of its width thick still 3e-5.
void refuseFlat(const TriMesh& surface, const std::string& path) {
  if (surface.V.rows() == 0) return;  // the tetrahedralization reports an empty mesh
  const double diagonal = (surface.V.colwise().maxCoeff() - surface.V.colwise().minCoeff()).norm();
  // Thickness across its flattest direction: the root of the smallest variance of the vertices.
  const MatrixX3d centred = surface.V.rowwise() - surface.V.colwise().mean();
  const Eigen::Matrix3d covariance = centred.transpose() * centred / double(surface.V.rows());
  const double thickness = std::sqrt(std::max(0.0, Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvalues()(0)));
  if (thickness <= 1e-6 * diagonal) {
    std::ostringstream text;
    text << "the template's vertices lie in one plane (" << thickness << " mm thick, " << diagonal
         << " mm across): a flat surface has no inside to fill with tets";
    throw BadInput(path, text.str());
  }
  const double volume = std::abs(enclosedVolume(surface.V, surface.F));
  if (volume <= 1e-6 * diagonal * diagonal * diagonal) {
    std::ostringstream text;
    text << "the template encloses " << volume << " mm^3 inside a bounding box " << diagonal
         << " mm across: a flat surface has no inside to fill with tets";
    throw BadInput(path, text.str());
  }
}

Template readTemplate(const FitCommandOptions& o, io::Report& report) {
  const std::optional<io::MeshKind> kind = io::meshFileKind(o.templ);
  if (!kind)
    throw BadInput(o.templ, "not a mesh file: give a tet mesh (.vtu .vtk .msh .mesh .ele) or a closed surface");
  if (*kind == io::MeshKind::kTetrahedral) {
    auto timer = report.time("read template");
    return {io::readTetMesh(o.templ), std::nullopt};
  }
  Template t;
  {
    auto timer = report.time("read template");
    t.surface = io::readTriMesh(o.templ);
  }
  auto timer = report.time("tetrahedralize");
  // The broken original is not kept for --surface-out: its triangles may cross, and the closed surface is
  // what the tets fill (--embed carries the original if wanted).
  refuseFlat(*t.surface, o.templ);  // before closing: the winding number of a flat surface is noise
  if (std::optional<TriMesh> closed = closedTemplate(o, *t.surface, report)) t.surface = std::move(closed);
  refuseFlat(*t.surface, o.templ);
  meshing::TetrahedralizeOptions options;
  options.targetTets = o.targetTets;
  // TetGen meshes a coarsened surface (--template-faces, or as the tet target allows); the template's own
  // surface is carried by the fit to --surface-out.
  if (o.templateFaces > 0) {
    const TriMesh coarse = meshing::coarsenedSurface(*t.surface, o.templateFaces);
    t.tets = meshing::tetrahedralize(coarse, options, o.templ);
    report.metric("tetrahedralized_faces", coarse.F.rows());
  } else {
    meshing::BudgetedTets budgeted = meshing::tetrahedralizeWithinBudget(*t.surface, options, o.templ);
    t.tets = std::move(budgeted.tets);
    report.metric("tetrahedralized_faces", budgeted.surfaceFaces);
  }
  return t;
}

// ---- Markers ----

struct FitInputs {
  fit::FitMarkers points;
  std::vector<std::string> icpLabels, landmarkLabels;
  long skipped = 0;  // undefined or preview points, and points of another kind in the ICP file
};

void append(MatrixX3d& M, const Eigen::Vector3d& p) {
  M.conservativeResize(M.rows() + 1, 3);
  M.row(M.rows() - 1) = p.transpose();
}

// Every defined point of the file that is not a landmark or an attachment.
void readIcpMarkers(const std::string& path, FitInputs& in) {
  const MarkerSet set = io::readMarkers(path, io::MarkerReadOptions{MarkerKind::IcpMarker});
  for (const Marker& m : set.markers) {
    if (m.status != MarkerStatus::Defined || m.kind != MarkerKind::IcpMarker) {
      ++in.skipped;
      continue;
    }
    append(in.points.icp, m.position);
    in.icpLabels.push_back(m.label);
  }
  if (in.points.icp.rows() == 0) throw BadInput(path, "holds no defined ICP markers");
}

// Landmarks paired by label; a pair with an undefined point is skipped, a label without a partner is refused.
void pairLandmarksByLabel(const std::string& templatePath, const std::string& scanPath, FitInputs& in) {
  const LandmarkPairs pairs = pairLandmarks(templatePath, scanPath);
  in.points.templateLandmarks = pairs.first;
  in.points.scanLandmarks = pairs.second;
  in.landmarkLabels = pairs.labels;
  in.skipped += pairs.skipped;
}

// Markers of `kind` that carry their template point (core/markers.h templatePosition): landmarks given
// in the scan file alone, and attachments. Returns template points and scan points, paired by row.
std::pair<MatrixX3d, MatrixX3d> pointsWithTemplatePositions(const std::string& path, MarkerKind kind, FitInputs& in,
                                                            std::vector<std::string>* labels) {
  const MarkerSet set = io::readMarkers(path, io::MarkerReadOptions{kind});
  MatrixX3d material, world;
  for (const Marker* m : markersOfKind(set, kind)) {
    if (m->status != MarkerStatus::Defined) {
      ++in.skipped;
      continue;
    }
    if (!m->templatePosition)
      throw BadInput(path, std::string(markerKindName(kind)) + " '" + m->label + "' has no template position");
    append(material, *m->templatePosition);
    append(world, m->position);
    if (labels) labels->push_back(m->label);
  }
  return {material, world};
}

FitInputs readFitInputs(const FitCommandOptions& o) {
  FitInputs in;
  readIcpMarkers(o.icp, in);
  if (!o.templateLandmarks.empty())
    pairLandmarksByLabel(o.templateLandmarks, o.scanLandmarks, in);
  else if (!o.scanLandmarks.empty())
    std::tie(in.points.templateLandmarks, in.points.scanLandmarks) =
        pointsWithTemplatePositions(o.scanLandmarks, MarkerKind::Landmark, in, &in.landmarkLabels);
  if (!o.attachments.empty())
    std::tie(in.points.attachmentMaterial, in.points.attachmentTargets) =
        pointsWithTemplatePositions(o.attachments, MarkerKind::Attachment, in, nullptr);
  return in;
}

// Attachments hold the organ only if they remove its rigid motions (§3.3: three non-collinear points).
void requireThreeAttachments(const FitInputs& in, const std::string& source, const std::string& advice) {
  const Eigen::Index count = in.points.attachmentMaterial.rows();
  if (count < 3)
    throw BadInput(source, std::to_string(count) + " attachment point(s); an attached organ needs at least 3" + advice);
}

// ---- Placement (Fig. 1: the template starts rigidly aligned, here with a uniform scale) ----

struct Start {
  MatrixX3d x0;        // #V by 3 placed positions
  Eigen::VectorXd s0;  // 6#T: the placement's scale times identity in every tet
  fit::Placement placement;
  std::string from;  // "landmarks", "icp markers" or "none"
};

Start place(const FitCommandOptions& o, const TetMesh& templ, const fit::FitMarkers& points) {
  Start start;
  start.from = "none";
  if (o.init == "similarity") {
    start.placement = fit::placeTemplate(tetBoundarySurface(templ.V, templ.T), points.templateLandmarks,
                                         points.scanLandmarks, points.icp);
    start.from = points.templateLandmarks.rows() >= 3 ? "landmarks" : "icp markers";
  }
  start.x0 = start.placement.transform.apply(templ.V);
  start.s0.resize(6 * templ.T.rows());
  for (Eigen::Index t = 0; t < templ.T.rows(); ++t)
    start.s0.segment<6>(6 * t) = start.placement.transform.scale * identityPlasticStrain();
  return start;
}

void attachToBone(const FitCommandOptions& o, const TetMesh& templ, const Start& start, FitInputs& in) {
  const TriMesh bone = io::readTriMesh(o.attachTo);
  const fit::BoneAttachments a = fit::boneAttachments(start.x0, templ.T, templ.V, bone, o.attachRadius);
  in.points.attachmentMaterial = a.material;
  in.points.attachmentTargets = a.targets;
  requireThreeAttachments(in, o.attachTo, " (bone vertices within --attach-radius of the placed template)");
  // A whole bone also holds the organ where other tissue lies between them (the test CT's gluteus medius
  // on its whole hip bone: 1,226 attachments and 0.76 mm, on its insertion 310 and 0.23 mm).
  if (countEdges(bone.F).boundary == 0)
    std::cerr << "vesalius: note: " << o.attachTo << " is closed (a whole bone): all " << a.material.rows()
              << " of its vertices within " << o.attachRadius
              << " mm of the template hold it; to attach at the insertion only, give the bone's interface with the "
                 "organ (vesalius surface --label BONE --shared --touching ORGAN)\n";
}

// ---- Measures ----

// Counts of `values` in bins [0, w), [w, 2w), ... up to the bin of the largest value.
std::vector<long> histogram(const Eigen::VectorXd& values, double binWidth) {
  std::vector<long> counts(values.size() ? std::size_t(values.maxCoeff() / binWidth) + 1 : 0, 0);
  for (double v : values) ++counts[std::size_t(std::max(v, 0.0) / binWidth)];
  return counts;
}

// A matrix as JSON rows (a row vector as one flat array).
nlohmann::json rows(const Eigen::MatrixXd& M) {
  nlohmann::json out = nlohmann::json::array();
  for (Eigen::Index i = 0; i < M.rows(); ++i) {
    std::vector<double> row;
    for (Eigen::Index j = 0; j < M.cols(); ++j) row.push_back(M(i, j));
    out.push_back(row);
  }
  return M.rows() == 1 ? out[0] : out;
}

nlohmann::json meanAndMax(const Eigen::VectorXd& values) {
  if (values.size() == 0) return {{"mean", 0.0}, {"max", 0.0}};
  return {{"mean", values.mean()}, {"max", values.maxCoeff()}};
}

// Distances (mm) between material points placed with positions V and their targets.
Eigen::VectorXd materialPointErrors(const TetMesh& templ, const MatrixX3d& material, const MatrixX3d& targets,
                                    const MatrixX3d& V) {
  const std::vector<fit::PointConstraint> points = fit::embedMaterialPoints(templ.V, templ.T, material, targets, 1.0);
  const Eigen::VectorXd x = PlasticFem::flatten(V);
  Eigen::VectorXd errors(Eigen::Index(points.size()));
  for (std::size_t k = 0; k < points.size(); ++k)
    errors[Eigen::Index(k)] = (fit::constrainedPoint(points[k], x) - points[k].target).norm();
  return errors;
}

// #T by 3 eigenvalues of each tet's plastic strain Fp (its principal stretches), ascending.
MatrixX3d principalStretches(const Eigen::VectorXd& s) {
  MatrixX3d stretches(s.size() / 6, 3);
  for (Eigen::Index t = 0; t < stretches.rows(); ++t) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(plasticStrainMatrix(s.segment<6>(6 * t)),
                                                             Eigen::EigenvaluesOnly);
    stretches.row(t) = eig.eigenvalues().transpose();
  }
  return stretches;
}

nlohmann::json quantiles(Eigen::VectorXd values) {
  std::sort(values.data(), values.data() + values.size());
  const auto at = [&](double q) { return values[Eigen::Index(std::lround(q * double(values.size() - 1)))]; };
  return {{"min", at(0)}, {"p05", at(0.05)}, {"median", at(0.5)}, {"p95", at(0.95)}, {"max", at(1)}};
}

TetMesh fittedTetMesh(const TetMesh& templ, const fit::FitResult& r, const MatrixX3d& stretches) {
  TetMesh fitted = templ;
  fitted.V = r.V;
  fitted.tetAttributes.real["plastic_stretch_min"] = stretches.col(0);
  fitted.tetAttributes.real["plastic_stretch_max"] = stretches.col(2);
  return fitted;
}

nlohmann::json perMarker(const std::vector<std::string>& labels, const Eigen::VectorXd& before,
                         const Eigen::VectorXd& after) {
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t k = 0; k < labels.size(); ++k)
    rows.push_back(
        {{"label", labels[k]}, {"before_mm", before[Eigen::Index(k)]}, {"after_mm", after[Eigen::Index(k)]}});
  return rows;
}

nlohmann::json iterationRows(const std::vector<fit::FitIteration>& history) {
  nlohmann::json rows = nlohmann::json::array();
  for (const fit::FitIteration& it : history)
    rows.push_back({{"stage", it.stage},
                    {"iteration", it.iteration},
                    {"objective", it.objective},
                    {"smoothness", it.smoothness},
                    {"constraints", it.constraints},
                    {"step", it.step},
                    {"mean_icp_error_mm", it.meanIcpError},
                    {"max_icp_error_mm", it.maxIcpError},
                    {"seconds", it.seconds}});
  return rows;
}

// Fig. 17: the smallest dihedral angle of each tet, its minimum and its histogram.
nlohmann::json dihedralMetrics(const MatrixX3d& V, const MatrixX4i& T) {
  const TetQuality q = tetQuality(V, T);
  return {{"min_deg", q.minDihedral.minCoeff()},
          {"histogram_bin_deg", kDihedralBinDeg},
          {"histogram", histogram(q.minDihedral, kDihedralBinDeg)}};
}

// ---- Picture (Figs. 16, 18) ----

// The fitted surface as label 1 on the scan's grid, drawn as an outline only.
LabelMap fittedLabels(const TriMesh& surface, const GridGeometry& grid) {
  return segmentation::labelMapOf(meshing::meshInsideMask(surface, grid), {1, "fitted surface", {{60, 220, 90}}});
}

Eigen::Vector3i sliceVoxel(const GridGeometry& grid, const MatrixX3d& points) {
  const Eigen::Vector3d index = grid.worldToIndex(points.colwise().mean().transpose());
  Eigen::Vector3i voxel;
  for (int a = 0; a < 3; ++a) voxel[a] = std::clamp(int(std::lround(index[a])), 0, grid.size[a] - 1);
  return voxel;
}

std::string mm(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f mm", value);
  return text;
}

// Bars of the final ICP errors in 0.25 mm bins (at most 80 bars; the last then holds everything beyond).
viz::RgbImage errorHistogramPanel(const Eigen::VectorXd& errors, int height, const viz::Rgb& background) {
  constexpr int kWidth = 380, kPad = 14, kTitle = 16, kSmall = 13, kMaxBars = 80;
  const viz::Rgb text{{235, 235, 235}}, bar{{60, 220, 90}}, axis{{150, 150, 150}};
  viz::RgbImage panel(kWidth, height, background);
  std::vector<long> counts = histogram(errors, kIcpBinMm);
  const bool capped = counts.size() > std::size_t(kMaxBars);
  if (capped) {
    for (std::size_t b = kMaxBars; b < counts.size(); ++b) counts[kMaxBars - 1] += counts[b];
    counts.resize(kMaxBars);
  }
  const int line = viz::measureText("Ag", kSmall).height + 4;
  viz::drawText(panel, kPad, kPad, "ICP marker error after the fit", text, kTitle);
  viz::drawText(
      panel, kPad, kPad + line + 6,
      std::to_string(errors.size()) + " markers, mean " + mm(errors.mean()) + ", max " + mm(errors.maxCoeff()), text,
      kSmall);
  const long highest = *std::max_element(counts.begin(), counts.end());
  const int left = kPad + viz::measureText(std::to_string(highest), kSmall).width + 6, right = kWidth - kPad;
  const int top = kPad + 3 * line + 12, bottom = std::max(top + 20, height - kPad - 2 * line);
  const double barWidth = double(right - left) / double(counts.size());
  for (std::size_t b = 0; b < counts.size(); ++b) {
    const int x0 = left + int(std::lround(double(b) * barWidth)),
              x1 = left + int(std::lround(double(b + 1) * barWidth));
    const int h = int(std::lround(double(bottom - top) * double(counts[b]) / double(highest)));
    panel.fillRect(x0, bottom - h, std::max(1, x1 - x0 - 1), h, bar);
  }
  panel.fillRect(left, bottom, right - left, 1, axis);
  panel.fillRect(left - 1, top, 1, bottom - top + 1, axis);
  viz::drawText(panel, kPad, top, std::to_string(highest), text, kSmall);
  viz::drawText(panel, kPad, bottom - line + 4, "0", text, kSmall);
  const std::string end = (capped ? ">" : "") + mm(double(counts.size()) * kIcpBinMm);
  viz::drawText(panel, left, bottom + 4, "0", text, kSmall);
  viz::drawText(panel, right - viz::measureText(end, kSmall).width, bottom + 4, end, text, kSmall);
  viz::drawText(panel, left, bottom + 4 + line, "markers per 0.25 mm bin", axis, kSmall);
  return panel;
}

void writePicture(const FitCommandOptions& o, const TriMesh& fittedSurface, const fit::FitMarkers& points,
                  const Eigen::VectorXd& icpErrors) {
  const Image scan = io::readScan(o.overlay);
  viz::OverlayOptions overlay;
  overlay.window = o.window;
  overlay.level = o.level;
  overlay.opacity = 0.0;
  overlay.outlineOpacity = 1.0;
  MatrixX3d scanPoints(points.icp.rows() + points.scanLandmarks.rows(), 3);
  scanPoints << points.icp, points.scanLandmarks;
  overlay.voxel = sliceVoxel(scan.geometry, scanPoints);
  const viz::RgbImage slices = viz::renderSliceOverlay(scan, fittedLabels(fittedSurface, scan.geometry), overlay);
  const viz::RgbImage panel = errorHistogramPanel(icpErrors, slices.height, slices.get(0, 0));
  viz::RgbImage canvas(slices.width + panel.width, slices.height, slices.get(0, 0));
  canvas.paste(slices, 0, 0);
  canvas.paste(panel, slices.width, 0);
  viz::writePng(o.png, canvas, o.common.writeOptions());
}

// ---- The command ----

void reportInputs(const FitCommandOptions& o, io::Report& report) {
  const std::pair<const char*, const std::string*> inputs[] = {{"template", &o.templ},
                                                               {"icp", &o.icp},
                                                               {"template_landmarks", &o.templateLandmarks},
                                                               {"scan_landmarks", &o.scanLandmarks},
                                                               {"attach_to", &o.attachTo},
                                                               {"attachments", &o.attachments},
                                                               {"embed", &o.embed},
                                                               {"overlay", &o.overlay}};
  for (const auto& [name, path] : inputs)
    if (!path->empty()) report.input(name, *path);
  report.parameter("method", o.method);
  report.parameter("init", o.init);
  report.parameter("attach_radius_mm", o.attachRadius);
  report.parameter("unattached", o.unattached);
  report.parameter("target_tets", o.targetTets);
  report.parameter("template_faces", o.templateFaces);
  report.parameter("refits", o.refit.refits);
  report.parameter("refit_icp_iterations", o.refit.icpIterations);
  report.parameter("icp_iterations", o.solver.icpIterations);
  report.parameter("max_icp_error_mm", o.solver.maxIcpError);
  report.parameter("min_icp_gain", o.solver.minIcpGain);
  report.parameter("min_icp_gain_mm", o.solver.minIcpGainMm);
  report.parameter("marker_weight", o.solver.markerWeight);
  report.parameter("attachment_weight", o.solver.attachmentWeight);
}

fit::FitResult solve(const FitCommandOptions& o, const TetMesh& templ, const Start& start, const FitInputs& in,
                     Progress& progress) {
  if (o.method == "elastic") return fit::fitElastic(templ, start.x0, start.s0, in.points, o.solver, &progress);
  return fit::fitPlasticStrains(templ, start.x0, start.s0, in.points, o.solver, &progress);
}

// A refit's rest mesh (fit/refit.h): the fitted boundary coarsened as the tet target allows
// (meshing/tet_budget.h), or decimated to --template-faces; either is closed by its winding number instead
// where it crosses itself (a fitted organ can touch itself in a cleft it was pulled into).
TetMesh refitMesh(const FitCommandOptions& o, const TriMesh& fittedBoundary) {
  meshing::TetrahedralizeOptions options;
  options.targetTets = o.targetTets;
  const std::string source = o.out + " (a refit's rest shape)";
  if (o.templateFaces > 0)
    return meshing::tetrahedralize(meshing::coarsenedSurface(fittedBoundary, o.templateFaces), options, source);
  return meshing::tetrahedralizeWithinBudget(fittedBoundary, options, source).tets;
}

// The fit, then its refits (plastic only): the rounds kept, the template's first.
std::vector<fit::FitRound> fitRounds(const FitCommandOptions& o, const TetMesh& templ, const Start& start,
                                     const FitInputs& in, Progress& progress) {
  fit::FitRound first{templ, in.points, solve(o, templ, start, in, progress)};
  if (o.method != "plastic" || o.refit.refits == 0) return {std::move(first)};
  return fit::refit(std::move(first), o.solver, o.refit,
                    [&](const TriMesh& boundary) { return refitMesh(o, boundary); }, &progress);
}

// A surface template keeps its own triangles (and uv, attributes), carried by the fit (§4.3). After
// refits the shape reached is the last round's boundary: the template's triangles, carried through the
// refits smoothly, follow it only as closely as they are fine (the SOFA liver's 274 triangles end 4.2 mm
// from the CT label's boundary where the refitted boundary is at 3.3; plastic-fit.md, "Refits").
TriMesh fittedSurface(const Template& t, const std::vector<fit::FitRound>& rounds) {
  if (rounds.size() > 1) return tetBoundarySurface(rounds.back().result.V, rounds.back().rest.T);
  return fit::carriedSurface(t.surface ? *t.surface : tetBoundarySurface(t.tets.V, t.tets.T), rounds);
}

nlohmann::json roundRows(const std::vector<fit::FitRound>& rounds) {
  nlohmann::json rows = nlohmann::json::array();
  for (const fit::FitRound& round : rounds) {
    const MatrixX3d stretches = principalStretches(round.result.s);
    rows.push_back({{"tets", round.rest.T.rows()},
                    {"iterations", round.result.history.size()},
                    {"icp_error_mm", meanAndMax(round.result.icpErrors)},
                    {"min_dihedral_deg", tetQuality(round.result.V, round.rest.T).minDihedral.minCoeff()},
                    {"plastic_stretches",
                     quantiles(Eigen::Map<const Eigen::VectorXd>(stretches.data(), stretches.size()))}});
  }
  return rows;
}

// rounds: the fit's rounds (fitRounds); the numbers "after" are the last round's, what the outputs hold.
void reportFit(const TetMesh& templ, const Start& start, const FitInputs& in, const Eigen::VectorXd& icpBefore,
               const std::vector<fit::FitRound>& rounds, io::Report& report) {
  const fit::FitMarkers& p = in.points;
  const fit::FitRound& last = rounds.back();
  const fit::FitResult& r = last.result;
  const fit::SimilarityTransform& t = start.placement.transform;
  report.metric("markers", {{"icp", p.icp.rows()},
                            {"landmark_pairs", p.scanLandmarks.rows()},
                            {"attachments", p.attachmentMaterial.rows()},
                            {"skipped", in.skipped}});
  report.metric("placement", {{"from", start.from},
                              {"scale", t.scale},
                              {"translation_mm", rows(t.translation.transpose())},
                              {"rotation", rows(t.rotation)},
                              {"rms_error_mm", start.placement.rmsError}});
  report.metric("attached", r.attached);
  report.metric("mesh", {{"vertices", templ.V.rows()},
                         {"tets", templ.T.rows()},
                         {"fitted_vertices", last.rest.V.rows()},
                         {"fitted_tets", last.rest.T.rows()},
                         {"inverted_after", (tetVolumes(r.V, last.rest.T).array() <= 0).count()}});
  report.metric("icp_error_mm", {{"before", meanAndMax(icpBefore)}, {"after", meanAndMax(r.icpErrors)}});
  report.metric("icp_errors", perMarker(in.icpLabels, icpBefore, r.icpErrors));
  report.metric("icp_error_histogram", {{"bin_mm", kIcpBinMm}, {"counts", histogram(r.icpErrors, kIcpBinMm)}});
  const Eigen::VectorXd landmarksBefore = materialPointErrors(templ, p.templateLandmarks, p.scanLandmarks, start.x0);
  report.metric("landmark_errors", perMarker(in.landmarkLabels, landmarksBefore, r.landmarkErrors));
  report.metric("attachment_error_mm", meanAndMax(materialPointErrors(last.rest, last.markers.attachmentMaterial,
                                                                      p.attachmentTargets, r.V)));
  nlohmann::json iterations = nlohmann::json::array(), ends = nlohmann::json::array();
  for (std::size_t k = 0; k < rounds.size(); ++k) {
    for (nlohmann::json row : iterationRows(rounds[k].result.history)) {
      row["round"] = k;
      iterations.push_back(row);
    }
    for (const fit::FitStageEnd& e : rounds[k].result.stageEnds)
      ends.push_back({{"round", k}, {"stage", e.stage}, {"iterations", e.iterations}, {"stopped_by", e.reason}});
  }
  report.metric("iterations", iterations);
  report.metric("stages", ends);
  report.metric("rounds", roundRows(rounds));
  report.metric("min_dihedral",
                {{"before", dihedralMetrics(start.x0, templ.T)}, {"after", dihedralMetrics(r.V, last.rest.T)}});
  const double volume = tetVolumes(templ.V, templ.T).sum(), fitted = tetVolumes(r.V, last.rest.T).sum();
  report.metric("volume_mm3", {{"template", volume},
                               {"placed", tetVolumes(start.x0, templ.T).sum()},
                               {"fitted", fitted},
                               {"fitted_over_template", fitted / volume}});
  // Fp of the first round, against the template (a refit's is against the shape before it: "rounds").
  const MatrixX3d stretches = principalStretches(rounds.front().result.s);
  report.metric("plastic_stretches", quantiles(Eigen::Map<const Eigen::VectorXd>(stretches.data(), stretches.size())));
}

void printSummary(const FitCommandOptions& o, const TetMesh& templ, const Start& start, const FitInputs& in,
                  const Eigen::VectorXd& before, const std::vector<fit::FitRound>& rounds, double seconds) {
  const fit::FitMarkers& p = in.points;
  const fit::FitResult& r = rounds.back().result;
  long iterations = 0;
  for (const fit::FitRound& round : rounds) iterations += long(round.result.history.size());
  std::cout << o.out << ": " << templ.V.rows() << " vertices, " << templ.T.rows() << " tets fitted (" << o.method
            << ", " << (r.attached ? "attached" : "un-attached") << ") to " << p.icp.rows() << " ICP markers, "
            << p.scanLandmarks.rows() << " landmark pairs, " << p.attachmentMaterial.rows() << " attachments\n"
            << "placement from " << start.from << ", scale " << start.placement.transform.scale << "; "
            << iterations << " iterations in " << std::lround(seconds * 10) / 10.0 << " s\n";
  if (rounds.size() > 1) {
    std::cout << "refitted " << rounds.size() - 1 << " time(s) from the fitted shape; mean ICP error by round:";
    for (const fit::FitRound& round : rounds) std::cout << ' ' << mm(round.result.icpErrors.mean());
    std::cout << "; the last has " << rounds.back().rest.T.rows() << " tets\n";
  }
  std::cout << "ICP error before: mean " << mm(before.mean()) << ", max " << mm(before.maxCoeff()) << "\n"
            << "ICP error after:  mean " << mm(r.icpErrors.mean()) << ", max " << mm(r.icpErrors.maxCoeff()) << "\n";
  if (!r.stageEnds.empty())
    std::cout << "last stage (" << r.stageEnds.back().stage << ") ended by " << r.stageEnds.back().reason << " after "
              << r.stageEnds.back().iterations << " iterations\n";
  if (in.skipped)
    std::cout << in.skipped << " marker(s) skipped: not placed yet, or not ICP markers in the --icp file\n";
}

void writeOutputs(const FitCommandOptions& o, const std::vector<fit::FitRound>& rounds,
                  const TriMesh& fittedSurface, io::Report& report) {
  const io::MeshWriteOptions write{o.common.writeOptions()};
  const fit::FitRound& last = rounds.back();
  io::writeTetMesh(o.out, fittedTetMesh(last.rest, last.result, principalStretches(last.result.s)), write);
  report.output("fitted", o.out);
  if (!o.surfaceOut.empty()) {
    io::writeTriMesh(o.surfaceOut, fittedSurface, write);
    report.output("surface", o.surfaceOut);
  }
  if (!o.embed.empty()) {
    io::writeTriMesh(o.embedOut, fit::carriedSurface(io::readTriMesh(o.embed), rounds), write);
    report.output("embedded", o.embedOut);
  }
}

FitOutcome runFit(const FitCommandOptions& o) {
  const auto started = std::chrono::steady_clock::now();
  checkOptions(o);
  io::Report report("fit");
  reportInputs(o, report);
  Progress progress(o.common.progressStyle());
  const Template t = readTemplate(o, report);
  FitInputs in;
  Start start;
  {
    auto timer = report.time("read markers");
    in = readFitInputs(o);
    if (!o.attachments.empty()) requireThreeAttachments(in, o.attachments, "");
  }
  {
    auto timer = report.time("placement");
    start = place(o, t.tets, in.points);
    if (!o.attachTo.empty()) attachToBone(o, t.tets, start, in);
  }
  std::vector<fit::FitRound> rounds;
  {
    auto timer = report.time("fit");
    rounds = fitRounds(o, t.tets, start, in, progress);
  }
  const fit::FitResult& result = rounds.back().result;
  const TriMesh surface = fittedSurface(t, rounds);
  {
    auto timer = report.time("write meshes");
    writeOutputs(o, rounds, surface, report);
  }
  if (!o.png.empty()) {
    auto timer = report.time("picture");
    writePicture(o, surface, in.points, result.icpErrors);
    report.output("png", o.png);
  }
  const Eigen::VectorXd icpBefore =
      fit::SurfaceProjection(t.tets.T).distances(PlasticFem::flatten(start.x0), in.points.icp);
  reportFit(t.tets, start, in, icpBefore, rounds, report);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  printSummary(o, t.tets, start, in, icpBefore, rounds, seconds);
  o.common.finish(report);
  return {rounds.back().rest.T.rows(), icpBefore, result.icpErrors, seconds};
}

}  // namespace

void addFitCommand(CLI::App& app) {
  auto o = std::make_shared<FitCommandOptions>();
  CLI::App* cmd =
      app.add_subcommand("fit", "Fit a template organ to markers picked on a scan (plastic strains, seed 002)");
  cmd->add_option("--template", o->templ,
                  "Template: tet mesh (.vtu .vtk .msh .mesh .ele) or surface (.stl .obj .ply .vtp; one that is "
                  "open, non-manifold or self-crossing is closed by its winding number first), in its own "
                  "(template) space, mm")
      ->required();
  cmd->add_option("--icp", o->icp,
                  "ICP markers on the organ's boundary in the scan (.mrk.json .fcsv .csv): every "
                  "defined point that is not a landmark or an attachment")
      ->required();
  cmd->add_option("--template-landmarks", o->templateLandmarks, "Landmarks on the template, paired by label");
  cmd->add_option("--scan-landmarks", o->scanLandmarks,
                  "The same landmarks in the scan; alone, each must carry its template position");
  cmd->add_option("--attach-to", o->attachTo,
                  "Bone surface (world mm) the organ inserts on: the insertion itself (from labels: surface "
                  "--label BONE --shared --touching MUSCLE), since of a whole bone every vertex within "
                  "--attach-radius is attached");
  cmd->add_option("--attach-radius", o->attachRadius,
                  "Bone vertices within this distance (mm) of the placed template are attached");
  cmd->add_option("--attachments", o->attachments,
                  "Attachment markers: position = bone point, template position = organ point");
  cmd->add_flag("--unattached", o->unattached, "The organ is free (a liver, a bone): no attachments (seed 002 §3.6)");
  cmd->add_option("--out", o->out,
                  "Fitted tet mesh (.vtu ...): the template's tets and fields, plus "
                  "plastic_stretch_min and plastic_stretch_max per tet")
      ->required();
  cmd->add_option("--surface-out", o->surfaceOut, "Fitted surface (.vtp .stl .obj .ply)");
  cmd->add_option("--embed", o->embed, "A surface in template space (e.g. textured) to carry along");
  cmd->add_option("--embed-out", o->embedOut, "Where the carried surface goes");
  cmd->add_option("--overlay", o->overlay, "Scan to draw the fitted contour on (with --png)");
  cmd->add_option("--png", o->png,
                  "Picture: the contour over three slices through the markers, and the error histogram");
  cmd->add_option("--window", o->window, "Grey window of the picture, scan units")->capture_default_str();
  cmd->add_option("--level", o->level, "Grey level of the picture, scan units")->capture_default_str();
  cmd->add_option("--method", o->method, "plastic (seed 002) or elastic (the FEM baseline of its Fig. 2)")
      ->check(CLI::IsMember({"plastic", "elastic"}))
      ->capture_default_str();
  cmd->add_option("--init", o->init,
                  "similarity: placed from landmark pairs (3 or more) or by ICP to the markers; "
                  "none: the template as it is")
      ->check(CLI::IsMember({"similarity", "none"}))
      ->capture_default_str();
  cmd->add_option("--iterations", o->solver.icpIterations, "Most iterations of the ICP stage")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  cmd->add_option("--max-icp-error", o->solver.maxIcpError, "The ICP stage stops when every marker is this close (mm)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--min-icp-gain", o->solver.minIcpGain,
                  "The ICP stage stops when two iterations lower the mean ICP error by less than this fraction "
                  "of it (0: off)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--min-icp-gain-mm", o->solver.minIcpGainMm,
                  "The ICP stage stops when two iterations lower the mean ICP error by less than this (mm; 0: off)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--marker-weight", o->solver.markerWeight,
                  "alpha of seed 002 eq. 3 per mm^2: higher meets the markers more closely, lower keeps Fp smoother")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--attachment-weight", o->solver.attachmentWeight,
                  "beta of seed 002 eq. 3 per mm^2: how much the attachments' elastic work counts")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--target-tets", o->targetTets,
                  "About this many tets for a surface template (within twice it: a surface finer than that allows "
                  "is coarsened for TetGen, and its own triangles are carried to --surface-out)")
      ->check(CLI::Range(100L, 5000000L))
      ->capture_default_str();
  cmd->add_option("--template-faces", o->templateFaces,
                  "Coarsen a surface template to about this many triangles before tetrahedralizing it instead of "
                  "as --target-tets allows; the full surface is still carried to --surface-out. 0: as the target "
                  "allows")
      ->check(CLI::Range(0, 100000000))
      ->capture_default_str();
  cmd->add_option("--refits", o->refit.refits,
                  "Fit again up to this many times, each from the fitted shape tetrahedralized afresh (about "
                  "--target-tets tets, or at --template-faces), while a marker is farther than --max-icp-error: "
                  "for a template far from the organ, whose first fit crushes its tets and stalls. --out and "
                  "--surface-out then hold the last refit's tets and their boundary; --embed-out is carried "
                  "through every round (smoothly through the refits)")
      ->check(CLI::Range(0, 20))
      ->capture_default_str();
  cmd->add_option("--refit-iterations", o->refit.icpIterations, "Most ICP iterations of each refit")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
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
  cmd->callback([o] { runFit(*o); });
}

}  // namespace vesalius::cli
