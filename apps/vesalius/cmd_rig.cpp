// vesalius rig: the posing rig of a body (seed 001 §3.1-3.5 preprocessing): a tet mesh of the inside of
// the skin with bone regions, bone weights, centres of rotation, and the meshes it will carry. Either from a
// skin and a skeleton (bones: capsules around its segments), from a label map with segmented bones
// (skeleton and bone regions from the labels, skeleton_from_bones.h), or from a reference anatomy with
// OpenSim's bone meshes placed in its skin (skeleton from the meshes, skeleton_from_bone_meshes.h; bone
// regions from the meshes voxelized, bone_mesh_labels.h).
#include "anatomy_rig.h"
#include "bone_mesh_labels.h"
#include "common.h"
#include "label_regions.h"
#include "posing_session.h"

#include "vesalius/core/error.h"
#include "vesalius/io/body_axes.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/motion_io.h"
#include "vesalius/io/reference_anatomy_io.h"
#include "vesalius/io/skeleton_io.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/meshing/mesh_volume.h"
#include "vesalius/meshing/tetrahedralize.h"
#include "vesalius/posing/bone_capsules.h"
#include "vesalius/posing/bone_vertices.h"
#include "vesalius/posing/bone_weights.h"
#include "vesalius/posing/rotation_centers.h"
#include "vesalius/posing/skeleton_from_bone_meshes.h"
#include "vesalius/posing/skeleton_from_bones.h"
#include "vesalius/segmentation/label_edit.h"
#include "vesalius/segmentation/label_ops.h"
#include "vesalius/segmentation/label_resample.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>

namespace fs = std::filesystem;

