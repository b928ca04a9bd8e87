// The shipped 3-slice CT series (testdata/dicom/ct-3slice-dcmqi, dcmqi's test data) and the two-class label
// map that the DICOM SEG and RT Structure Set tests write over it.
#pragma once

#include "vesalius/core/grid.h"
#include "vesalius/core/label_map.h"

#include <string>

namespace vesalius::test {

inline const std::string kCt3SliceFolder = std::string(VESALIUS_TESTDATA) + "/dicom/ct-3slice-dcmqi/ct-3slice";

// Soft tissue (1, above -200 HU) and bone (2, above 200 HU) of `scan`, named and coloured; air is 0.
inline LabelMap softTissueAndBone(const Image& scan) {
  LabelMap map;
  map.labels = Grid<Label>(scan.geometry, 0);
  for (std::size_t n = 0; n < scan.values.size(); ++n)
    map.labels.values[n] = scan.values[n] > 200 ? 2 : scan.values[n] > -200 ? 1 : 0;
  map.table.add({1, "soft_tissue", {{200, 100, 90}}});
  map.table.add({2, "bone", {{240, 240, 220}}});
  return map;
}

}  // namespace vesalius::test
