#include "vesalius/core/landmark_pairs.h"

#include "vesalius/core/error.h"

#include <map>

namespace vesalius {

namespace {

std::map<std::string, const Marker*> landmarksByLabel(const MarkerSet& set, const std::string& source) {
  std::map<std::string, const Marker*> byLabel;
  for (const Marker* m : markersOfKind(set, MarkerKind::Landmark))
    if (!byLabel.emplace(m->label, m).second)
      throw BadInput(source, "landmark label '" + m->label + "' is used twice, so it cannot be paired");
  return byLabel;
}

void append(MatrixX3d& M, const Eigen::Vector3d& p) {
  M.conservativeResize(M.rows() + 1, 3);
  M.row(M.rows() - 1) = p.transpose();
}

}  // namespace

std::vector<const Marker*> markersOfKind(const MarkerSet& set, MarkerKind kind) {
  std::vector<const Marker*> found;
  for (const Marker& m : set.markers)
    if (m.kind == kind) found.push_back(&m);
  return found;
}

LandmarkPairs pairLandmarks(const MarkerSet& first, const std::string& firstSource, const MarkerSet& second,
                            const std::string& secondSource) {
  const auto firstByLabel = landmarksByLabel(first, firstSource);
  const auto secondByLabel = landmarksByLabel(second, secondSource);
  for (const auto& [label, marker] : secondByLabel)
    if (!firstByLabel.count(label))
      throw BadInput(secondSource, "landmark '" + label + "' has no partner in " + firstSource);
  LandmarkPairs pairs;
  pairs.first.resize(0, 3);
  pairs.second.resize(0, 3);
  for (const Marker* a : markersOfKind(first, MarkerKind::Landmark)) {
    const auto partner = secondByLabel.find(a->label);
    if (partner == secondByLabel.end())
      throw BadInput(firstSource, "landmark '" + a->label + "' has no partner in " + secondSource);
    const Marker* b = partner->second;
    if (a->status != MarkerStatus::Defined || b->status != MarkerStatus::Defined) {
      ++pairs.skipped;
      continue;
    }
    append(pairs.first, a->position);
    append(pairs.second, b->position);
    pairs.labels.push_back(a->label);
  }
  return pairs;
}

}  // namespace vesalius
