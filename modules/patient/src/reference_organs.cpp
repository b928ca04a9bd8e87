#include "vesalius/patient/reference_organs.h"

#include "skin_distances.h"

#include "vesalius/core/error.h"
#include "vesalius/core/stage_clock.h"
#include "vesalius/meshing/surface_samples.h"
#include "vesalius/meshing/winding_number.h"

#include <algorithm>
#include <map>

namespace vesalius::patient {

namespace {

bool isSoftTissue(TissueKind kind) { return kind == TissueKind::Organ || kind == TissueKind::Muscle; }

// The reference's own bones as the targets of the transfer's per-bone registration (Dicko et al. 2013, §8 with the
// target's bones known): each bone group's meshes, 2,000 points spread over them.
std::map<std::string, MatrixX3d> ownBones(const ReferenceAnatomy& reference) {
  std::map<std::string, TriMesh> groups;
  for (const ReferenceTissue& t : reference.tissues) {
    if (t.kind != TissueKind::Bone || t.group.empty()) continue;
    TriMesh& g = groups[t.group];
    g = g.F.rows() ? concatenate(g, t.mesh) : t.mesh;
  }
  std::map<std::string, MatrixX3d> targets;
  for (const auto& [group, mesh] : groups)
    targets[group] = meshing::spreadSurfacePoints(mesh, std::min<int>(2000, int(mesh.F.rows())), 1);
  return targets;
}

}  // namespace

ReferenceOrgans referenceOrgans(const Image& ct, const LabelMap& organs, const std::vector<OrganTemplate>& templates,
                                const ReferenceAnatomy& fullBodyReference, const ReferenceOrgansOptions& options,
                                const std::string& scanSource, const std::string& organsSource, Progress* progress) {
  ReferenceOrgans result;
  StageClock clock(result.stageSeconds);
  // Step 1 on the reference's bones alone: organs it already holds would pass into the model unreplaced.
  ReferenceAnatomy bones = fullBodyReference;
  bones.tissues.erase(std::remove_if(bones.tissues.begin(), bones.tissues.end(),
                                     [](const ReferenceTissue& t) { return isSoftTissue(t.kind); }),
                      bones.tissues.end());
  VirtualPatientOptions patientOptions = options.patient;
  patientOptions.fullBodyReference = &bones;
  const VirtualPatient patient =
      buildVirtualPatient(ct, &organs, templates, patientOptions, scanSource, organsSource, progress);
  result.scanSkinToCompletedMeanMm = patient.completion->registration.skinMeanDistance;
  clock.end("virtual patient");

  // Step 2: the model's skin onto the reference's skin (the same vertices), no erosion, each bone group
  // onto the reference's own.
  ReferenceAnatomy model = patient.whole->anatomy;
  model.skinCutVertices.clear();
  if (progress) progress->begin("back", "the model carried into the reference's skin");
  TransferIntoBodyOptions transferOptions = options.transfer;
  transferOptions.transfer.boneTargets = ownBones(bones);
  const TransferIntoBody back = transferIntoBody(model, bones.skin.V, Eigen::VectorXd::Zero(bones.skin.V.rows()),
                                                 transfer::SkinParts{}, transferOptions, nullptr);
  if (progress) progress->end();
  clock.end("transfer into the reference");

  // Step 3: the kept tissues, in the order of options.tissues.
  result.anatomy.name = "organs and muscles of " + scanSource + " in " + fullBodyReference.name;
  result.anatomy.skin = fullBodyReference.skin;
  result.anatomy.sagittal = fullBodyReference.sagittal;
  const auto outsideSkin = [&](const MatrixX3d& V) {
    const Eigen::VectorXd w = meshing::windingNumbers(result.anatomy.skin.V, result.anatomy.skin.F, V);
    return long((w.array() < 0.5).count());
  };
  for (const std::string& name : options.tissues) {
    const auto t = std::find_if(back.anatomy.tissues.begin(), back.anatomy.tissues.end(),
                                [&](const ReferenceTissue& x) { return x.name == name && isSoftTissue(x.kind); });
    if (t == back.anatomy.tissues.end()) continue;
    ReferenceTissue kept = *t;
    kept.group.clear();
    kept.symmetric = false;
    result.carried.push_back({kept.name, kept.kind, long(kept.mesh.V.rows()), outsideSkin(kept.mesh.V), 0});
    result.anatomy.tissues.push_back(std::move(kept));
  }
  clock.end("kept tissues");

  // Step 4: one displacement for all, so that tissues side by side stay so.
  result.bendLargestMm = bendTissuesIntoSkin(result.anatomy, options.intoSkin).largestMoveMm;
  for (std::size_t t = 0; t < result.anatomy.tissues.size(); ++t)
    result.carried[t].outsideSkin = outsideSkin(result.anatomy.tissues[t].mesh.V);
  clock.end("bent inside the skin");
  if (result.anatomy.tissues.empty())
    throw BadInput(organsSource, "none of the reference's organs and muscles (liver, kidney_left, gluteus_maximus_left, "
                                 "...) has voxels in the label map");
  result.anatomy.validate(organsSource);
  return result;
}

}  // namespace vesalius::patient
