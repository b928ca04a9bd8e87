// Landmarks of two markups files paired by label (`fit --template-landmarks/--scan-landmarks`,
// `transfer --reference-landmarks/--target-landmarks`): core/landmark_pairs.h on the files' marker sets.
#pragma once

#include "vesalius/core/landmark_pairs.h"

#include <string>

namespace vesalius::cli {

// Reads both files and pairs their landmarks. Throws BadInput naming the file for an unreadable file, a
// label used twice or a label without a partner.
LandmarkPairs pairLandmarks(const std::string& firstPath, const std::string& secondPath);

}  // namespace vesalius::cli
