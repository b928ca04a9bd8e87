// The modality of a scan from its values (segmentation/scan_modality.h): the shipped CTs hold air at about
// −1000 HU, the shipped MRIs (a head, an abdomen of other subjects) no value near it.
#include "vesalius/segmentation/scan_modality.h"

#include "vesalius/io/image_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <string>

namespace vesalius::segmentation {
namespace {

const std::string kData = std::string(VESALIUS_TESTDATA) + "/";

TEST(ScanModality, TheShippedScansAreTakenForWhatTheyAre) {
  const std::pair<const char*, Modality> scans[] = {
      {"ct-abdomen-pelvis/example_ct.nii.gz", Modality::Ct},
      {"ct-abdomen-pelvis/example_ct_sm.nii.gz", Modality::Ct},
      {"dicom/ct-series-jpeg2000", Modality::Ct},
      {"mr-abdomen/example_mr_sm.nii.gz", Modality::Mri},
      {"head-mri/ch2.nii.gz", Modality::Mri},
  };
  for (const auto& [path, modality] : scans) {
    const Image scan = io::readScan(kData + path);
    const auto [low, high] = std::minmax_element(scan.values.begin(), scan.values.end());
    std::cout << path << ": values " << *low << " .. " << *high << ", " << modalityName(guessModality(scan)) << '\n';
    EXPECT_EQ(guessModality(scan), modality) << path;
  }
}

TEST(ScanModality, AStandardizedMriAndAScannersPaddingAreToldApart) {
  Image scan;
  scan.geometry.size = {4, 4, 4};
  scan.values.assign(64, 0.0f);
  for (std::size_t i = 0; i < scan.values.size(); ++i) scan.values[i] = float(i % 7) - 3.0f;  // z-scores
  EXPECT_EQ(guessModality(scan), Modality::Mri);
  scan.values[5] = -1024.0f;  // one voxel of a CT's padding
  EXPECT_EQ(guessModality(scan), Modality::Ct);
}

}  // namespace
}  // namespace vesalius::segmentation
