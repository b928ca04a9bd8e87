// The CT tissue classifier: runs the stages of ct_tissues.h and writes the labels.
#include "ct_stages.h"
#include "run_stage.h"
#include "vesalius/core/error.h"

#include <limits>
#include <string>

namespace vesalius::segmentation {
namespace {

// Bone voxels at or above corticalMinHu stay kCtBone (cortical); the others become trabecular.
void splitBone(Grid<Label>& labels, const Image& ct, float corticalMinHu) {
  for (std::size_t n = 0; n < labels.values.size(); ++n)
    if (labels.values[n] == kCtBone && ct.values[n] < corticalMinHu) labels.values[n] = kCtTrabecularBone;
}

void validate(const Image& ct, const CtTissueOptions& o) {
  ct.geometry.validate("CT");
  if (ct.values.size() != static_cast<std::size_t>(ct.geometry.voxelCount()))
    throw BadInput("", "CT has " + std::to_string(ct.values.size()) + " values for " +
                           std::to_string(ct.geometry.voxelCount()) + " voxels");
  if (!(o.fatMinHu < o.fatMaxHu) || !(o.fatMaxHu < o.boneMinHu) || !(o.skinThicknessMm >= 0))
    throw UsageError("CT tissue options need fatMinHu < fatMaxHu < boneMinHu and skin thickness >= 0");
}

}  // namespace

LabelMap segmentCtTissues(const Image& ct, const CtTissueOptions& options, Progress* progress) {
  validate(ct, options);
  Mask body, skin, bone, subcutaneous;
  detail::runStage(progress, "body", [&] { body = segmentCtBody(ct, options); });
  detail::runStage(progress, "skin", [&] { skin = detail::skinShell(body, options.skinThicknessMm); });
  detail::runStage(progress, "bone", [&] { bone = maskAndNot(detail::ctBone(ct, body, options), skin); });
  const Mask inner = maskAndNot(maskAndNot(body, skin), bone);
  const Mask fat = maskAnd(inner, thresholdMask(ct, options.fatMinHu, options.fatMaxHu));
  detail::runStage(progress, "subcutaneous fat", [&] {
    subcutaneous = detail::subcutaneousFat(body, fat, maskOr(maskAndNot(inner, fat), bone), options);
  });
  LabelMap result;
  result.labels = Grid<Label>(ct.geometry, kCtAir);
  paintMask(result.labels,
        maskAnd(inner, thresholdMask(ct, options.fatMaxHu, std::numeric_limits<float>::infinity())),
        kCtSoftTissue);
  paintMask(result.labels, fat, kCtFat);
  paintMask(result.labels, subcutaneous, kCtSubcutaneousFat);
  paintMask(result.labels, bone, kCtBone);
  paintMask(result.labels, skin, kCtSkin);
  if (options.splitBone) splitBone(result.labels, ct, options.corticalMinHu);
  result.table = ctTissueTable(options.splitBone);
  return result;
}

}  // namespace vesalius::segmentation
