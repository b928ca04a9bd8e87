#include "vesalius/patient/whole_model.h"

#include "labels_with_voxels.h"

#include "vesalius/meshing/label_surface.h"
#include "vesalius/meshing/surface_samples.h"

#include <algorithm>

namespace vesalius::patient {

std::map<std::string, MatrixX3d> boneGroupTargets(const ReferenceAnatomy& reference, const LabelMap& organs,
                                                  const std::vector<std::pair<std::string, std::string>>& groupLabels,
                                                  int pointsPerGroup) {
  const LabelsWithVoxels present(organs);
  std::map<std::string, std::vector<Label>> groups;
  for (const auto& [group, label] : groupLabels) {
    if (std::none_of(reference.tissues.begin(), reference.tissues.end(),
                     [&](const ReferenceTissue& t) { return t.kind == TissueKind::Bone && t.group == group; }))
      continue;
    const bool prefix = !label.empty() && label.back() == '*';
    const std::string stem = prefix ? label.substr(0, label.size() - 1) : label;
    for (const LabelEntry& e : organs.table.entries)
      if (present.has(e.id) && (prefix ? e.name.rfind(stem, 0) == 0 : e.name == stem))
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
  const LabelsWithVoxels present(*organs);
  std::vector<std::string> represented;
  for (const auto& [tissueName, label] : boneLabels) {
    const Label id = present.idOf(label);
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
