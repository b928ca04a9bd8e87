// Fat thickness carried from the skin voxels of a FatForest to the vertices of a skin surface mesh
// (Dicko et al. 2013, §5: thickness is kept per skin point before it is rasterized into the skin's texture).
//
// Each vertex takes the largest thickness of the skin voxels whose centres lie within `radiusMm` of it
// (default: one voxel diagonal). The maximum, not the mean or the nearest voxel: a skin layer more than
// one voxel thick roots the trees at its inner voxels, next to the fat, while the outer voxels that lie
// closest to the surface keep thickness 0 (fat_forest.h); the mean would dilute the value by the skin's
// thickness in voxels. On a layer one voxel thick under a flat skin all candidates agree.
//
// NaN-free: vertices with no skin voxel within the radius (the mesh runs past the mask, e.g. where the
// field of view cuts the body) are filled from their mesh neighbours, frontier by frontier, each taking
// the mean of its already known neighbours, then smoothed by Jacobi iterations of neighbour averaging
// with the measured vertices held fixed. Vertices in mesh components with no measured vertex get 0.
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/fat/fat_forest.h"

#include <Eigen/Core>

namespace vesalius::fat {

struct VertexThicknessOptions {
  double radiusMm = 0;          // search radius; 0: one voxel diagonal |direction · spacing|
  int smoothingIterations = 5;  // Jacobi iterations over the filled (unmeasured) vertices
};

struct VertexThickness {
  Eigen::VectorXd thickness;  // #V, mm, finite
  Eigen::Index measured = 0;  // vertices with a skin voxel within the radius
  Eigen::Index filled = 0;    // vertices given values from their mesh neighbours
  Eigen::Index unreached = 0; // vertices in components with nothing measured (set to 0)
  enum Source : int { kUnreached = 0, kMeasured = 1, kFilled = 2 };
  Eigen::VectorXi source;     // #V: where each vertex's value came from
};

// V: #V by 3 vertex positions (LPS mm, the forest's world space); F: #F by 3 triangles (used for the
// neighbours of unmeasured vertices). Throws UsageError for a negative radius or iteration count.
// Parallel over vertices (TBB); the result does not depend on the number of threads.
VertexThickness thicknessAtVertices(const FatForest& forest, const MatrixX3d& V, const MatrixX3i& F,
                                    const VertexThicknessOptions& options = {});

}  // namespace vesalius::fat
