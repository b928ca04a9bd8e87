// What `vesalius fit` tells of a template fit (fit_report.h).
#include "fit_report.h"

#include "vesalius/meshing/mesh_volume.h"
#include "vesalius/segmentation/label_ops.h"
#include "vesalius/viz/histogram_panel.h"
#include "vesalius/viz/slice_overlay.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace vesalius::cli {

namespace {

std::string mm(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f mm", value);
  return text;
}

nlohmann::json meanAndMax(const Eigen::VectorXd& values) {
  if (values.size() == 0) return {{"mean", 0.0}, {"max", 0.0}};
  return {{"mean", values.mean()}, {"max", values.maxCoeff()}};
}

// A matrix as JSON rows (a row vector as one flat array).
nlohmann::json rows(const Eigen::MatrixXd& M) {
  nlohmann::json out = nlohmann::json::array();
  for (Eigen::Index i = 0; i < M.rows(); ++i) {
    std::vector<double> row(M.cols());
    for (Eigen::Index j = 0; j < M.cols(); ++j) row[std::size_t(j)] = M(i, j);
    out.push_back(row);
  }
  return M.rows() == 1 ? out[0] : out;
}

nlohmann::json quantiles(const fit::Quantiles& q) {
  return {{"min", q.min}, {"p05", q.p05}, {"median", q.median}, {"p95", q.p95}, {"max", q.max}};
}

nlohmann::json perMarker(const std::vector<std::string>& labels, const Eigen::VectorXd& before,
                         const Eigen::VectorXd& after) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t k = 0; k < labels.size(); ++k)
    out.push_back({{"label", labels[k]}, {"before_mm", before[Eigen::Index(k)]}, {"after_mm", after[Eigen::Index(k)]}});
  return out;
}

nlohmann::json dihedrals(const fit::MinDihedrals& d) {
  return {{"min_deg", d.minDeg}, {"histogram_bin_deg", fit::kDihedralBinDeg}, {"histogram", d.histogram}};
}

}  // namespace

// The numbers "after" are the last round's, what the outputs hold.
void reportFit(const fit::TemplateFit& f, io::Report& report) {
  const fit::FitMarkers& p = f.markers;
  const fit::FitResult& r = f.rounds.back().result;
  const SimilarityTransform& t = f.placement.transform;
  if (f.repair)
    report.metric("template_repair", {{"boundary_edges", f.repair->boundaryEdges},
                                      {"non_manifold_edges", f.repair->nonManifoldEdges},
                                      {"crossing_triangle_pairs", f.repair->crossingTrianglePairs},
                                      {"closed_triangles", f.repair->closedTriangles}});
  if (f.tetrahedralizedFaces > 0) report.metric("tetrahedralized_faces", f.tetrahedralizedFaces);
  report.metric("markers", {{"icp", p.icp.rows()}, {"landmark_pairs", p.scanLandmarks.rows()},
                            {"attachments", p.attachmentMaterial.rows()}, {"skipped", f.skippedMarkers}});
  report.metric("placement", {{"from", f.placedFrom},
                              {"scale", t.scale},
                              {"translation_mm", rows(t.translation.transpose())},
                              {"rotation", rows(t.rotation)},
                              {"rms_error_mm", f.placement.rmsError}});
  report.metric("attached", r.attached);
  report.metric("mesh", {{"vertices", f.templ.V.rows()},
                         {"tets", f.templ.T.rows()},
                         {"fitted_vertices", f.fitted.V.rows()},
                         {"fitted_tets", f.fitted.T.rows()},
                         {"inverted_after", f.invertedAfter}});
  report.metric("icp_error_mm", {{"before", meanAndMax(f.icpBefore)}, {"after", meanAndMax(r.icpErrors)}});
  report.metric("icp_errors", perMarker(f.icpLabels, f.icpBefore, r.icpErrors));
  report.metric("icp_error_histogram", {{"bin_mm", fit::kIcpErrorBinMm}, {"counts", f.icpErrorHistogram}});
  report.metric("landmark_errors", perMarker(f.landmarkLabels, f.landmarksBefore, r.landmarkErrors));
  report.metric("attachment_error_mm", meanAndMax(f.attachmentErrors));
  nlohmann::json iterations = nlohmann::json::array(), ends = nlohmann::json::array(), rounds = nlohmann::json::array();
  for (std::size_t k = 0; k < f.rounds.size(); ++k) {
    const fit::FitResult& round = f.rounds[k].result;
    for (const fit::FitIteration& it : round.history)
      iterations.push_back({{"stage", it.stage}, {"iteration", it.iteration}, {"objective", it.objective},
                            {"smoothness", it.smoothness}, {"constraints", it.constraints}, {"step", it.step},
                            {"mean_icp_error_mm", it.meanIcpError}, {"max_icp_error_mm", it.maxIcpError},
                            {"seconds", it.seconds}, {"round", k}});
    for (const fit::FitStageEnd& e : round.stageEnds)
      ends.push_back({{"round", k}, {"stage", e.stage}, {"iterations", e.iterations}, {"stopped_by", e.reason}});
    rounds.push_back({{"tets", f.rounds[k].rest.T.rows()}, {"iterations", round.history.size()},
                      {"icp_error_mm", meanAndMax(round.icpErrors)},
                      {"min_dihedral_deg", f.roundMeasures[k].minDihedralDeg},
                      {"plastic_stretches", quantiles(f.roundMeasures[k].plasticStretches)}});
  }
  report.metric("iterations", iterations);
  report.metric("stages", ends);
  report.metric("rounds", rounds);
  report.metric("min_dihedral", {{"before", dihedrals(f.dihedralsBefore)}, {"after", dihedrals(f.dihedralsAfter)}});
  report.metric("volume_mm3", {{"template", f.templateVolume}, {"placed", f.placedVolume}, {"fitted", f.fittedVolume},
                               {"fitted_over_template", f.fittedVolume / f.templateVolume}});
  report.metric("plastic_stretches", quantiles(f.plasticStretches));
}

