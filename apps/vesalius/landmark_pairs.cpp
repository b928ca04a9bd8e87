// Landmarks of two markups files paired by label (landmark_pairs.h).
#include "landmark_pairs.h"

#include "vesalius/io/marker_io.h"

namespace vesalius::cli {

LandmarkPairs pairLandmarks(const std::string& firstPath, const std::string& secondPath) {
  const MarkerSet first = io::readMarkers(firstPath), second = io::readMarkers(secondPath);
  return vesalius::pairLandmarks(first, firstPath, second, secondPath);
}

}  // namespace vesalius::cli
