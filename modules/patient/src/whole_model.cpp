#include "vesalius/patient/whole_model.h"

#include "vesalius/meshing/label_surface.h"
#include "vesalius/meshing/surface_samples.h"

#include <algorithm>

namespace vesalius::patient {

namespace {

// The label's id in `organs` if it has voxels, else 0.
Label presentLabel(const LabelMap& organs, const std::string& name) {
  const LabelEntry* e = organs.table.find(name);
  if (!e || e->id == 0) return 0;
  return std::find(organs.labels.values.begin(), organs.labels.values.end(), e->id) != organs.labels.values.end() ? e->id : 0;
}

const ReferenceTissue* findTissue(const ReferenceAnatomy& a, const std::string& name) {
  const auto t = std::find_if(a.tissues.begin(), a.tissues.end(), [&](const ReferenceTissue& x) { return x.name == name; });
  return t == a.tissues.end() ? nullptr : &*t;
}

}  // namespace

std::map<std::string, MatrixX3d> boneGroupTargets(const ReferenceAnatomy& reference, const LabelMap& organs,
                                                  const std::vector<std::pair<std::string, std::string>>& groupLabels,
                                                  int pointsPerGroup) {
  std::vector<char> present;
  for (const Label l : organs.labels.values) {
    if (std::size_t(l) >= present.size()) present.resize(std::size_t(l) + 1, 0);
    present[std::size_t(l)] = 1;
  }
  std::map<std::string, std::vector<Label>> groups;
  for (const auto& [group, label] : groupLabels) {
    if (std::none_of(reference.tissues.begin(), reference.tissues.end(),
                     [&](const ReferenceTissue& t) { return t.kind == TissueKind::Bone && t.group == group; }))
      continue;
    const bool prefix = !label.empty() && label.back() == '*';
    const std::string stem = prefix ? label.substr(0, label.size() - 1) : label;
    for (const LabelEntry& e : organs.table.entries)
      if (e.id != 0 && std::size_t(e.id) < present.size() && present[std::size_t(e.id)] &&
          (prefix ? e.name.rfind(stem, 0) == 0 : e.name == stem))
        groups[group].push_back(e.id);
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
                      const std::vector<std::pair<std::string, std::string>>& boneLabels,
                      const BoneOntoLabelOptions& options, const std::string& organsSource) {
  WholeModel model;
  model.anatomy = completed;
  if (!organs) return model;
  std::vector<std::string> represented;
  for (const auto& [tissueName, label] : boneLabels) {
    const Label id = presentLabel(*organs, label);
    const auto t = std::find_if(model.anatomy.tissues.begin(), model.anatomy.tissues.end(),
                                [&](const ReferenceTissue& x) { return x.name == tissueName; });
    if (!id || t == model.anatomy.tissues.end()) continue;
    RegisteredBone bone{tissueName, label,
                        registerBoneOntoLabel(t->mesh, *organs, {id}, options, completed.name + ": " + tissueName, organsSource)};
    t->mesh = bone.registration.mesh;
    model.labelTissues[label] = {tissueName};
    represented.push_back(label);
    model.bones.push_back(std::move(bone));
  }
  for (const ReferenceTissue& tissue : inFov.tissues) {
    if (std::find(represented.begin(), represented.end(), tissue.name) != represented.end()) continue;
    const auto same = std::find_if(model.anatomy.tissues.begin(), model.anatomy.tissues.end(),
                                   [&](const ReferenceTissue& x) { return x.name == tissue.name; });
    ReferenceTissue added = tissue;
    added.group.clear();  // the reference's groups are OpenSim's bodies; a label is a tissue of its own
    added.symmetric = false;
    if (same != model.anatomy.tissues.end())
      *same = std::move(added);
    else
      model.anatomy.tissues.push_back(std::move(added));
    model.labelTissues[tissue.name] = {tissue.name};
  }
  return model;
}

}  // namespace vesalius::patient