void printFitSummary(const std::string& out, const std::string& method, const fit::TemplateFit& f, double seconds) {
  const fit::FitMarkers& p = f.markers;
  const fit::FitResult& r = f.rounds.back().result;
  long iterations = 0;
  for (const fit::FitRound& round : f.rounds) iterations += long(round.result.history.size());
  std::cout << out << ": " << f.templ.V.rows() << " vertices, " << f.templ.T.rows() << " tets fitted (" << method
            << ", " << (r.attached ? "attached" : "un-attached") << ") to " << p.icp.rows() << " ICP markers, "
            << p.scanLandmarks.rows() << " landmark pairs, " << p.attachmentMaterial.rows() << " attachments\n"
            << "placement from " << f.placedFrom << ", scale " << f.placement.transform.scale << "; " << iterations
            << " iterations in " << std::lround(seconds * 10) / 10.0 << " s\n";
  if (f.rounds.size() > 1) {
    std::cout << "refitted " << f.rounds.size() - 1 << " time(s) from the fitted shape; mean ICP error by round:";
    for (const fit::FitRound& round : f.rounds) std::cout << ' ' << mm(round.result.icpErrors.mean());
    std::cout << "; the last has " << f.fitted.T.rows() << " tets\n";
  }
  std::cout << "ICP error before: mean " << mm(f.icpBefore.mean()) << ", max " << mm(f.icpBefore.maxCoeff()) << "\n"
            << "ICP error after:  mean " << mm(r.icpErrors.mean()) << ", max " << mm(r.icpErrors.maxCoeff()) << "\n";
  if (!r.stageEnds.empty())
    std::cout << "last stage (" << r.stageEnds.back().stage << ") ended by " << r.stageEnds.back().reason << " after "
              << r.stageEnds.back().iterations << " iterations\n";
  if (f.skippedMarkers)
    std::cout << f.skippedMarkers << " marker(s) skipped: not placed yet, or not ICP markers in the --icp file\n";
}

viz::RgbImage fitPicture(const Image& scan, const fit::TemplateFit& f, double window, double level) {
  viz::OverlayOptions overlay;
  overlay.window = window;
  overlay.level = level;
  overlay.opacity = 0.0;
  overlay.outlineOpacity = 1.0;
  MatrixX3d points(f.markers.icp.rows() + f.markers.scanLandmarks.rows(), 3);
  points << f.markers.icp, f.markers.scanLandmarks;
  const Eigen::Vector3d index = scan.geometry.worldToIndex(points.colwise().mean().transpose());
  Eigen::Vector3i voxel;
  for (int a = 0; a < 3; ++a) voxel[a] = std::clamp(int(std::lround(index[a])), 0, scan.geometry.size[a] - 1);
  overlay.voxel = voxel;
  const LabelMap fitted = segmentation::labelMapOf(meshing::meshInsideMask(f.surface, scan.geometry),
                                                   {1, "fitted surface", {{60, 220, 90}}});
  const viz::RgbImage slices = viz::renderSliceOverlay(scan, fitted, overlay);
  viz::HistogramPanelOptions histogram;
  histogram.title = "ICP marker error after the fit";
  histogram.items = "markers";
  histogram.binWidth = fit::kIcpErrorBinMm;
  histogram.height = slices.height;
  histogram.background = slices.get(0, 0);
  const viz::RgbImage panel = viz::histogramPanel(f.rounds.back().result.icpErrors, histogram);
  viz::RgbImage canvas(slices.width + panel.width, slices.height, slices.get(0, 0));
  canvas.paste(slices, 0, 0);
  canvas.paste(panel, slices.width, 0);
  return canvas;
}

}  // namespace vesalius::cli
