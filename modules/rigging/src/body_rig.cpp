#include "vesalius/rigging/body_rig.h"

#include "vesalius/core/error.h"
#include "vesalius/core/tet_locator.h"
#include "vesalius/io/reference_anatomy_io.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/meshing/mesh_volume.h"
#include "vesalius/meshing/tet_budget.h"
#include "vesalius/meshing/tetrahedralize.h"
#include "vesalius/posing/bone_vertices.h"
#include "vesalius/posing/bone_weights.h"
#include "vesalius/posing/rotation_centers.h"
#include "vesalius/rigging/bone_mesh_labels.h"
#include "vesalius/rigging/label_regions.h"
#include "vesalius/segmentation/label_edit.h"
#include "vesalius/segmentation/label_ops.h"
#include "vesalius/segmentation/label_resample.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <optional>

namespace vesalius::rigging {

namespace {

// Runs `stage`, adding its wall time to rig.stageSeconds under `name`.
template <class F>
void timed(BuiltRig& rig, const std::string& name, F&& stage) {
  const auto start = std::chrono::steady_clock::now();
  stage();
  rig.stageSeconds.emplace_back(name, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

// The grid of the voxelized body: --voxel-size, grown if needed to stay under Sujar et al.'s cap (§3.2).
GridGeometry bodyGrid(const TriMesh& skin, const RigOptions& o) {
  meshing::CoveringGridOptions grid;
  grid.voxelSizeMm = o.voxelSize;
  return meshing::coveringGrid({&skin}, grid);
}

// Sujar et al. 2018, §3.2: the inside of the skin as a voxel image under the size cap (bone_mesh_labels.h), its
// surface (closed, free of self-crossings, which TetGen needs and an artist's mesh need not be), then TetGen.
TetMesh bodyTets(const TriMesh& skin, const RigOptions& o, const std::string& source) {
  const segmentation::Mask inside = skinInsideMask(skin, bodyGrid(skin, o), source);
  meshing::TetrahedralizeOptions tet;
  tet.targetTets = o.targetTets;
  tet.keepSurfaceOverBudget = true;
  // The voxel surface has about a triangle per boundary voxel face, which TetGen keeps and refines around
  // (900k tets for a target of 30k at 8 mm voxels; 129k for 20k with a quarter of the target in faces):
  // decimated to the faces the target allows, and coarsened again while the tets are more than twice it.
  meshing::SurfaceOptions surface;
  surface.targetFaces = meshing::facesForTets(o.targetTets);
  const LabelMap body = segmentation::labelMapOf(inside, {1, "body"});
  return meshing::tetrahedralizeWithinBudget(meshing::labelSurface(body, 1, surface), tet, source + " (voxelized)").tets;
}

// Whether tet t has bone vertices only, of more than one bone: the bones' relative turn deforms it and the
// untangler (untangle_tets.h), which moves tissue vertices only, cannot repair it if it inverts.
bool joinsBonesAlone(const MatrixX4i& T, Eigen::Index t, const Eigen::VectorXi& bone) {
  for (int k = 0; k < 4; ++k)
    if (bone[T(t, k)] < 0) return false;
  for (int k = 1; k < 4; ++k)
    if (bone[T(t, k)] != bone[T(t, 0)]) return true;
  return false;
}

// Capsules that touch (the pelvis's halves and the lowest spine segment meet at the root) can give a tet
// of bone vertices alone that joins two bones; such a tet inverted in 13 of 28 CMU frames on the muscular
// body. Each loses one bone vertex to the tissue: the one of the bone with the most vertices.
void separateBones(const TetMesh& tets, int joints, Eigen::VectorXi& bone) {
  std::vector<long> count(std::size_t(joints), 0);
  for (Eigen::Index v = 0; v < bone.size(); ++v)
    if (bone[v] >= 0) ++count[std::size_t(bone[v])];
  for (Eigen::Index t = 0; t < tets.T.rows(); ++t) {
    if (!joinsBonesAlone(tets.T, t, bone)) continue;
    int freed = tets.T(t, 0);
    for (int k = 1; k < 4; ++k)
      if (count[std::size_t(bone[tets.T(t, k)])] > count[std::size_t(bone[freed])]) freed = tets.T(t, k);
    --count[std::size_t(bone[freed])];
    bone[freed] = -1;
  }
}

// Capsules inside the meshed body that hold no tet vertex (a metacarpal's capsule of 2-3 mm radius between
// vertices 15-30 mm apart in a coarse rig) each take the free vertex nearest their trimmed segment that
// makes no tet of bone vertices alone join two bones, so that every bone inside the tets moves its tissue.
// "Inside": points along the trimmed segment, as many as the capsules' clearance samples, all in a tet.
// Segments leaving the tets (finger tips and face bones thinner than a voxel or crossing the skin) stay
// without bone. The vertex taken lies outside the capsule, at most a tet's size from its axis: a deviation
// from the capsule rule (bone_capsules.h), stated in docs/methods/posing.md.
void holdEmptyCapsules(const TetMesh& tets, const Skeleton& skeleton, const posing::BoneCapsuleOptions& o,
                       Eigen::VectorXi& bone) {
  std::vector<bool> held(skeleton.joints.size(), false);
  for (Eigen::Index v = 0; v < bone.size(); ++v)
    if (bone[v] >= 0) held[std::size_t(bone[v])] = true;
  const std::vector<Eigen::Isometry3d> rest = skeleton.restWorld();
  std::optional<TetLocator> locator;
  std::vector<std::vector<Eigen::Index>> tetsOf;
  for (std::size_t j = 0; j < rest.size(); ++j) {
    if (held[j] || skeleton.joints[j].tail.norm() == 0) continue;
    const Eigen::Vector3d head = rest[j].translation(), tail = rest[j] * skeleton.joints[j].tail;
    const Eigen::Vector3d a = head + o.endTrim * (tail - head), b = tail - o.endTrim * (tail - head);
    if (!locator) {
      locator.emplace(tets.V, tets.T);
      tetsOf.resize(std::size_t(tets.V.rows()));
      for (Eigen::Index t = 0; t < tets.T.rows(); ++t)
        for (int k = 0; k < 4; ++k) tetsOf[std::size_t(tets.T(t, k))].push_back(t);
    }
    bool inside = true;
    for (int k = 0; k < o.samples && inside; ++k)
      inside = bool(locator->locate(a + (b - a) * (k / double(o.samples - 1))));
    if (!inside) continue;
    const Eigen::Vector3d ab = b - a;
    std::vector<std::pair<double, Eigen::Index>> free;
    for (Eigen::Index v = 0; v < tets.V.rows(); ++v) {
      if (bone[v] >= 0) continue;
      const Eigen::Vector3d p = tets.V.row(v).transpose();
      const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
      free.emplace_back((p - (a + t * ab)).squaredNorm(), v);
    }
    std::sort(free.begin(), free.end());
    for (const auto& [distance, v] : free) {
      bone[v] = int(j);
      const auto& around = tetsOf[std::size_t(v)];
      if (std::none_of(around.begin(), around.end(), [&](Eigen::Index t) { return joinsBonesAlone(tets.T, t, bone); }))
        break;
      bone[v] = -1;
    }
  }
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

// Weights and (optionally) centres of rotation of built.rig.tets for the bone regions `bone`.
void weighRig(BuiltRig& built, const Eigen::VectorXi& bone, const RigOptions& o, Progress& progress) {
  TetMesh& tets = built.rig.tets;
  timed(built, "weights", [&] {
    progress.begin("weights", "Laplace bone weights");
    tets.vertexAttributes.real["weights"] = posing::computeBoneWeights(tets.V, tets.T, bone);
    progress.end();
  });
  if (o.corCentres)
    timed(built, "rotation_centres", [&] {
      progress.begin("centres", "CoR centres of rotation");
      tets.vertexAttributes.real["cor_centre"] =
          posing::computeRotationCenters(tets.V, tets.T, tets.vertexAttributes.real["weights"]);
      progress.end();
    });
  tets.vertexAttributes.integer["bone"] = bone;
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

// Sujar et al. 2018, §3.2 from a label map: only the bones' box grown by `margin` is meshed (the body is cut flat
// at its sides), resampled (nearest neighbour) to voxels of at least `voxelSize` and within Sujar et al.'s
// 250x700x120.
LabelMap bonesBox(const LabelMap& map, const posing::BoneSkeleton& bones, double margin, double voxelSize) {
  std::vector<bool> isBone(65536, false);
  for (const auto& labels : bones.labels)
    for (Label l : labels) isBone[l] = true;
  segmentation::Mask bone(map.labels.geometry, 0);
  for (std::size_t v = 0; v < bone.values.size(); ++v) bone.values[v] = isBone[map.labels.values[v]];
  LabelMap box = segmentation::cropLabelMap(map, segmentation::maskBounds(bone, margin));
  // At most one voxel per voxelSize along each axis, and within Sujar et al.'s cap (LPS order).
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

// The fewest triangles of a skin that carries the model (rig --reference): with fewer the posed skin loses
// volume (below).
constexpr int kMinSkinFaces = 2000;

// How a rig's regions are surfaced: a solid body (a rig of bone labels) or a skin (a reference's rig).
// checkRigTargetTets takes its floors from the same options.
LabelRegionOptions rigRegionOptions(bool solidBody) {
  LabelRegionOptions regions;
  regions.solidBody = solidBody;
  regions.largestPartOnly = solidBody;
  regions.largestBodyPartOnly = !solidBody;
  regions.closeOverBudget = !solidBody;
  return regions;
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
// gaps narrower than two voxels closed and only their largest parts: the test CT's sacrum at 4 mm has
// foramina, handles that its decimated surface keeps. The reference's bones get the same budgets, and a bone
// whose surface stays above twice its share is closed until it meets it (LabelRegionOptions::closeOverBudget):
// the torso's rib cage, spine, scapulae and skull keep a handle per rib. The tissue so filled lies between
// bones of the one torso joint, which moved it with them before as well.
std::vector<meshing::RegionSurface> boneRegions(LabelMap box, const std::vector<std::vector<Label>>& boneLabels,
                                                Label body, bool solidBody, const RigOptions& o,
                                                const std::string& source, Progress& progress) {
  std::vector<Label> ids;
  for (const auto& labels : boneLabels) ids.insert(ids.end(), labels.begin(), labels.end());
  checkRigTargetTets(o.targetTets, ids.size(), !solidBody);
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
  LabelRegionOptions regions = rigRegionOptions(solidBody);
  regions.body = body;
  // Coarse bones can cross each other or a coarse body a voxel above them (the test CT's hip bones at
  // 110-170 faces); labelRegionSurfaces then decimates them together, apart. Where they still cross (their
  // undecimated surfaces touch), finer budgets, and TetGen names the crossing if it stays. A solid body
  // grows its budget only from the third try: its bones have a few hundred faces where it has thousands
  // (growing both took the test CT's rig at 4,000 tets to a body of 1,686 faces and 10,502 tets).
  std::vector<meshing::RegionSurface> surfaces;
  long budget = o.targetTets, bodyBudget = o.targetTets;
  for (int attempt = 0; attempt < 6; ++attempt) {
    budgetSurfaces(regions, bodyBudget);
    // The skin is carried by the body's tets: with an eighth of the target on the body (2,500 faces of a
    // MakeHuman body at 20,000 tets) the demo's model lost 1.3 % of its skin's volume at frame 400 of the
    // CMU walk, 0.8 % with a quarter.
    const int bodyFaces =
        solidBody ? regions.bodySurface.targetFaces : int(std::max<long>(kMinSkinFaces, bodyBudget / 4));
    budgetSurfaces(regions, budget);
    regions.bodySurface.targetFaces = bodyFaces;
    surfaces = labelRegionSurfaces(box, ids, regions, source, &progress);
    if (!meshing::surfacesCross(surfaces)) break;
    budget = long(double(budget) * kCrossingGrowth);
    if (attempt >= 2 || !solidBody) bodyBudget = long(double(bodyBudget) * kCrossingGrowth);
  }
  return surfaces;
}

// Sujar et al. 2018, §3.2-3.3 from the nested region surfaces of the body and its bones: TetGen, each bone's region
// the vertices of its tets (boneLabels: per joint of the skeleton, the labels of its bone), weights, centres.
void rigOfRegions(BuiltRig& built, const std::vector<meshing::RegionSurface>& regions,
                  const std::vector<std::vector<Label>>& boneLabels, const RigOptions& o, Progress& progress) {
  AnatomyRig& rig = built.rig;
  timed(built, "tetrahedralize", [&] {
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
  });
  Eigen::VectorXi bone =
      posing::boneVerticesOfLabels(rig.tets.T, rig.tets.tetAttributes.integer.at(kLabel), boneLabels, rig.tets.V.rows());
  rig.boneJoint = compactBones(bone, int(rig.skeleton.joints.size()));
  weighRig(built, bone, o, progress);
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

// Sujar et al. 2018, §3.2 for a reference anatomy: its skin and, per joint, the bone meshes of the joint's OpenSim
// body (the tissues' group, jointOfBody) voxelized into one label map (bone_mesh_labels.h: label j + 1
// for joint j), then nested region surfaces as for --labels. boneLabels: per joint its label, none for a
// joint with no bone voxel (a hand outside the skin at coarse voxels would have none).
std::vector<meshing::RegionSurface> referenceRegions(const ReferenceAnatomy& reference, const Skeleton& skeleton,
                                                     std::vector<std::vector<Label>>& boneLabels, const RigOptions& o,
                                                     const std::string& source, Progress& progress) {
  std::vector<BoneMeshes> bones(skeleton.joints.size());
  for (std::size_t j = 0; j < bones.size(); ++j) bones[j].name = skeleton.joints[j].name;
  for (const ReferenceTissue& t : reference.tissues) {
    const int j = skeleton.find(jointOfBody(t.group));
    if (j >= 0) bones[std::size_t(j)].meshes.push_back(&t.mesh);
  }
  const LabelMap map = boneMeshLabelMap(reference.skin, bones, bodyGrid(reference.skin, o), source);
  std::vector<long> voxels(bones.size() + 2, 0);
  for (Label l : map.labels.values) ++voxels[l];
  boneLabels.assign(bones.size(), {});
  for (std::size_t j = 0; j < bones.size(); ++j)
    if (voxels[j + 1] > 0) boneLabels[j] = {Label(j + 1)};
  return boneRegions(map, boneLabels, Label(bones.size() + 1), false, o, source, progress);
}

// The skeleton's torso meshes in `reference`: the options' as far as it holds them, and every other bone of
// the torso's joint (a scan's labelled vertebrae, ribs or scapulae that take the place of OpenSim's one-mesh
// spine and rib cage inside its field of view, patient/whole_model.h) with the torso, the spine and the
// scapulae alike: the lumbar joint lies where the spine's meshes come nearest the sacrum and the shoulders
// where the humeri come nearest the scapulae, so that bones farther away change neither.
// A list with no mesh at all is left whole, for skeletonFromBoneMeshes to name what is missing.
posing::SkeletonFromBoneMeshesOptions withTorsoOf(const ReferenceAnatomy& reference, posing::SkeletonFromBoneMeshesOptions o) {
  std::set<std::string> names;
  for (const ReferenceTissue& t : reference.tissues) names.insert(t.name);
  const std::vector<std::string> named = o.torso;
  for (const ReferenceTissue& t : reference.tissues)
    if (t.kind == TissueKind::Bone && jointOfBody(t.group) == "torso" &&
        std::find(named.begin(), named.end(), t.name) == named.end())
      for (std::vector<std::string>* list : {&o.torso, &o.spine, &o.scapulae}) list->push_back(t.name);
  for (std::vector<std::string>* list : {&o.torso, &o.spine, &o.scapulae}) {
    const auto missing = [&](const std::string& n) { return !names.count(n); };
    if (!std::all_of(list->begin(), list->end(), missing))
      list->erase(std::remove_if(list->begin(), list->end(), missing), list->end());
  }
  return o;
}

}  // namespace

void checkRigTargetTets(long targetTets, std::size_t bones, bool reference) {
  const long least = leastTargetTets(rigRegionOptions(!reference), bones, reference ? kMinSkinFaces : kMinBodyFaces);
  if (targetTets < least)
    throw UsageError(std::to_string(targetTets) + " tets are too few for a rig of " + std::to_string(bones) +
                     " bones: the body's and the bones' surfaces keep at least " + std::to_string(least / 2) +
                     " triangles, which alone make more than twice as many tets; ask for at least " +
                     std::to_string(least));
}

BuiltRig rigFromSkeleton(const TriMesh& skin, const Skeleton& skeleton, const RigOptions& options,
                         const std::string& source, const std::string& skeletonSource, Progress* progress) {
  Progress none;
  Progress& p = progress ? *progress : none;
  BuiltRig built;
  built.rig.skeleton = skeleton;
  timed(built, "tetrahedralize", [&] {
    p.begin("tetrahedralize", "voxelize the skin, surface it, TetGen");
    built.rig.tets = bodyTets(skin, options, source);
    p.end();
  });
  Eigen::VectorXi bone = posing::boneCapsuleVertices(built.rig.tets.V, skeleton, skin, options.capsules);
  separateBones(built.rig.tets, int(skeleton.joints.size()), bone);
  holdEmptyCapsules(built.rig.tets, skeleton, options.capsules, bone);
  built.rig.boneJoint = compactBones(bone, int(skeleton.joints.size()));
  if (built.rig.boneJoint.empty())
    throw BadInput(skeletonSource, "no bone of the skeleton lies inside the skin " + source +
                                       "; is the skeleton in the skin's space and place?");
  weighRig(built, bone, options, p);
  return built;
}

BuiltRig rigFromBoneLabels(const LabelMap& labels, const posing::SkeletonFromBonesOptions& bonesOptions,
                           const RigOptions& options, const std::string& source, Progress* progress) {
  Progress none;
  Progress& p = progress ? *progress : none;
  const posing::BoneSkeleton bones = posing::skeletonFromBones(labels, bonesOptions, source);
  const Label body = bodyLabel(bones.labels);
  BuiltRig built;
  built.rig.skeleton = bones.skeleton;
  built.femoralHeadRadiusLeft = bones.femoralHeadLeft.radius;
  built.femoralHeadRadiusRight = bones.femoralHeadRight.radius;
  std::vector<meshing::RegionSurface> regions;
  timed(built, "surfaces", [&] {
    p.begin("surfaces", "the body and its bones, nested");
    regions = boneRegions(bonesBox(labels, bones, options.margin, options.voxelSize), bones.labels, body, true,
                          options, source, p);
    p.end();
  });
  rigOfRegions(built, regions, bones.labels, options, p);
  for (meshing::RegionSurface& r : regions) {
    const LabelEntry* entry = labels.table.find(Label(r.label));
    built.regionSurfaces.emplace_back((r.label == body || !entry ? "skin" : entry->name) + ".vtp", std::move(r.surface));
  }
  return built;
}

BuiltRig rigFromReference(const ReferenceAnatomy& reference, const posing::SkeletonFromBoneMeshesOptions& bonesOptions,
                          const RigOptions& options, const std::string& source, Progress* progress) {
  Progress none;
  Progress& p = progress ? *progress : none;
  std::map<std::string, TriMesh> byName;
  for (const ReferenceTissue& t : reference.tissues) byName.emplace(t.name, t.mesh);
  const posing::MeshSkeleton bones = posing::skeletonFromBoneMeshes(byName, withTorsoOf(reference, bonesOptions), source);
  BuiltRig built;
  built.rig.skeleton = bones.skeleton;
  built.femoralHeadRadiusLeft = bones.left.femoralHead.radius;
  built.femoralHeadRadiusRight = bones.right.femoralHead.radius;
  std::vector<std::vector<Label>> boneLabels;
  std::vector<meshing::RegionSurface> regions;
  timed(built, "surfaces", [&] {
    p.begin("surfaces", "skin and bone meshes voxelized; the body and its bones, nested");
    regions = referenceRegions(reference, built.rig.skeleton, boneLabels, options, source, p);
    p.end();
  });
  rigOfRegions(built, regions, boneLabels, options, p);
  for (const ReferenceTissue& t : reference.tissues)
    if (const int j = built.rig.skeleton.find(jointOfBody(t.group)); j >= 0) built.boneJoints[t.name] = j;
  return built;
}

std::vector<int> meshJoints(const std::vector<std::string>& meshes, const std::map<std::string, int>& boneJoints) {
  std::vector<int> joints;
  for (const std::string& file : meshes) {
    const auto found = boneJoints.find(std::filesystem::path(file).stem().string());
    joints.push_back(found == boneJoints.end() ? -1 : found->second);
  }
  return joints;
}

}  // namespace vesalius::rigging
