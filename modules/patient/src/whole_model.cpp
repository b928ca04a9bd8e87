#include "vesalius/patient/whole_model.h"

#include "labels_with_voxels.h"
#include "skin_distances.h"

#include "vesalius/core/cap_holes.h"
#include "vesalius/core/keep_faces.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/meshing/surface_samples.h"
#include "vesalius/transfer/tissues_bent_apart.h"

#include <algorithm>

namespace vesalius::patient {

bool labelMatches(const std::string& name, const std::string& pattern) {
  if (!pattern.empty() && pattern.back() == '*') return name.rfind(pattern.substr(0, pattern.size() - 1), 0) == 0;
  return name == pattern;
}

namespace {

// Whether the organ map has voxels of a label `pattern` matches.
bool hasLabel(const LabelMap& organs, const LabelsWithVoxels& present, const std::string& pattern) {
  return std::any_of(organs.table.entries.begin(), organs.table.entries.end(),
                     [&](const LabelEntry& e) { return present.has(e.id) && labelMatches(e.name, pattern); });
}

// Faces of `mesh` wholly beyond the scan's extent (the box of its voxels, half a voxel beyond the outer
// voxel centres): a face with a vertex inside would hold that vertex where the labels' bones are.
std::vector<bool> facesBeyond(const TriMesh& mesh, const GridGeometry& scan) {
  const Eigen::Array3d first = Eigen::Array3d::Constant(-0.5), last = scan.size.cast<double>().array() - 0.5;
  std::vector<bool> inside(std::size_t(mesh.V.rows()));
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    const Eigen::Array3d index = scan.worldToIndex(mesh.V.row(v).transpose()).array();
    inside[std::size_t(v)] = (index >= first).all() && (index <= last).all();
  }
  std::vector<bool> beyond(std::size_t(mesh.F.rows()));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    beyond[std::size_t(f)] = !inside[std::size_t(mesh.F(f, 0))] && !inside[std::size_t(mesh.F(f, 1))] &&
                             !inside[std::size_t(mesh.F(f, 2))];
  return beyond;
}

}  // namespace

std::map<std::string, MatrixX3d> boneGroupTargets(const ReferenceAnatomy& reference, const LabelMap& organs,
                                                  const std::vector<std::pair<std::string, std::string>>& groupLabels,
                                                  int pointsPerGroup) {
  const LabelsWithVoxels present(organs);
  std::map<std::string, std::vector<Label>> groups;
  for (const auto& [group, label] : groupLabels) {
    if (std::none_of(reference.tissues.begin(), reference.tissues.end(),
                     [&](const ReferenceTissue& t) { return t.kind == TissueKind::Bone && t.group == group; }))
      continue;
    for (const LabelEntry& e : organs.table.entries)
      if (present.has(e.id) && labelMatches(e.name, label)) groups[group].push_back(e.id);
  }
  std::map<std::string, MatrixX3d> targets;
  for (const auto& [group, ids] : groups) {
    TriMesh boundary;
    for (const meshing::LabelSurface& s : meshing::labelSurfaces(organs, ids)) {
      const TriMesh inside = meshing::withinScan(s.mesh, organs.labels.geometry);
      boundary = boundary.F.rows() ? concatenate(boundary, inside) : inside;
    }
    if (boundary.F.rows() == 0) continue;
    targets[group] = meshing::spreadSurfacePoints(boundary, std::min<int>(pointsPerGroup, int(boundary.F.rows())), 1);
  }
  return targets;
}

