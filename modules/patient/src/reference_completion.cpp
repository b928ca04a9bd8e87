#include "vesalius/patient/reference_completion.h"

#include "skin_distances.h"

#include "vesalius/core/error.h"
#include "vesalius/core/stage_clock.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/transfer/surface_harmonic_extension.h"


namespace vesalius::patient {
namespace {

// The bone tissues of both anatomies, for the alignment (AlignmentBones); false if either has none.
bool alignmentBones(const ReferenceAnatomy& patient, const ReferenceAnatomy& reference, transfer::AlignmentBones& bones) {
  TriMesh source;
  for (const ReferenceTissue& t : reference.tissues)
    if (t.kind == TissueKind::Bone) source = source.V.rows() ? concatenate(source, t.mesh) : t.mesh;
  bones.target.resize(0, 3);
  for (const ReferenceTissue& t : patient.tissues)
    if (t.kind == TissueKind::Bone) {
      bones.target.conservativeResize(bones.target.rows() + t.mesh.V.rows(), 3);
      bones.target.bottomRows(t.mesh.V.rows()) = t.mesh.V;
    }
  bones.sourceV = source.V;
  bones.sourceF = source.F;
  return source.V.rows() > 0 && bones.target.rows() > 0;
}

}  // namespace

ReferenceCompletion completeWithReference(const ReferenceAnatomy& patientInFov, const Eigen::VectorXd& fatThickness,
                                          const ReferenceAnatomy& fullBodyReference,
                                          const ReferenceCompletionOptions& options, Progress* progress) {
  const TriMesh& skin = patientInFov.skin;
  if (fatThickness.size() != skin.V.rows())
    throw BadInput("", "reference completion: the fat needs one value per patient skin vertex");
  ReferenceCompletion c;
  StageClock clock(c.stageSeconds);
  if (progress) progress->begin("complete", "the full-body reference registered to the skin the scan sees");
  transfer::AlignmentBones bones;
  const bool withBones = options.alignBones && alignmentBones(patientInFov, fullBodyReference, bones);
  c.registration = transfer::registerSkinToPartialTarget(fullBodyReference.skin.V, fullBodyReference.skin.F, skin.V, skin.F,
                                                         patientInFov.skinCutVertices, options.registration,
                                                         withBones ? &bones : nullptr);
  c.pulled = c.registration.pulled;
  if (progress) progress->end();
  clock.end("partial skin registration");

  // Step 2: the patient's fat where the scan pulled the skin, continued beyond.
  const MatrixX3d& completed = c.registration.V;
  const std::vector<ClosestPoint> closest = TriangleTree(skin.V, skin.F).closest(completed);
  Eigen::MatrixXd fat = Eigen::MatrixXd::Zero(completed.rows(), 1);
  for (Eigen::Index v = 0; v < completed.rows(); ++v) {
    if (!c.pulled[std::size_t(v)]) continue;
    const ClosestPoint& p = closest[std::size_t(v)];
    for (int k = 0; k < 3; ++k) fat(v, 0) += p.barycentric[k] * fatThickness[skin.F(p.face, k)];
  }
  c.fatThickness = transfer::extendHarmonically(fat, c.pulled, fullBodyReference.skin.F).col(0);
  clock.end("fat");

  c.transfer = transferIntoBody(fullBodyReference, completed, c.fatThickness,
                                transfer::skinPartsFromBones(fullBodyReference), options.transfer, progress);
  for (const auto& stage : c.transfer.stageSeconds) c.stageSeconds.push_back(stage);
  c.anatomy = c.transfer.anatomy;
  c.anatomy.name = "completed from " + fullBodyReference.name;
  c.erodedSkin = c.transfer.erodedSkin;

  // Step 4: one displacement for all tissues, so that tissues side by side stay so.
  const transfer::InsideSkinWarp bend = bendTissuesIntoSkin(c.anatomy, options.intoSkin);
  c.outsideBefore = bend.outsideBefore;
  c.outsideAfter = bend.outsideAfter;
  c.bendLargestMm = bend.largestMoveMm;
  clock.end("tissues into the skin");
  return c;
}

}  // namespace vesalius::patient
