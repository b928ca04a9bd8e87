// The MRI tissue classifier: runs the stages of mri_tissues.h and writes the labels.
#include "skin_shell.h"
#include "mri_stages.h"
#include "run_stage.h"
#include "vesalius/core/error.h"

#include <string>

namespace vesalius::segmentation {
namespace {

void validate(const Image& scan, const MriTissueOptions& o) {
  scan.geometry.validate("MRI");
  if (scan.values.size() != static_cast<std::size_t>(scan.geometry.voxelCount()))
    throw BadInput("", "MRI has " + std::to_string(scan.values.size()) + " values for " +
                           std::to_string(scan.geometry.voxelCount()) + " voxels");
  if (!(o.skinThicknessMm >= 0) || !(o.layerDepthMm > o.skinThicknessMm) || !(o.bodyOtsuFraction > 0) ||
      !(o.maxBoneDistanceMm >= o.boneSeedDistanceMm))
    throw UsageError("MRI tissue options need skin thickness >= 0, layer depth > skin thickness, "
                     "a positive Otsu fraction and bone distance >= seed distance");
}

}  // namespace

LabelMap segmentMriTissues(const Image& scan, const MriTissueOptions& options, Progress* progress) {
  validate(scan, options);
  Mask body, skin;
  detail::MriLayers layers;
  detail::runStage(progress, "body", [&] { body = segmentMriBody(scan, options); });
  detail::runStage(progress, "skin", [&] { skin = detail::skinShell(body, options.skinThicknessMm); });
  detail::runStage(progress, "fat and bone", [&] { layers = detail::mriLayers(scan, body, skin, options); });
  LabelMap result;
  result.labels = Grid<Label>(scan.geometry, kMriBackground);
  paintMask(result.labels, body, kMriSoftTissue);
  paintMask(result.labels, layers.bone, kMriBone);
  paintMask(result.labels, layers.fat, kMriSubcutaneousFat);
  paintMask(result.labels, skin, kMriSkin);
  result.table = mriTissueTable();
  return result;
}

}  // namespace vesalius::segmentation
