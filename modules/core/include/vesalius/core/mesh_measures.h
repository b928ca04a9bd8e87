// Measures of triangle surfaces used to check meshes everywhere: edge counts (is it a closed
// 2-manifold?), connected components, triangle areas, enclosed volume, vertex normals, bounding boxes.
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Geometry>

namespace vesalius {

struct EdgeCounts {
  long boundary = 0;     // edges of exactly one triangle (0 for a closed surface)
  long nonManifold = 0;  // edges of three or more triangles
};

// F: #F by 3 triangles.
EdgeCounts countEdges(const MatrixX3i& F);

// Components of triangles connected through shared vertices. V only gives the vertex count (#V).
int triangleComponents(Eigen::Index vertexCount, const MatrixX3i& F);

// The component of each triangle (as triangleComponents counts them): #F, numbered 0, 1, ... in the order
// of their first triangles.
Eigen::VectorXi triangleComponentIds(Eigen::Index vertexCount, const MatrixX3i& F);

// Area of each triangle: #F, units of V squared.
Eigen::VectorXd triangleAreas(const MatrixX3d& V, const MatrixX3i& F);

// Signed volume enclosed by a closed surface, by the divergence theorem: sum over triangles of
// a · (b × c) / 6. Positive for outward (counter-clockwise seen from outside) triangles; cavities count
// negative. Units: those of V cubed.
double enclosedVolume(const MatrixX3d& V, const MatrixX3i& F);

// Area-weighted vertex normals: per vertex, the sum of its triangles' (b − a) × (c − a), of unit length;
// zero for a vertex no triangle uses. #V by 3, pointing out of counter-clockwise triangles.
MatrixX3d vertexNormals(const MatrixX3d& V, const MatrixX3i& F);

// The box of the rows of V (#V by 3); empty when V has no rows.
Eigen::AlignedBox3d boundingBox(const MatrixX3d& V);

}  // namespace vesalius
