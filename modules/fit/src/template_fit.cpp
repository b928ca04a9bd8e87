// A template organ fitted to markers (template_fit.h).
#include "vesalius/fit/template_fit.h"

#include "vesalius/core/error.h"
#include "vesalius/core/histogram.h"
#include "vesalius/core/landmark_pairs.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/stage_clock.h"
#include "vesalius/core/tet_quality.h"
#include "vesalius/fem/plastic_fem.h"
#include "vesalius/fem/plastic_strain.h"
#include "vesalius/fit/attachments.h"
#include "vesalius/fit/point_constraints.h"
#include "vesalius/fit/surface_projection.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>

namespace vesalius::fit {

namespace {

void checkInputs(const TemplateFitInputs& in, const TemplateFitOptions& o) {
  if (in.templateTets.has_value() == in.templateSurface.has_value())
    throw UsageError("fit a template: give a tet mesh or a surface as the template, not both or neither");
  if (in.attachments && in.bone) throw UsageError("fit a template: give attachments or a bone, not both");
  if (in.bone && !(o.attachRadius > 0)) throw UsageError("fit a template: a bone needs a positive attach radius");
  if (o.refit.refits > 0 && o.method != FitMethod::Plastic)
    throw UsageError("fit a template: refits refit plastic strains; the elastic baseline has none");
}

// ---- Markers (§3.1, §3.3) ----

void append(MatrixX3d& M, const Eigen::Vector3d& p) {
  M.conservativeResize(M.rows() + 1, 3);
  M.row(M.rows() - 1) = p.transpose();
}

void takeIcpMarkers(const SourcedMarkers& icp, TemplateFit& f) {
  f.markers.icp.resize(0, 3);
  for (const Marker& m : icp.set.markers) {
    if (m.status != MarkerStatus::Defined || m.kind != MarkerKind::IcpMarker) {
      ++f.skippedMarkers;
      continue;
    }
    append(f.markers.icp, m.position);
    f.icpLabels.push_back(m.label);
  }
  if (f.markers.icp.rows() == 0) throw BadInput(icp.source, "holds no defined ICP markers");
}

// Markers of `kind` that carry their template point: template points and scan points, paired by row.
std::pair<MatrixX3d, MatrixX3d> pointsWithTemplatePositions(const SourcedMarkers& markers, MarkerKind kind,
                                                            TemplateFit& f, std::vector<std::string>* labels) {
  MatrixX3d material(0, 3), world(0, 3);
  for (const Marker* m : markersOfKind(markers.set, kind)) {
    if (m->status != MarkerStatus::Defined) {
      ++f.skippedMarkers;
      continue;
    }
    if (!m->templatePosition)
      throw BadInput(markers.source,
                     std::string(markerKindName(kind)) + " '" + m->label + "' has no template position");
    append(material, *m->templatePosition);
    append(world, m->position);
    if (labels) labels->push_back(m->label);
  }
  return {material, world};
}

void takeMarkers(const TemplateFitInputs& in, TemplateFit& f) {
  takeIcpMarkers(in.icp, f);
  if (in.templateLandmarks && in.scanLandmarks) {
    LandmarkPairs pairs = pairLandmarks(in.templateLandmarks->set, in.templateLandmarks->source,
                                        in.scanLandmarks->set, in.scanLandmarks->source);
    f.markers.templateLandmarks = std::move(pairs.first);
    f.markers.scanLandmarks = std::move(pairs.second);
    f.landmarkLabels = std::move(pairs.labels);
    f.skippedMarkers += pairs.skipped;
  } else if (in.scanLandmarks) {
    std::tie(f.markers.templateLandmarks, f.markers.scanLandmarks) =
        pointsWithTemplatePositions(*in.scanLandmarks, MarkerKind::Landmark, f, &f.landmarkLabels);
  } else if (in.templateLandmarks) {
    throw UsageError("fit a template: template landmarks need their scan landmarks");
  }
  if (in.attachments) {
    std::tie(f.markers.attachmentMaterial, f.markers.attachmentTargets) =
        pointsWithTemplatePositions(*in.attachments, MarkerKind::Attachment, f, nullptr);
  }
}

// Landmarks on one line leave the placement's turn about that line undetermined (fitSimilarity refuses
// them, without knowing their file): refused here naming the file they came from.
void requireLandmarksOffOneLine(const MatrixX3d& points, const std::string& source) {
  const MatrixX3d centred = points.rowwise() - points.colwise().mean();
  const Eigen::Vector3d spread = Eigen::JacobiSVD<MatrixX3d>(centred).singularValues();
  if (spread[1] <= 1e-6 * spread[0])
    throw BadInput(source, "landmarks on one line: the " + std::to_string(points.rows()) +
                               " paired for placing the template leave its turn about that line undetermined; "
                               "give 3 or more that are not in a line");
}

void requirePlacingLandmarks(const TemplateFitInputs& in, const TemplateFitOptions& o, const FitMarkers& markers) {
  if (!o.placeBySimilarity || markers.templateLandmarks.rows() < 3 || !in.scanLandmarks) return;
  // Without template landmarks the scan's landmark file holds their template positions too.
  requireLandmarksOffOneLine(markers.templateLandmarks,
                             in.templateLandmarks ? in.templateLandmarks->source : in.scanLandmarks->source);
  requireLandmarksOffOneLine(markers.scanLandmarks, in.scanLandmarks->source);
}

// Attachments hold the organ only if they remove its rigid motions (§3.3: three non-collinear points).
void requireThreeAttachments(const FitMarkers& markers, const std::string& source, const std::string& advice) {
  const Eigen::Index count = markers.attachmentMaterial.rows();
  if (count < 3)
    throw BadInput(source, std::to_string(count) + " attachment point(s); an attached organ needs at least 3" + advice);
}

// ---- Placement (Fig. 1: the template starts rigidly aligned, here with a uniform scale) ----

// Returns s0, 6#T: the placement's scale times identity in every tet.
Eigen::VectorXd place(const TemplateFitOptions& o, TemplateFit& f) {
  f.placedFrom = "none";
  if (o.placeBySimilarity) {
    f.placement = placeTemplate(tetBoundarySurface(f.templ.V, f.templ.T), f.markers.templateLandmarks,
                                f.markers.scanLandmarks, f.markers.icp);
    f.placedFrom = f.markers.templateLandmarks.rows() >= 3 ? "landmarks" : "icp markers";
  }
  f.placedV = f.placement.transform.apply(f.templ.V);
  Eigen::VectorXd s0(6 * f.templ.T.rows());
  for (Eigen::Index t = 0; t < f.templ.T.rows(); ++t)
    s0.segment<6>(6 * t) = f.placement.transform.scale * identityPlasticStrain();
  return s0;
}

void attachToBone(const TemplateFitInputs& in, const TemplateFitOptions& o, TemplateFit& f) {
  const BoneAttachments a = boneAttachments(f.placedV, f.templ.T, f.templ.V, *in.bone, o.attachRadius);
  f.markers.attachmentMaterial = a.material;
  f.markers.attachmentTargets = a.targets;
  requireThreeAttachments(f.markers, in.boneSource, " (bone vertices within --attach-radius of the placed template)");
  // A whole bone also holds the organ where other tissue lies between them.
  f.attachedToClosedBone = countEdges(in.bone->F).boundary == 0;
}

// ---- The fit and its refits ----

std::vector<FitRound> fitRounds(const TemplateFitInputs& in, const TemplateFitOptions& o, const Eigen::VectorXd& s0,
                                const TemplateFit& f, Progress* progress) {
  FitRound first{f.templ, f.markers,
                 o.method == FitMethod::Elastic
                     ? fitElastic(f.templ, f.placedV, s0, f.markers, o.solver, progress)
                     : fitPlasticStrains(f.templ, f.placedV, s0, f.markers, o.solver, progress)};
  if (o.method != FitMethod::Plastic || o.refit.refits == 0) return {std::move(first)};
  // A refit's rest mesh: the fitted boundary tetrahedralized as the template was (closed by its winding
  // number where it crosses itself: a fitted organ can touch itself in a cleft it was pulled into).
  const std::string source = in.fittedName + " (a refit's rest shape)";
  const Remesh remesh = [&](const TriMesh& boundary) {
    return meshing::closedSurfaceTets(boundary, o.tets, source).tets;
  };
  RefitOptions within = o.refit;
  if (o.tets.faces <= 0) within.maxTets = 2 * o.tets.targetTets;  // the budget, when the target sets it
  return refit(std::move(first), o.solver, within, remesh, progress);
}

// ---- Measures ----

// Distances (mm) between material points placed with positions V and their targets.
Eigen::VectorXd materialPointErrors(const TetMesh& rest, const MatrixX3d& material, const MatrixX3d& targets,
                                    const MatrixX3d& V) {
  const std::vector<PointConstraint> points = embedMaterialPoints(rest.V, rest.T, material, targets, 1.0);
  const Eigen::VectorXd x = PlasticFem::flatten(V);
  Eigen::VectorXd errors(Eigen::Index(points.size()));
  for (std::size_t k = 0; k < points.size(); ++k)
    errors[Eigen::Index(k)] = (constrainedPoint(points[k], x) - points[k].target).norm();
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

Quantiles quantiles(const MatrixX3d& values) {
  std::vector<double> sorted(values.data(), values.data() + values.size());
  std::sort(sorted.begin(), sorted.end());
  const auto at = [&](double q) { return sorted[std::size_t(std::lround(q * double(sorted.size() - 1)))]; };
  return {at(0), at(0.05), at(0.5), at(0.95), at(1)};
}

MinDihedrals minDihedrals(const MatrixX3d& V, const MatrixX4i& T) {
  const TetQuality q = tetQuality(V, T);
  return {q.minDihedral.minCoeff(), histogramCounts(q.minDihedral, kDihedralBinDeg)};
}

void measure(TemplateFit& f) {
  const FitRound& last = f.rounds.back();
  const FitResult& r = last.result;
  const FitMarkers& p = f.markers;
  f.icpBefore = SurfaceProjection(f.templ.T).distances(PlasticFem::flatten(f.placedV), p.icp);
  f.landmarksBefore = materialPointErrors(f.templ, p.templateLandmarks, p.scanLandmarks, f.placedV);
  f.attachmentErrors = materialPointErrors(last.rest, last.markers.attachmentMaterial, p.attachmentTargets, r.V);
  f.icpErrorHistogram = histogramCounts(r.icpErrors, kIcpErrorBinMm);
  f.dihedralsBefore = minDihedrals(f.placedV, f.templ.T);
  f.dihedralsAfter = minDihedrals(r.V, last.rest.T);
  for (const FitRound& round : f.rounds)
    f.roundMeasures.push_back({tetQuality(round.result.V, round.rest.T).minDihedral.minCoeff(),
                               quantiles(principalStretches(round.result.s))});
  f.plasticStretches = f.roundMeasures.front().plasticStretches;
  f.templateVolume = tetVolumes(f.templ.V, f.templ.T).sum();
  f.placedVolume = tetVolumes(f.placedV, f.templ.T).sum();
  const Eigen::VectorXd fittedVolumes = tetVolumes(r.V, last.rest.T);
  f.fittedVolume = fittedVolumes.sum();
  f.invertedAfter = long((fittedVolumes.array() <= 0).count());
}

}  // namespace

TemplateFit fitTemplate(const TemplateFitInputs& in, const TemplateFitOptions& o, Progress* progress) {
  checkInputs(in, o);
  TemplateFit f;
  StageClock clock(f.stageSeconds);
  // A surface template keeps its own triangles (and uv, attributes), carried by the fit (§4.3); the surface
  // that is carried is the closed one the tets fill, since a broken original's triangles may cross.
  std::optional<TriMesh> templateSurface;
  if (in.templateSurface) {
    meshing::TemplateTets prepared = meshing::templateTets(*in.templateSurface, o.tets, in.templateSource);
    f.templ = std::move(prepared.tets);
    templateSurface = std::move(prepared.surface);
    f.repair = prepared.repair;
    f.tetrahedralizedFaces = prepared.tetrahedralizedFaces;
    clock.end("tetrahedralize");
  } else {
    f.templ = *in.templateTets;
  }
  takeMarkers(in, f);
  requirePlacingLandmarks(in, o, f.markers);
  if (in.attachments) requireThreeAttachments(f.markers, in.attachments->source, "");
  const Eigen::VectorXd s0 = place(o, f);
  if (in.bone) attachToBone(in, o, f);
  clock.end("placement");
  f.rounds = fitRounds(in, o, s0, f, progress);
  clock.end("fit");

  const FitRound& last = f.rounds.back();
  const MatrixX3d stretches = principalStretches(last.result.s);
  f.fitted = last.rest;
  f.fitted.V = last.result.V;
  f.fitted.tetAttributes.real["plastic_stretch_min"] = stretches.col(0);
  f.fitted.tetAttributes.real["plastic_stretch_max"] = stretches.col(2);
  // After refits the shape reached is the last round's boundary: the template's triangles, carried through
  // the refits smoothly, follow it only as closely as they are fine (docs/methods/plastic-fit.md, "Refits").
  f.surface = f.rounds.size() > 1
                  ? tetBoundarySurface(last.result.V, last.rest.T)
                  : carriedSurface(templateSurface ? *templateSurface : tetBoundarySurface(f.templ.V, f.templ.T),
                                   f.rounds);
  if (in.embed) f.embedded = carriedSurface(*in.embed, f.rounds);
  measure(f);
  return f;
}

}  // namespace vesalius::fit
