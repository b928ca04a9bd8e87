#include "transfer_outputs.h"

#include "common.h"

#include "vesalius/io/reference_anatomy_io.h"
#include "vesalius/viz/surface_render.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <vector>

namespace fs = std::filesystem;

namespace vesalius::cli {

namespace {

// Per tissue, the metric `prefix` + NAME where a count is not zero.
template <class Count>
void perTissue(const ReferenceAnatomy& anatomy, const transfer::AnatomyRules& rules, const std::string& prefix,
               Count count, io::Report& report) {
  for (std::size_t t = 0; t < rules.tissues.size(); ++t)
    if (const long n = count(rules.tissues[t])) report.metric(prefix + anatomy.tissues[t].name, n);
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

}  // namespace

void reportTransferRules(const ReferenceAnatomy& reference, const patient::TransferIntoBody& into,
                         const transfer::TransferRules& both, const meshing::BodyDistance& body, double deepMm,
                         io::Report& report) {
  const transfer::AnatomyRules& rules = both.rules;
  const transfer::TransferredAnatomy& result = into.transferred;
  const transfer::AnatomyRules& step1 = both.interpolated;
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
}

void writeTransferOutputs(const ReferenceAnatomy& reference, const patient::TransferIntoBody& into,
                          const std::string& outDir, const std::string& png, const WriteOptions& write,
                          io::Report& report) {
  TriMesh eroded = reference.skin;
  eroded.V = into.erodedSkin;
  const ReferenceAnatomy& out = into.anatomy;
  // The sub-fat surface (the paper's Fig. 2.b) goes beside the anatomy: to look at, not part of it.
  io::writeReferenceAnatomy(outDir, out, write, {{"eroded_skin.obj", eroded}});
  report.output("anatomy", outDir);
  report.output("eroded_skin", (fs::path(outDir) / "eroded_skin.obj").string());
  if (!png.empty()) {
    // The result, and the reference beside it under the same name with "_reference".
    renderPng(out, into.transferred.tissues, out.skin, png, write);
    std::vector<MatrixX3d> rest;
    for (const ReferenceTissue& t : reference.tissues) rest.push_back(t.mesh.V);
    const fs::path path(png);
    const std::string referencePng =
        (path.parent_path() / (path.stem().string() + "_reference" + path.extension().string())).string();
    renderPng(reference, rest, reference.skin, referencePng, write);
    report.output("png", png);
    report.output("png_reference", referencePng);
  }
}

}  // namespace vesalius::cli
