#include "vesalius/segmentation/scan_modality.h"

#include "vesalius/segmentation/ct_tissues.h"
#include "vesalius/segmentation/mri_tissues.h"

#include <algorithm>

namespace vesalius::segmentation {

std::string modalityName(Modality modality) { return modality == Modality::Ct ? "ct" : "mri"; }

Modality guessModality(const Image& scan) {
  return std::any_of(scan.values.begin(), scan.values.end(), [](float v) { return v <= -500.0f; }) ? Modality::Ct
                                                                                                   : Modality::Mri;
}

LabelMap segmentTissues(const Image& scan, Modality modality, double skinThicknessMm, Progress* progress) {
  if (modality == Modality::Mri) {
    MriTissueOptions options;
    options.skinThicknessMm = skinThicknessMm;
    return segmentMriTissues(scan, options, progress);
  }
  CtTissueOptions options;
  options.skinThicknessMm = skinThicknessMm;
  return segmentCtTissues(scan, options, progress);
}

SkinAndFatLabels skinAndFatLabels(Modality modality) {
  if (modality == Modality::Mri) return {kMriSkin, kMriSubcutaneousFat};
  return {kCtSkin, kCtSubcutaneousFat};
}

Mask segmentBody(const Image& scan, Modality modality) {
  return modality == Modality::Mri ? segmentMriBody(scan) : segmentCtBody(scan, {});
}

}  // namespace vesalius::segmentation
