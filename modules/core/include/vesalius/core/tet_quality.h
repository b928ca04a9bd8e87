// Quality of a tetrahedral mesh: the measures TetGen bounds and FEM accuracy depends on.
//
// Per tet: the six interior dihedral angles (the angle between the two faces at an edge; a regular tet has
// acos(1/3) = 70.53° everywhere, slivers have some near 0° and some near 180°), the radius-edge ratio
// (circumradius over shortest edge: sqrt(6)/4 = 0.612 for a regular tet, the bound TetGen's -q enforces;
// Shewchuk, "What is a good linear finite element?", 2002, §6) and the signed volume.
#pragma once

#include "vesalius/core/mesh.h"

#include <array>

namespace vesalius {

struct TetQuality {
  Eigen::VectorXd volume;       // #T signed volumes, units of V cubed (positive for mesh.h's orientation)
  Eigen::VectorXd minDihedral;  // #T smallest dihedral angle, degrees
  Eigen::VectorXd maxDihedral;  // #T largest dihedral angle, degrees
  Eigen::VectorXd radiusEdge;   // #T circumradius / shortest edge (infinite for a flat tet)
  Eigen::Matrix<double, Eigen::Dynamic, 6> dihedral;  // #T by 6 angles at edges 01 02 03 12 13 23, degrees
};

// V: #V by 3, T: #T by 4 (indices must be valid rows of V).
TetQuality tetQuality(const MatrixX3d& V, const MatrixX4i& T);

struct TetQualityReport {
  long tets = 0;
  double minDihedral = 0, maxDihedral = 0;  // degrees, over all tets
  std::array<long, 18> dihedralHistogram{};  // every dihedral angle (6 per tet) in 10° bins: [0,10), ... [170,180]
  double maxRadiusEdge = 0, meanRadiusEdge = 0;
  double minVolume = 0, maxVolume = 0, totalVolume = 0;  // signed
  long inverted = 0;    // negative volume beyond round-off
  long degenerate = 0;  // |volume| below 1e-12 times the cube of the tet's longest edge (flat)
};

// Summary of tetQuality over the mesh (zeros for no tets).
TetQualityReport tetQualityReport(const MatrixX3d& V, const MatrixX4i& T);

}  // namespace vesalius
