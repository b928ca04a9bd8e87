// Landmarks of two markups files paired by label (`fit --template-landmarks/--scan-landmarks`,
// `transfer --reference-landmarks/--target-landmarks`).
#pragma once

#include "vesalius/core/markers.h"
#include "vesalius/core/mesh.h"

#include <string>
#include <vector>

namespace vesalius::cli {

// The markers of `set` of one kind, in file order.
std::vector<const Marker*> markersOfKind(const MarkerSet& set, MarkerKind kind);

struct LandmarkPairs {
  std::vector<std::string> labels;  // per pair, in the first file's order
  MatrixX3d first, second;          // #pairs by 3: the two files' points
  long skipped = 0;                 // pairs with a point not defined (skipped, preview)
};

// The landmarks of the two files paired by label; a pair with an undefined point is skipped. Throws
// BadInput naming the file for an unreadable file, a label used twice or a label without a partner.
LandmarkPairs pairLandmarks(const std::string& firstPath, const std::string& secondPath);

}  // namespace vesalius::cli
