#include "vesalius/core/anatomy.h"

#include "vesalius/core/error.h"

#include <map>
#include <set>

namespace vesalius {

const char* tissueKindName(TissueKind kind) {
  switch (kind) {
    case TissueKind::Bone: return "bone";
    case TissueKind::Muscle: return "muscle";
    case TissueKind::Organ: return "organ";
    case TissueKind::Other: return "other";
  }
  return "other";
}

DisplayColour tissueKindColour(TissueKind kind) {
  switch (kind) {
    case TissueKind::Bone: return {235, 225, 200};
    case TissueKind::Muscle: return {190, 60, 55};
    case TissueKind::Organ:
    case TissueKind::Other: break;
  }
  return {150, 100, 80};
}

TissueKind tissueKindFromName(const std::string& name) {
  for (TissueKind kind : {TissueKind::Bone, TissueKind::Muscle, TissueKind::Organ, TissueKind::Other})
    if (name == tissueKindName(kind)) return kind;
  throw UsageError("unknown tissue kind '" + name + "' (expected bone, muscle, organ or other)");
}

void ReferenceAnatomy::validate(const std::string& source) const {
  if (skin.V.rows() == 0 || skin.F.rows() == 0) throw BadInput(source, "the skin mesh is empty");
  skin.validate(source + " (skin)");
  if (!sagittal.point.allFinite() || !sagittal.normal.allFinite() || sagittal.normal.norm() < 1e-12)
    throw BadInput(source, "the sagittal plane needs a finite point and a non-zero normal");
  for (const int v : skinCutVertices)
    if (v < 0 || v >= skin.V.rows()) throw BadInput(source, "cut vertex " + std::to_string(v) + " is not a skin vertex");
  std::set<std::string> names;
  std::map<std::string, bool> groupSymmetry;
  for (const ReferenceTissue& tissue : tissues) {
    if (!names.insert(tissue.name).second) throw BadInput(source, "tissue '" + tissue.name + "' appears twice");
    if (tissue.mesh.V.rows() == 0) throw BadInput(source, "tissue '" + tissue.name + "' has no vertices");
    tissue.mesh.validate(source + " (" + tissue.name + ")");
    if (tissue.group.empty()) continue;
    if (tissue.kind != TissueKind::Bone)
      throw BadInput(source, "tissue '" + tissue.name + "' is in bone group '" + tissue.group + "' but is not a bone");
    const auto [it, inserted] = groupSymmetry.emplace(tissue.group, tissue.symmetric);
    if (!inserted && it->second != tissue.symmetric)
      throw BadInput(source, "the tissues of group '" + tissue.group + "' disagree on 'symmetric'");
  }
  for (const ReferencePoint& point : points) {
    if (!point.position.allFinite()) throw BadInput(source, "point '" + point.name + "' is not finite");
    if (!point.tissue.empty() && !names.count(point.tissue))
      throw BadInput(source, "point '" + point.name + "' is fixed to unknown tissue '" + point.tissue + "'");
  }
}

}  // namespace vesalius
