// The signed distance grid of rules R5 and R6 (body_distance.h).
#include "vesalius/meshing/body_distance.h"

#include "vesalius/meshing/mesh_volume.h"
#include "vesalius/meshing/sealed_cavities.h"

#include <cmath>

namespace vesalius::meshing {

BodyDistance bodySignedDistance(const TriMesh& body) {
  static_assert(kCavityOpeningMm <= 2 * kDistanceBandMm, "the closing reads distances up to half the opening");
  meshing::CoveringGridOptions grid;
  grid.voxelSizeMm = 2.0;
  grid.maxSize = Eigen::Vector3i(400, 400, 1000);
  meshing::SignedDistanceOptions band;
  band.bandMm = kDistanceBandMm;
  BodyDistance d{meshing::meshSignedDistance(body, meshing::coveringGrid({&body}, grid), band), {}};
  d.cavities = meshing::sealedCavities(d.signedDistance, kCavityOpeningMm);
  std::int64_t voxels = 0;
  for (std::size_t v = 0; v < d.cavities.values.size(); ++v) {
    if (!d.cavities.values[v]) continue;
    // Inside by the distance to the pocket's wall, so the field stays continuous across the wall.
    d.signedDistance.values[v] = -std::abs(d.signedDistance.values[v]);
    ++voxels;
  }
  d.cavitiesMl = double(voxels) * d.signedDistance.geometry.spacing.prod() / 1000.0;
  return d;
}

long verticesInCavities(const BodyDistance& body, const MatrixX3d& V) {
  const GridGeometry& g = body.cavities.geometry;
  long count = 0;
  for (Eigen::Index r = 0; r < V.rows(); ++r) {
    const Eigen::Vector3i v = g.worldToIndex(V.row(r).transpose()).array().round().cast<int>();
    count += g.contains(v.x(), v.y(), v.z()) && body.cavities.at(v.x(), v.y(), v.z());
  }
  return count;
}

}  // namespace vesalius::meshing
