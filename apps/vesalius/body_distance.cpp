// The signed distance grid of rules R5 and R6 (body_distance.h).
#include "body_distance.h"

#include "vesalius/meshing/mesh_volume.h"

namespace vesalius::cli {

Grid<float> bodySignedDistance(const TriMesh& body) {
  meshing::CoveringGridOptions grid;
  grid.voxelSizeMm = 2.0;
  grid.maxSize = Eigen::Vector3i(400, 400, 1000);
  meshing::SignedDistanceOptions band;
  band.bandMm = kDistanceBandMm;
  return meshing::meshSignedDistance(body, meshing::coveringGrid({&body}, grid), band);
}

}  // namespace vesalius::cli
