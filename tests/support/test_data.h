// The shipped test data every test reads (testdata/README.md says where each file comes from), named once.
#pragma once

#include <string>

namespace vesalius::test {

// The example abdomen-pelvis CT (3 mm voxels) and its TotalSegmentator v1 labels.
inline const std::string kCtScan = std::string(VESALIUS_TESTDATA) + "/ct-abdomen-pelvis/example_ct.nii.gz";
inline const std::string kCtLabels =
    std::string(VESALIUS_TESTDATA) + "/ct-abdomen-pelvis/example_seg_total_v1_for_example_ct.nii.gz";
inline const std::string kCtLabelTable = std::string(VESALIUS_TESTDATA) + "/ct-abdomen-pelvis/labels_total_v1.tsv";

}  // namespace vesalius::test
