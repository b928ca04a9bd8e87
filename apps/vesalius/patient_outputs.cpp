#include "patient_outputs.h"

#include "common.h"

#include "vesalius/core/markers.h"
#include "vesalius/io/anatomy_rig_io.h"
#include "vesalius/io/gltf.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/marker_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/motion_io.h"
#include "vesalius/io/reference_anatomy_io.h"
#include "vesalius/viz/slice_overlay.h"
#include "vesalius/viz/surface_render.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace fs = std::filesystem;

namespace vesalius::cli {

namespace {

nlohmann::json fitReport(const patient::FittedOrgan& f) {
  const auto meanAndMax = [](const Eigen::VectorXd& e) {
    return nlohmann::json{{"mean", e.mean()}, {"max", e.maxCoeff()}};
  };
  return {{"template", f.templateSource},
          {"markers", f.fit.markers.rows()},
          {"error_before_mm", meanAndMax(f.fit.errorBefore)},
          {"error_after_mm", meanAndMax(f.fit.errorAfter)},
          {"tets_per_round", f.fit.tetsPerRound},
          {"mean_error_per_round_mm", f.fit.meanErrorPerRound}};
}

MarkerSet icpMarkers(const patient::FittedOrgan& f) {
  MarkerSet set;
  set.name = f.organ;
  for (Eigen::Index i = 0; i < f.fit.markers.rows(); ++i) {
    Marker m;
    m.label = "icp-" + std::to_string(i + 1);
    m.kind = MarkerKind::IcpMarker;
    m.position = f.fit.markers.row(i).transpose();
    m.description = "on label " + f.organ;
    set.markers.push_back(std::move(m));
  }
  return set;
}

// Surfaces moved apart where they crossed: vertices inside another before and after, the deepest, the
// largest move.
nlohmann::json apartReport(const meshing::LabelSurfacesApart& a) {
  return {{"vertices_inside_before", a.insideBefore},
          {"vertices_inside_after", a.insideAfter},
          {"deepest_before_mm", a.deepestBeforeMm},
          {"deepest_after_mm", a.deepestAfterMm},
          {"largest_move_mm", a.largestMoveMm}};
}

void renderPng(const ReferenceAnatomy& anatomy, const std::string& path) {
  std::vector<viz::SurfaceLayer> layers;
  for (const ReferenceTissue& t : anatomy.tissues) layers.push_back({&t.mesh, tissueKindColour(t.kind), 1.0});
  layers.push_back({&anatomy.skin, kSkinColour, 0.2});
  viz::writeSurfacesPng(layers, path, {});
}

// The whole model inside its translucent skin, the scan's own skin over it: where the patient ends and the
// reference goes on.
void renderCompletionPng(const ReferenceAnatomy& whole, const ReferenceAnatomy& scan, const std::string& path) {
  std::vector<viz::SurfaceLayer> layers;
  for (const ReferenceTissue& t : whole.tissues) layers.push_back({&t.mesh, tissueKindColour(t.kind), 1.0});
  layers.push_back({&whole.skin, kSkinColour, 0.15});
  layers.push_back({&scan.skin, viz::Rgb{{90, 160, 230}}, 0.35});
  viz::writeSurfacesPng(layers, path, {});
}

// The anatomy with the posed vertices of the rig's meshes (skin first, then the tissues in order).
ReferenceAnatomy posedAnatomy(const ReferenceAnatomy& rest, const patient::PosedPatient& posed) {
  ReferenceAnatomy anatomy = rest;
  anatomy.skin.V = posed.meshes[0];
  for (std::size_t t = 0; t < anatomy.tissues.size(); ++t) anatomy.tissues[t].mesh.V = posed.meshes[t + 1];
  return anatomy;
}

nlohmann::json qualityReport(const patient::PosedPatient& posed) {
  const posing::PoseQuality& q = posed.quality;
  return {{"inverted_tets", q.inverted},
          {"min_tet_volume_ratio", q.minVolumeRatio},
          {"skin_volume_change_pct", q.skinVolumeChangePct},
          {"tet_volume_change_pct", q.tetVolumeChangePct},
          {"tissue_vertices_left_outside", q.leftOutside},
          {"tissue_vertices_inside_at_rest", posed.tissueVerticesInsideAtRest},
          {"untangled_tets", q.untangle.badBefore},
          {"restore_max_move_mm", q.restore.maxMove},
          {"max_bone_mesh_gap_mm", q.boneMeshGapMax},
          {"mean_bone_mesh_gap_mm", q.boneMeshGapMean}};
}

// DIR/posed/: the posed model (anatomy/ and patient.glb), the rig's posed tets and skeleton, the scan and
// organ map re-posed.
void writePosed(const patient::VirtualPatient& p, const PatientPose& asked, bool png, const std::string& dir,
                io::Report& report) {
  const patient::PosedPatient& posed = asked.posed;
  fs::create_directories(dir);
  const ReferenceAnatomy anatomy = posedAnatomy(p.model(), posed);
  io::writeReferenceAnatomy(dir + "/anatomy", anatomy, {});
  io::writeAnatomyGlb(dir + "/patient.glb", anatomy, {});
  TetMesh tets = p.rig->rig.tets;
  tets.V = posed.tets;
  io::writeTetMesh(dir + "/tets.vtu", tets);
  io::writeBvh(dir + "/skeleton.bvh", io::posedSkeletonMotion(p.rig->rig.skeleton, asked.world), {});
  io::writeScan(dir + "/scan.nii.gz", posed.scan, {});
  if (posed.organs) io::writeLabelMap(dir + "/organs.nii.gz", *posed.organs, {});
  if (png) renderPng(anatomy, dir + "/patient.png");
  nlohmann::json pose = qualityReport(posed);
  pose["method"] = asked.method;
  if (!asked.angles.empty()) pose["angles"] = asked.angles;
  if (!asked.motion.empty()) pose["motion"] = {{"file", asked.motion}, {"frame", asked.frame}};
  report.metric("pose", pose);
}

// The completed skin with the fat and the vertices the scan's skin pulled; how the reference's bones met
// the patient's labels.
void writeCompletion(const patient::ReferenceCompletion& c, const patient::WholeModel& whole, const std::string& dir,
                     io::Report& report) {
  TriMesh skin = c.anatomy.skin;
  skin.vertexAttributes.real["fat_thickness"] = c.fatThickness;
  Eigen::VectorXi pulled(skin.V.rows());
  for (Eigen::Index v = 0; v < pulled.size(); ++v) pulled[v] = c.pulled[std::size_t(v)];
  skin.vertexAttributes.integer["pulled_by_scan"] = pulled;
  io::writeTriMesh(dir + "/completed_skin.vtp", skin);
  nlohmann::json groups = nlohmann::json::object(), bones = nlohmann::json::object();
  for (const transfer::BoneGroupMap& g : c.transfer.transferred.boneGroups)
    if (!std::isnan(g.targetRmsBeforeMm))
      groups[g.group] = {{"labels_rms_before_mm", g.targetRmsBeforeMm}, {"labels_rms_after_mm", g.targetRmsAfterMm}};
  for (const patient::RegisteredBone& b : whole.bones)
    bones[b.tissue] = {{"label", b.label},
                       {"vertices", b.registration.mesh.V.rows()},
                       {"label_boundary_to_bone_mean_mm", b.registration.boundaryToMeshMeanMm},
                       {"label_boundary_to_bone_max_mm", b.registration.boundaryToMeshMaxMm}};
  nlohmann::json replaced = nlohmann::json::object();
  for (const auto& [tissue, faces] : whole.replacedFaces) replaced[tissue] = faces;
  report.metric("completion", {{"tissues", c.anatomy.tissues.size()},
                               {"skin_vertices_pulled_by_scan", pulled.sum()},
                               {"scan_skin_to_completed_mean_mm", c.registration.skinMeanDistance},
                               {"scan_skin_to_completed_max_mm", c.registration.skinMaxDistance},
                               {"bone_groups_on_labels", groups},
                               {"bones_on_labels", bones},
                               {"bones_on_labels_apart", apartReport(whole.bonesApart)},
                               {"bones_on_labels_apart_from_scan", apartReport(whole.bonesApartFromScan)},
                               {"tissue_vertices_bent_into_skin", c.outsideBefore},
                               {"tissue_vertices_left_outside_skin", c.outsideAfter},
                               {"into_skin_largest_move_mm", c.bendLargestMm},
                               {"reference_faces_replaced_inside_scan", replaced},
                               {"reference_points_bent_out_of_patient", whole.apart.insideBefore},
                               {"reference_points_left_in_patient", whole.apart.insideAfter},
                               {"out_of_patient_largest_move_mm", whole.apart.largestMoveMm}});
}

// Dicko et al.'s rules on the whole model, in brief: whether each holds and its worst value and tissue.
nlohmann::json rulesReport(const transfer::AnatomyRules& r, const ReferenceAnatomy& model) {
  const auto name = [&](int t) { return t >= 0 ? model.tissues[std::size_t(t)].name : std::string(); };
  nlohmann::json pairs = nlohmann::json::array();
  for (std::size_t i = 0; i < std::min<std::size_t>(r.interpenetration.pairs.size(), 10); ++i) {
    const transfer::Interpenetration& p = r.interpenetration.pairs[i];
    pairs.push_back({{"tissues", {name(p.a), name(p.b)}},
                     {"depth_mm", p.depthMm},
                     {"reference_depth_mm", std::isnan(p.referenceDepthMm) ? nlohmann::json() : nlohmann::json(p.referenceDepthMm)}});
  }
  return {{"hold", r.holds()},
          {"outside", {{"holds", r.outside.holds}, {"vertices", r.outside.vertices}, {"outside", r.outside.outside},
                       {"at_cut", r.outside.outsideAtCut}, {"worst_mm", r.outside.worstMm},
                       {"worst_tissue", name(r.outside.worstTissue)}}},
          {"folds", {{"holds", r.folds.holds}, {"jacobian_min", r.folds.jacobian.minimum},
                     {"nonpositive_cells", r.folds.jacobian.nonPositiveCells}}},
          {"symmetry", {{"holds", r.symmetry.holds}, {"worst_excess_mm", r.symmetry.worstExcessMm},
                        {"worst_group", r.symmetry.worstGroup}}},
          {"straightness", {{"holds", r.straightness.holds}, {"worst_excess", r.straightness.worstExcess},
                            {"worst_bone", name(r.straightness.worstTissue)}}},
          {"interpenetration", {{"holds", r.interpenetration.holds}, {"worst_mm", r.interpenetration.worstMm},
                                {"worst_excess_mm", r.interpenetration.worstExcessMm}, {"deepest_pairs", pairs}}}};
}

}  // namespace

void writePatientFolder(const Image& scan, const patient::VirtualPatient& p, const PatientPose* pose, bool png,
                        const std::string& dir, io::Report& report) {
  const ReferenceAnatomy& model = p.model();
  io::writeReferenceAnatomy(dir + "/anatomy", model, {});
  io::writeAnatomyGlb(dir + "/patient.glb", model, {});
  if (p.whole) io::writeReferenceAnatomy(dir + "/scan_anatomy", p.anatomy, {});
  TriMesh skin = p.anatomy.skin;
  skin.vertexAttributes.real["fat_thickness"] = p.fatThickness;
  io::writeTriMesh(dir + "/skin_fat.vtp", skin);
  io::writeLabelMap(dir + "/tissue_classes.nii.gz", p.tissueClasses);
  viz::writeSliceOverlayPng(scan, p.tissueClasses, dir + "/tissue_classes.png");
  nlohmann::json labelTissues = nlohmann::json::object(), fits = nlohmann::json::object();
  for (const auto& [label, tissues] : p.whole ? p.whole->labelTissues : p.labelTissues)
    for (const std::string& t : tissues) labelTissues[label].push_back("anatomy/" + io::tissueFile(t));
  if (p.completion) writeCompletion(*p.completion, *p.whole, dir, report);
  if (p.rules) report.metric("anatomy_rules", rulesReport(*p.rules, model));
  if (p.rig) {
    io::writeAnatomyRig(dir + "/rig", p.rig->rig, p.rig->meshes, {});
    report.metric("hip_joints", {{"left", p.rig->hipLeft}, {"right", p.rig->hipRight}});
    report.metric("rig", {{"tets", p.rig->rig.tets.T.rows()},
                          {"tet_vertices", p.rig->rig.tets.V.rows()},
                          {"joints", p.rig->rig.skeleton.joints.size()}});
  } else {
    report.metric("rig", {{"none", p.noRigBecause}});
  }
  if (!p.fits.empty()) fs::create_directories(dir + "/organs");
  for (const patient::FittedOrgan& f : p.fits) {
    const std::string stem = dir + "/organs/" + fs::path(io::tissueFile(f.organ)).stem().string();
    io::writeMarkers(stem + "_markers.mrk.json", icpMarkers(f));
    io::writeTriMesh(stem + "_template_fitted.obj", f.fit.carriedTemplate);
    fits[f.organ] = fitReport(f);
  }
  report.metric("label_tissues", labelTissues);
  report.metric("organ_fits", fits);
  nlohmann::json separation = nlohmann::json::array();
  for (const patient::OrganPairSeparation& s : p.organSeparation)
    if (s.penetratingBefore > 0)
      separation.push_back({{"organs", {p.fits[s.first].organ, p.fits[s.second].organ}},
                            {"penetrating_vertices_before", s.penetratingBefore},
                            {"penetrating_vertices_after", s.penetratingAfter},
                            {"max_depth_before_mm", s.maxDepthBefore},
                            {"max_depth_after_mm", s.maxDepthAfter},
                            {"max_displacement_mm", s.maxDisplacement}});
  report.metric("organ_separation", separation);
  report.metric("labels_apart", apartReport(p.labelsApart));
  if (!p.fits.empty())
    report.metric("organs_off_labels", {{"points_inside_before", p.organsOffLabels.insideBefore},
                                        {"points_inside_after", p.organsOffLabels.insideAfter},
                                        {"largest_move_mm", p.organsOffLabels.largestMoveMm}});
  report.metric("tissues", model.tissues.size());
  report.metric("skin_vertices", model.skin.V.rows());
  report.metric("scan_skin_cut_vertices", p.anatomy.skinCutVertices.size());
  report.metric("fat_thickness_mm", {{"mean", p.fatThickness.mean()}, {"max", p.fatThickness.maxCoeff()}});
  for (const auto& [stage, seconds] : p.stageSeconds) report.stage(stage, seconds);
  if (png) renderPng(model, dir + "/patient.png");
  if (png && p.whole) renderCompletionPng(p.whole->anatomy, p.anatomy, dir + "/completed.png");
  if (pose) writePosed(p, *pose, png, dir + "/posed", report);
  report.write(dir + "/report.json", {});
}

}  // namespace vesalius::cli
