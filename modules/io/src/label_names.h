// How a label map that names its own labels (a DICOM SEG, a 3D Slicer segmentation, an RT Structure Set)
// takes an explicit table, in one place so that every such reader applies the same rule (image_io.cpp,
// dicom_rtstruct.cpp). Private to io.
#pragma once

#include "vesalius/core/label_map.h"

#include <string>
#include <vector>

namespace vesalius::io {

// Names every label present in `labels` that `table` does not list: "label_<id>" with defaultLabelColor(id).
void nameUnlistedLabels(const std::vector<Label>& labels, LabelTable& table);

// The table at `tablePath`, if given, replaces `map`'s own names and colours whole (a label it leaves out
// loses its own name: one table names the labels, not a mix of two); then nameUnlistedLabels.
void applyExplicitTable(LabelMap& map, const std::string& tablePath);

}  // namespace vesalius::io
