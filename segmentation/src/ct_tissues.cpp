// The CT tissue classifier: runs the stages of ct_tissues.h and writes the labels.
#include "ct_stages.h"

#include "vesalius/core/error.h"

#include <functional>
#include <string>

namespace vesalius::segmentation {
namespace {

void runStage(Progress* progress, const std::string& name, const std::function<void()>& work) {
  if (progress) progress->begin(name);
  work();
  if (progress) {
    progress->update(1.0);
    progress->end();
  }
}

void paint(Grid<Label>& labels, const Mask& mask, Label id) {
  for (std::size_t n = 0; n < mask.values.size(); ++n)
    if (mask.values[n]) labels.values[n] = id;
}

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
  runStage(progress, "body", [&] { body = segmentCtBody(ct, options); });
  runStage(progress, "skin", [&] { skin = detail::skinShell(body, options.skinThicknessMm); });
  runStage(progress, "bone", [&] { bone = maskAndNot(detail::ctBone(ct, body, options), skin); });
  const Mask inner = maskAndNot(maskAndNot(body, skin), bone);
  const Mask fat = maskAnd(inner, thresholdMask(ct, options.fatMinHu, options.fatMaxHu));
  runStage(progress, "subcutaneous fat", [&] {
    subcutaneous = detail::subcutaneousFat(body, fat, maskOr(maskAndNot(inner, fat), bone), options);
  });
  LabelMap result;
  result.labels = Grid<Label>(ct.geometry, kCtAir);
  paint(result.labels, maskAnd(inner, thresholdMask(ct, options.fatMaxHu, 1e30f)), kCtSoftTissue);
  paint(result.labels, fat, kCtFat);
  paint(result.labels, subcutaneous, kCtSubcutaneousFat);
  paint(result.labels, bone, kCtBone);
  paint(result.labels, skin, kCtSkin);
  if (options.splitBone) splitBone(result.labels, ct, options.corticalMinHu);
  result.table = ctTissueTable(options.splitBone);
  return result;
}

}  // namespace vesalius::segmentation