namespace vesalius::cli {

namespace {

struct RigOptions {
  std::string skin, skeleton, baseMesh, out, space = "auto", labels, labelTable, reference;
  posing::SkeletonFromBonesOptions bones;
  // With the femurs placed on the pelvis's hip centres (skeleton_placement.h), the default 6 mm finds 20
  // (right) and 70 (left) femoral head vertices, centres 1.6 and 0.8 mm from the placed femurs' own.
  posing::SkeletonFromBoneMeshesOptions meshBones;
  double acetabulumDistance = NAN;  // --acetabulum-distance if given, for bones or meshBones
  std::vector<std::string> tissues;
  double voxelSize = 4.0;
  double margin = 15.0;  // --labels: the map is cropped to the bones' box grown by this, mm
  long targetTets = 100000;
  bool corCentres = true;
  posing::BoneCapsuleOptions capsules;
  CommonOptions common;
};

// MakeHuman's space (decimetres, +Y up, facing +Z) to ours (mm, LPS); the identity for "lps".
TriMesh toLps(TriMesh mesh, bool makeHuman) {
  if (makeHuman) mesh.V = io::transformPoints(mesh.V, io::yUpToLps(), 100.0);
  return mesh;
}

Skeleton readSkeleton(const RigOptions& o, bool makeHuman) {
  if (fileExtension(o.skeleton) == ".bvh") {
    const Skeleton s = readMotion(o.skeleton).skeleton;
    return makeHuman ? io::transformSkeleton(s, io::yUpToLps(), 100.0) : s;
  }
  if (fileExtension(o.skeleton) != ".mhskel") throw UsageError("rig: --skeleton must be a .mhskel or .bvh file");
  const std::string base = o.baseMesh.empty() ? (fs::path(o.skeleton).parent_path() / "base.obj").string() : o.baseMesh;
  if (!fs::exists(base)) throw UsageError(o.skeleton + ": a MakeHuman skeleton needs its base mesh; pass --base-mesh");
  const Skeleton s = io::readMakeHumanSkeleton(o.skeleton, io::readTriMesh(base).V);
  return makeHuman ? io::transformSkeleton(s, io::yUpToLps(), 100.0) : s;
}

// The grid of the voxelized body: --voxel-size, grown if needed to stay under the seed's cap (§3.2).
GridGeometry bodyGrid(const TriMesh& skin, const RigOptions& o) {
  meshing::CoveringGridOptions grid;
  grid.voxelSizeMm = o.voxelSize;
  return meshing::coveringGrid({&skin}, grid);
}

// Seed 001 §3.2: the inside of the skin as a voxel image under the size cap (bone_mesh_labels.h), its
// surface (closed, free of self-crossings, which TetGen needs and an artist's mesh need not be), then TetGen.
TetMesh bodyTets(const TriMesh& skin, const RigOptions& o) {
  const segmentation::Mask inside = skinInsideMask(skin, bodyGrid(skin, o), o.skin);
  meshing::TetrahedralizeOptions tet;
  tet.targetTets = o.targetTets;
  // The voxel surface has about a triangle per boundary voxel face, which TetGen would keep and refine
  // around (900k tets for a target of 30k at 8 mm voxels); decimated to a quarter of the target, the
  // tet count follows the target.
  meshing::SurfaceOptions surface;
  surface.targetFaces = int(std::max<long>(2000, o.targetTets / 4));
  const LabelMap body = segmentation::labelMapOf(inside, {1, "body"});
  return meshing::tetrahedralizeRegions({{meshing::labelSurface(body, 1, surface), 1, o.skin + " (voxelized)"}}, tet);
}

// Bone columns: the joints whose capsule holds a vertex, in skeleton order; "bone" becomes the column.
std::vector<int> compactBones(Eigen::VectorXi& boneOfVertex, int joints) {
  std::vector<int> column(joints, -1), boneJoint;
  for (Eigen::Index v = 0; v < boneOfVertex.size(); ++v)
    if (boneOfVertex[v] >= 0) column[boneOfVertex[v]] = 0;
  for (int j = 0; j < joints; ++j)
    if (column[j] == 0) {
      column[j] = int(boneJoint.size());
      boneJoint.push_back(j);
    }
  for (Eigen::Index v = 0; v < boneOfVertex.size(); ++v)
    if (boneOfVertex[v] >= 0) boneOfVertex[v] = column[boneOfVertex[v]];
  return boneJoint;
}

// Weights and (optionally) centres of rotation of rig.tets for the bone regions `bone`.
void weighRig(AnatomyRig& rig, const Eigen::VectorXi& bone, const RigOptions& o, io::Report& report, Progress& progress) {
  {
    auto timer = report.time("weights");
    progress.begin("weights", "Laplace bone weights");
    rig.tets.vertexAttributes.real["weights"] = posing::computeBoneWeights(rig.tets.V, rig.tets.T, bone);
    progress.end();
  }
  if (o.corCentres) {
    auto timer = report.time("rotation_centres");
    progress.begin("centres", "CoR centres of rotation");
    rig.tets.vertexAttributes.real["cor_centre"] =
        posing::computeRotationCenters(rig.tets.V, rig.tets.T, rig.tets.vertexAttributes.real["weights"]);
    progress.end();
  }
  rig.tets.vertexAttributes.integer["bone"] = bone;
}

void finishRig(const RigOptions& o, const AnatomyRig& rig, const std::vector<std::pair<std::string, TriMesh>>& meshes,
               io::Report& report) {
  writeAnatomyRig(o.out, rig, meshes, o.common.writeOptions());
  report.output("anatomy", o.out);
  const Eigen::VectorXi& bone = rig.boneOfVertex();
  const long boneVertices = (bone.array() >= 0).count();
  report.metric("tet_vertices", rig.tets.V.rows());
  report.metric("tets", rig.tets.T.rows());
  report.metric("bones", rig.boneJoint.size());
  report.metric("bone_vertices", boneVertices);
  std::cout << o.out << ": " << rig.tets.V.rows() << " vertices, " << rig.tets.T.rows() << " tets, "
            << rig.boneJoint.size() << " of " << rig.skeleton.joints.size() << " joints with bone regions ("
            << boneVertices << " bone vertices), " << meshes.size() << " mesh(es)\n";
  o.common.finish(report);
}

void runSkinRig(const RigOptions& o) {
  if (o.space != "auto" && o.space != "makehuman" && o.space != "lps")
    throw UsageError("rig: --space must be auto, makehuman or lps");
  const bool makeHuman = o.space == "makehuman" || (o.space == "auto" && fileExtension(o.skeleton) == ".mhskel");
  io::Report report("rig");
  report.input("skin", o.skin);
  report.input("skeleton", o.skeleton);
  report.parameter("voxel_size_mm", o.voxelSize);
  report.parameter("target_tets", o.targetTets);
  report.parameter("capsule_radius_fraction", o.capsules.radiusFraction);
  report.parameter("capsule_end_trim", o.capsules.endTrim);
  report.parameter("cor_centres", o.corCentres);
  Progress progress(o.common.progressStyle());

  AnatomyRig rig;
  const TriMesh skin = toLps(io::readTriMesh(o.skin), makeHuman);
  rig.skeleton = readSkeleton(o, makeHuman);
  {
    auto timer = report.time("tetrahedralize");
    progress.begin("tetrahedralize", "voxelize the skin, surface it, TetGen");
    rig.tets = bodyTets(skin, o);
    progress.end();
  }
  Eigen::VectorXi bone = posing::boneCapsuleVertices(rig.tets.V, rig.skeleton, skin, o.capsules);
  rig.boneJoint = compactBones(bone, int(rig.skeleton.joints.size()));
  weighRig(rig, bone, o, report, progress);
  std::vector<std::pair<std::string, TriMesh>> meshes{{"skin" + fileExtension(o.skin), skin}};
  for (const std::string& t : o.tissues) meshes.emplace_back(fs::path(t).filename().string(), toLps(io::readTriMesh(t), makeHuman));
  finishRig(o, rig, meshes, report);
}

// The smallest positive label that is no bone's: the rest of the body.
Label bodyLabel(const std::vector<std::vector<Label>>& boneLabels) {
  std::vector<bool> taken(65536, false);
  for (const auto& labels : boneLabels)
    for (Label l : labels) taken[l] = true;
  Label body = 1;
  while (taken[body]) ++body;
  return body;
}

// Seed 001 §3.2 from a label map: only the bones' box grown by `margin` is meshed (the body is cut flat
// at its sides), resampled (nearest neighbour) to voxels of at least `voxelSize` and within the seed's
// 250x700x120.
LabelMap bonesBox(const LabelMap& map, const posing::BoneSkeleton& bones, double margin, double voxelSize) {
  std::vector<bool> isBone(65536, false);
  for (const auto& labels : bones.labels)
    for (Label l : labels) isBone[l] = true;
  segmentation::Mask bone(map.labels.geometry, 0);
  for (std::size_t v = 0; v < bone.values.size(); ++v) bone.values[v] = isBone[map.labels.values[v]];
  LabelMap box = segmentation::cropLabelMap(map, segmentation::maskBounds(bone, margin));
  // At most one voxel per voxelSize along each axis, and within the seed's cap (LPS order).
  const GridGeometry& g = box.labels.geometry;
  Eigen::Vector3i cap = meshing::CoveringGridOptions{}.maxSize;
  for (int d = 0; d < 3; ++d) {
    Eigen::Index lps;
    g.direction.col(d).cwiseAbs().maxCoeff(&lps);
    cap[lps] = std::min(cap[lps], std::max(1, int(std::ceil(g.size[d] * g.spacing[d] / voxelSize))));
  }
  const GridGeometry capped = segmentation::cappedGeometry(g, cap);
  return capped.size == g.size ? box : segmentation::resampleLabels(box, capped);
}

// The body (every labelled voxel, made solid) as the outer region and each bone label nested in it, as
// `tetmesh --labels --body` makes them (label_regions.h); decimated, since TetGen keeps every boundary
// triangle. Each bone is first grown by a voxel into the tissue around it (not into other bones): plates a
// voxel or two thick (the iliac wings at 4 mm) would otherwise be two sheets so close that TetGen's quality
// refinement fills them and the body around them with tets (0.93M tets instead of 0.68M for 20k asked).
// A map that labels the whole body (solidBody false: rig --reference) grows its bones into the body only
// and keeps the body's shape; a CT's map labels organs and bones, so its body is every labelled voxel made
// solid and its bones grow into the unlabelled soft tissue too.
// A CT's bones (solidBody) then get the surface budgets of budgetSurfaces (within 2x of the target), their
// gaps narrower than two voxels closed and only their largest parts: quadric decimation tore the test CT's
// sacrum (its foramina and thin parts at 4 mm) at every budget up to twice its own, and the topology-keeping
// fallback stopped at 2,634 faces, 10,642 tets inside it and as many around it. The reference's bones keep a
// quarter of the target on the body and another shared equally by the bones, at least 300 faces each: with
// the budgets, the flexed left femur's mesh was 2.3-5.3 mm off its rigid turn (the test's bound is 2 mm;
// docs/methods/posing.md, Not yet).
std::vector<meshing::RegionSurface> boneRegions(LabelMap box, const std::vector<std::vector<Label>>& boneLabels,
                                                Label body, bool solidBody, const RigOptions& o,
                                                const std::string& source, Progress& progress) {
  std::vector<Label> ids;
  for (const auto& labels : boneLabels) ids.insert(ids.end(), labels.begin(), labels.end());
  std::vector<bool> isBone(65536, false);
  for (Label l : ids) isBone[l] = true;
  const Grid<Label> rest = box.labels;
  const double voxel = box.labels.geometry.spacing.maxCoeff();
  for (Label l : ids) {
    segmentation::Mask grown = segmentation::dilateMm(segmentation::maskOf(rest, l), voxel);
    if (solidBody) grown = segmentation::closeMm(grown, voxel);
    for (std::size_t v = 0; v < grown.values.size(); ++v)
      if (grown.values[v] && !isBone[rest.values[v]] && (solidBody || rest.values[v] != 0)) box.labels.values[v] = l;
  }
  LabelRegionOptions regions;
  regions.body = body;
  regions.solidBody = solidBody;
  if (!solidBody) {
    regions.bodySurface.targetFaces = int(std::max<long>(2000, o.targetTets / 4));
    regions.labelSurface.targetFaces = int(std::max<long>(300, o.targetTets / 4 / long(ids.size())));
    return labelRegionSurfaces(box, ids, regions, source, &progress);
  }
  regions.largestPartOnly = true;
  // A coarse body surface can cut a bone a voxel below it (the test CT's body at 3,562 faces crossed
  // hip_right at 10 triangle pairs); finer budgets then, and TetGen names the crossing if they stay.
  std::vector<meshing::RegionSurface> surfaces;
  long budget = o.targetTets;
  for (int attempt = 0; attempt < 4; ++attempt, budget = budget * 3 / 2) {
    budgetSurfaces(regions, budget);
    surfaces = labelRegionSurfaces(box, ids, regions, source, &progress);
    if (!meshing::surfacesCross(surfaces)) break;
  }
  return surfaces;
}

// Seed 001 §3.2-3.3 from the nested region surfaces of the body and its bones: TetGen, each bone's region
// the vertices of its tets (boneLabels: per joint of rig.skeleton, the labels of its bone), weights, centres.
void rigOfRegions(AnatomyRig& rig, const std::vector<meshing::RegionSurface>& regions,
                  const std::vector<std::vector<Label>>& boneLabels, const RigOptions& o, io::Report& report,
                  Progress& progress) {
  {
    auto timer = report.time("tetrahedralize");
    progress.begin("tetrahedralize", "TetGen");
    meshing::TetrahedralizeOptions tet;
    tet.targetTets = o.targetTets;
    // No Steiner points on the surfaces (TetGen -Y): on the decimated body and bone surfaces, TetGen's
    // splitting of the surface triangles that its refinement points encroach on made nearly all the tets
    // (the test CT at --target-tets 20000: 707,544 tets at the first volume bound, 57,723 with -Y;
    // docs/methods/tetrahedral-meshes.md).
    tet.keepSurface = true;
    rig.tets = meshing::tetrahedralizeRegions(regions, tet);
    progress.end();
  }
  Eigen::VectorXi bone =
      posing::boneVerticesOfLabels(rig.tets.T, rig.tets.tetAttributes.integer.at(kLabel), boneLabels, rig.tets.V.rows());
  rig.boneJoint = compactBones(bone, int(rig.skeleton.joints.size()));
  weighRig(rig, bone, o, report, progress);
}

void runLabelRig(const RigOptions& o) {
  io::Report report("rig");
  report.input("labels", o.labels);
  report.parameter("target_tets", o.targetTets);
  report.parameter("margin_mm", o.margin);
  report.parameter("voxel_size_mm", o.voxelSize);
  report.parameter("cor_centres", o.corCentres);
  Progress progress(o.common.progressStyle());
  const LabelMap map = io::readLabelMap(o.labels, o.labelTable);
  posing::SkeletonFromBonesOptions boneOptions = o.bones;
  if (!std::isnan(o.acetabulumDistance)) boneOptions.acetabulumDistance = o.acetabulumDistance;
  const posing::BoneSkeleton bones = posing::skeletonFromBones(map, boneOptions, o.labels);
  const Label body = bodyLabel(bones.labels);
  AnatomyRig rig;
  rig.skeleton = bones.skeleton;
  std::vector<meshing::RegionSurface> regions;
  {
    auto timer = report.time("surfaces");
    progress.begin("surfaces", "the body and its bones, nested");
    regions = boneRegions(bonesBox(map, bones, o.margin, o.voxelSize), bones.labels, body, true, o, o.labels, progress);
    progress.end();
  }
  rigOfRegions(rig, regions, bones.labels, o, report, progress);
  std::vector<std::pair<std::string, TriMesh>> meshes;
  for (meshing::RegionSurface& r : regions) {
    const LabelEntry* entry = map.table.find(Label(r.label));
    meshes.emplace_back((r.label == body || !entry ? "skin" : entry->name) + ".vtp", std::move(r.surface));
  }
  for (const std::string& t : o.tissues) meshes.emplace_back(fs::path(t).filename().string(), io::readTriMesh(t));
  report.metric("femoral_head_radius_left_mm", bones.femoralHeadLeft.radius);
  report.metric("femoral_head_radius_right_mm", bones.femoralHeadRight.radius);
  finishRig(o, rig, meshes, report);
}

// The OpenSim bodies that have no joint in skeletonFromBoneMeshes but move rigidly with one: the foot
// (calcaneus, toes) with the talus, as there are no subtalar and toe joints; the radius with the ulna (the
// forearm is one bone, no radioulnar joint); the "skull" group (the torso's skull and jaw, which
// `reference full-body` groups apart) with the torso. Other bodies are their joint (the patellae have
// none: they follow the weights).
std::string jointOfBody(const std::string& body) {
  if (body == io::kSkullGroup) return "torso";
  for (const char* foot : {"calcn_", "toes_"})
    if (body.rfind(foot, 0) == 0) return "talus_" + body.substr(std::strlen(foot));
  if (body.rfind("radius_", 0) == 0) return "ulna_" + body.substr(std::strlen("radius_"));
  return body;
}

// Seed 001 §3.2 for a reference anatomy: its skin and, per joint, the bone meshes of the joint's OpenSim
// body (the tissues' group, jointOfBody) voxelized into one label map (bone_mesh_labels.h: label j + 1
// for joint j), then nested region surfaces as for --labels. boneLabels: per joint its label, none for a
// joint with no bone voxel (a hand outside the skin at coarse voxels would have none).
std::vector<meshing::RegionSurface> referenceRegions(const ReferenceAnatomy& reference, const Skeleton& skeleton,
                                                     std::vector<std::vector<Label>>& boneLabels, const RigOptions& o,
                                                     Progress& progress) {
  std::vector<BoneMeshes> bones(skeleton.joints.size());
  for (std::size_t j = 0; j < bones.size(); ++j) bones[j].name = skeleton.joints[j].name;
  for (const ReferenceTissue& t : reference.tissues) {
    const int j = skeleton.find(jointOfBody(t.group));
    if (j >= 0) bones[std::size_t(j)].meshes.push_back(&t.mesh);
  }
  const LabelMap map = boneMeshLabelMap(reference.skin, bones, bodyGrid(reference.skin, o), o.reference);
  std::vector<long> voxels(bones.size() + 2, 0);
  for (Label l : map.labels.values) ++voxels[l];
  boneLabels.assign(bones.size(), {});
  for (std::size_t j = 0; j < bones.size(); ++j)
    if (voxels[j + 1] > 0) boneLabels[j] = {Label(j + 1)};
  return boneRegions(map, boneLabels, Label(bones.size() + 1), false, o, o.reference, progress);
}

void runReferenceRig(const RigOptions& o) {
  io::Report report("rig");
  report.input("reference", o.reference);
  report.parameter("voxel_size_mm", o.voxelSize);
  report.parameter("target_tets", o.targetTets);
  report.parameter("cor_centres", o.corCentres);
  Progress progress(o.common.progressStyle());
  const ReferenceAnatomy reference = io::readReferenceAnatomy(o.reference);
  std::map<std::string, TriMesh> byName;
  for (const ReferenceTissue& t : reference.tissues) byName.emplace(t.name, t.mesh);
  posing::SkeletonFromBoneMeshesOptions boneOptions = o.meshBones;
  if (!std::isnan(o.acetabulumDistance)) boneOptions.acetabulumDistance = o.acetabulumDistance;
  const posing::MeshSkeleton bones = posing::skeletonFromBoneMeshes(byName, boneOptions, o.reference);
  AnatomyRig rig;
  rig.skeleton = bones.skeleton;
  std::vector<std::vector<Label>> boneLabels;
  std::vector<meshing::RegionSurface> regions;
  {
    auto timer = report.time("surfaces");
    progress.begin("surfaces", "skin and bone meshes voxelized; the body and its bones, nested");
    regions = referenceRegions(reference, rig.skeleton, boneLabels, o, progress);
    progress.end();
  }
  rigOfRegions(rig, regions, boneLabels, o, report, progress);
  std::vector<std::pair<std::string, TriMesh>> meshes{{"skin.obj", reference.skin}};
  for (const ReferenceTissue& t : reference.tissues) meshes.emplace_back(t.name + ".obj", t.mesh);
  for (const std::string& t : o.tissues) meshes.emplace_back(fs::path(t).filename().string(), io::readTriMesh(t));
  report.metric("femoral_head_radius_left_mm", bones.left.femoralHead.radius);
  report.metric("femoral_head_radius_right_mm", bones.right.femoralHead.radius);
  finishRig(o, rig, meshes, report);
}

void runRig(const RigOptions& o) {
  const bool fromSkin = !o.skin.empty() || !o.skeleton.empty();
  if (int(fromSkin) + int(!o.labels.empty()) + int(!o.reference.empty()) != 1)
    throw UsageError("rig: give --skin and --skeleton, or --labels, or --reference (one of them)");
  if (fromSkin && (o.skin.empty() || o.skeleton.empty())) throw UsageError("rig: --skin and --skeleton go together");
  if (!o.labelTable.empty() && o.labels.empty()) throw UsageError("rig: --label-table needs --labels");
  if (!o.reference.empty()) return runReferenceRig(o);
  fromSkin ? runSkinRig(o) : runLabelRig(o);
}

}  // namespace

void addRigCommand(CLI::App& app) {
  auto o = std::make_shared<RigOptions>();
  CLI::App* cmd = app.add_subcommand("rig", "Posing rig of a body: tet mesh, bone regions, weights, CoR centres");
  cmd->add_option("--skin", o->skin, "Closed body surface (.obj .stl .vtp .ply .vtk), with --skeleton");
  cmd->add_option("--skeleton", o->skeleton, "Skeleton: MakeHuman .mhskel or .bvh, with --skin");
  cmd->add_option("--labels", o->labels,
                  "Instead of --skin/--skeleton: a label map with segmented bones (hip_left, hip_right, sacrum, "
                  "femur_left, femur_right, vertebrae_L5 upward); skeleton and bone regions from its labels");
  cmd->add_option("--label-table", o->labelTable, "Label table for --labels (default: the one beside it)");
  cmd->add_option("--reference", o->reference,
                  "Instead of --skin/--skeleton or --labels: a reference anatomy with OpenSim's bone meshes in its "
                  "skin (`reference full-body`); skeleton (pelvis, legs, torso, arms) and bone regions from the meshes");
  cmd->add_option("--acetabulum-distance", o->acetabulumDistance,
                  "With --labels or --reference: femoral head voxels or vertices within this of the hip bone give the "
                  "hip centre, mm (default 6)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--base-mesh", o->baseMesh, "MakeHuman base.obj for a .mhskel (default: beside it)");
  cmd->add_option("--tissue", o->tissues, "A mesh to carry along (organ, bone, muscle), repeatable");
  cmd->add_option("--space", o->space,
                  "Space of the inputs: makehuman (decimetres, +Y up; converted to mm LPS), lps (mm), or auto "
                  "(makehuman for a .mhskel)")
      ->capture_default_str();
  cmd->add_option("--margin", o->margin, "With --labels: mesh the bones' bounding box grown by this, mm")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--voxel-size", o->voxelSize, "Voxel size of the inside image (--skin, --reference) or of the labels meshed (--labels; coarser only), mm (grown to keep it under "
                                               "250x120x700 voxels, seed 001 §3.2)")
      ->capture_default_str();
  cmd->add_option("--target-tets", o->targetTets, "About this many tets")->capture_default_str();
  cmd->add_option("--capsule-radius", o->capsules.radiusFraction,
                  "Bone capsule radius as a fraction of the bone's distance to the skin")
      ->capture_default_str();
  cmd->add_option("--capsule-trim", o->capsules.endTrim, "Fraction of each bone left free at both ends")
      ->capture_default_str();
  cmd->add_flag("--cor-centres,!--no-cor-centres", o->corCentres,
                "Compute the centres of rotation that `pose --method cor` needs (default; a few seconds for the "
                "body's 50 bones); --no-cor-centres skips them");
  cmd->add_option("--out", o->out, "Anatomy directory to write (rig.vtu, bones.txt, skeleton.bvh, meshes/)")->required();
  addCommonOptions(*cmd, o->common);
  cmd->footer(
      "Example (with the centres of rotation for `pose --method cor`; add --no-cor-centres to skip them):\n"
      "  vesalius rig --skin testdata/body/shapes/mh_neutral_body.obj "
      "--skeleton testdata/body/default.mhskel --out body-rig\n"
      "Bones are capsules around the skeleton's segments (no bone meshes are needed); see docs/methods/posing.md.\n"
      "From a CT's bone labels (TotalSegmentator names; the pelvis, femurs and lumbar spine):\n"
      "  vesalius rig --labels seg.nii.gz --label-table labels_total_v1.tsv --target-tets 20000 --out ct-rig\n"
      "From the full-body reference (OpenSim's bones in MakeHuman's skin; joints pelvis, femur_l, tibia_l, talus_l, ...):\n"
      "  vesalius rig --reference body-reference --voxel-size 6 --target-tets 20000 --out body-bones-rig\n"
      "(about 20 s and 67k tets; at the defaults about 250k tets, 72 s)");
  cmd->callback([o] { runRig(*o); });
}

}  // namespace vesalius::cli
