// Seed points for TetGen's regions: one point strictly inside each closed part of each surface and outside
// every surface nested in that part, and one in each cavity another surface holds (see tetrahedralize.h).
#pragma once

#include "vesalius/core/mesh.h"

#include <vector>

namespace vesalius::meshing {

struct RegionSeed {
  Eigen::Vector3d point;
  int region = 0;          // index of the surface whose region the point lies in
  double clearance = 0.0;  // distance to the nearest triangle of any surface, mm
};

// `all` holds every surface's triangles (closed, outward, not intersecting, parts not sharing vertices); `owner`
// (#F) the surface index of each triangle. One seed per connected part facing outward; throws
// NumericalFailure if such a part has no room for one (a flat part). A part facing inward (the inner shell
// of a hollow, whose material its outer shell's seed names) gets instead a seed inside its cavity, for the
// smallest other surface holding that point, if there is one.
std::vector<RegionSeed> regionSeeds(const TriMesh& all, const std::vector<int>& owner);

// A partition into labelled regions (shared_label_surfaces.h): `all` holds each triangle once, `sides`
// (#F by 2) the labels its normal points out of and into. One seed per connected part of each label's
// triangles, with region = the label's index in `labels`; throws NumericalFailure as above.
std::vector<RegionSeed> partitionSeeds(const TriMesh& all, const Eigen::MatrixX2i& sides, const std::vector<int>& labels);

}  // namespace vesalius::meshing