WholeModel wholeModel(const ReferenceAnatomy& completed, const ReferenceAnatomy& inFov, const LabelMap* organs,
                      const WholeModelOptions& options, const std::string& organsSource) {
  WholeModel model;
  model.anatomy = completed;
  if (!organs) return model;
  const LabelsWithVoxels present(*organs);
  std::vector<ReferenceTissue>& tissues = model.anatomy.tissues;
  const auto named = [&](const std::string& name) {
    return std::find_if(tissues.begin(), tissues.end(), [&](const ReferenceTissue& x) { return x.name == name; });
  };
  // The labels the registered bones represent; the tissues that are the patient's (those bones and the
  // scan's), which the reference's give way to.
  std::vector<std::string> represented, patientTissues;
  for (const auto& [tissueName, label] : options.boneLabels) {
    const Label id = present.idOf(label);
    const auto t = named(tissueName);
    if (!id || t == tissues.end()) continue;
    RegisteredBone bone{tissueName, label,
                        registerBoneOntoLabel(t->mesh, *organs, {id}, options.bones, completed.name + ": " + tissueName, organsSource)};
    t->mesh = bone.registration.mesh;
    model.labelTissues[label] = {tissueName};
    represented.push_back(label);
    patientTissues.push_back(tissueName);
    model.bones.push_back(std::move(bone));
  }
  // Bones on labels that share voxel faces, everywhere (they go on beyond the scan).
  std::vector<TriMesh*> onLabels;
  for (const RegisteredBone& bone : model.bones) onLabels.push_back(&named(bone.tissue)->mesh);
  model.bonesApart = meshing::moveLabelSurfacesApart(onLabels, nullptr);
  for (const auto& [tissueName, label] : options.replacedInsideScan) {
    const auto t = named(tissueName);
    if (t == tissues.end() || !hasLabel(*organs, present, label)) continue;
    const std::vector<bool> keep = facesBeyond(t->mesh, organs->labels.geometry);
    const long gone = long(std::count(keep.begin(), keep.end(), false));
    if (gone == 0) continue;
    model.replacedFaces.emplace_back(tissueName, gone);
    t->mesh = capHoles(keepFaces(t->mesh, keep));
    if (t->mesh.F.rows() == 0) tissues.erase(t);
  }
  // Each group's symmetry, which a bone joining it takes (a group agrees on it, core/anatomy.h).
  std::map<std::string, bool> groupSymmetric;
  for (const ReferenceTissue& t : tissues)
    if (!t.group.empty()) groupSymmetric.emplace(t.group, t.symmetric);
  for (const ReferenceTissue& tissue : inFov.tissues) {
    if (std::find(represented.begin(), represented.end(), tissue.name) != represented.end()) continue;
    ReferenceTissue added = tissue;
    added.group.clear();  // the scan's groups are its own; the reference's are OpenSim's bodies
    added.symmetric = false;
    if (added.kind == TissueKind::Bone)
      for (const auto& [group, label] : options.groupLabels)
        if (labelMatches(tissue.name, label) && groupSymmetric.count(group)) {
          added.group = group;
          added.symmetric = groupSymmetric.at(group);
          break;
        }
    if (const auto same = named(tissue.name); same != tissues.end())
      *same = std::move(added);
    else
      tissues.push_back(std::move(added));
    model.labelTissues[tissue.name] = {tissue.name};
    patientTissues.push_back(tissue.name);
  }
  // The bones on labels moved out of the scan's tissues of the labels they touch (the bladder against a hip
  // bone), in the field of view, where the label map puts their boundary; the scan's tissues stay.
  if (!model.bones.empty()) {
    std::vector<TriMesh*> labelled;
    meshing::LabelSurfacesApartOptions scanFixed;
    for (const std::string& name : patientTissues)
      if (const auto t = named(name); t != tissues.end()) {
        labelled.push_back(&t->mesh);
        scanFixed.fixed.push_back(std::none_of(model.bones.begin(), model.bones.end(),
                                               [&](const RegisteredBone& b) { return b.tissue == name; }));
      }
    model.bonesApartFromScan = meshing::moveLabelSurfacesApart(labelled, &organs->labels.geometry, scanFixed);
  }
  std::vector<transfer::BendRole> roles;
  for (const ReferenceTissue& t : tissues)
    roles.push_back(std::find(patientTissues.begin(), patientTissues.end(), t.name) != patientTissues.end()
                        ? transfer::BendRole::Fixed
                        : transfer::BendRole::Bent);
  model.apart = transfer::bendTissuesApart(model.anatomy, roles, skinDistances(model.anatomy.skin), options.apart);
  return model;
}

}  // namespace vesalius::patient
