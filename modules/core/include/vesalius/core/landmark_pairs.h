// Landmarks of two marker sets paired by label: a template's and a scan's (vesalius fit), a reference
// body's and a target's (vesalius transfer). Each set names the file it came from in messages.
#pragma once

#include "vesalius/core/markers.h"
#include "vesalius/core/mesh.h"

#include <string>
#include <vector>

namespace vesalius {

// The markers of `set` of one kind, in set order.
std::vector<const Marker*> markersOfKind(const MarkerSet& set, MarkerKind kind);

struct LandmarkPairs {
  std::vector<std::string> labels;  // per pair, in the first set's order
  MatrixX3d first, second;          // #pairs by 3: the two sets' points
  long skipped = 0;                 // pairs with a point not defined (not placed yet, preview, missing)
};

// The landmarks of the two sets paired by label; a pair with a point that is not defined is skipped.
// Throws BadInput naming the set's source for a label used twice in a set or a label without a partner in
// the other set.
LandmarkPairs pairLandmarks(const MarkerSet& first, const std::string& firstSource, const MarkerSet& second,
                            const std::string& secondSource);

}  // namespace vesalius
