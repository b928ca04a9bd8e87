// Internal to the transfer module: the closest-point correspondences of the skin registration
// (skin_registration.h, step 2) and the composition of similarity transforms, shared by its ICP and by
// the articulated stage (articulated_registration.h).
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/linalg/similarity_transform.h"
#include "vesalius/transfer/skin_registration.h"

#include <Eigen/Core>

#include <array>
#include <utility>
#include <vector>

namespace vesalius::transfer::detail {

// Unit face normals (#F by 3; zero for a degenerate face) and area-weighted unit vertex normals (#V by 3).
MatrixX3d faceNormals(const MatrixX3d& V, const MatrixX3i& F);
MatrixX3d vertexNormals(const MatrixX3d& V, const MatrixX3i& F);

// Each vertex's neighbours along the edges of the faces F (sorted, unique).
std::vector<std::vector<int>> skinNeighbours(Eigen::Index vertexCount, const MatrixX3i& F);

// A correspondence: the point Σ b_k x_{v_k} of the source belongs at `target`, with weight `weight`.
struct Pair {
  std::array<int, 3> vertices{};
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  double weight = 0;
};

// The target skin with what the correspondences need of it. A partial target (a scan's skin cut by its
// field of view) marks the cut: faces touching a cut vertex and the cut vertices pull nothing, and a
// forward pair counts only where the source point is about as near the target point as the source
// surface is (reciprocal within reciprocalToleranceMm), so that a limb beside the trunk is not pulled
// onto the trunk's skin.
struct Target {
  const MatrixX3d& V;
  TriangleTree tree;
  MatrixX3d faceNormals, vertexNormals;
  std::vector<char> cutFace, cutVertex;  // empty for a whole target
  double reciprocalToleranceMm = 0;
  bool partial() const { return !cutVertex.empty(); }
};
Target makeTarget(const MatrixX3d& Vt, const MatrixX3i& Ft);
// cut: ascending or not, indices into Vt of the vertices that are not skin.
Target makePartialTarget(const MatrixX3d& Vt, const MatrixX3i& Ft, const std::vector<int>& cut,
                         double reciprocalToleranceMm);

// The pairs of the source X (faces Fs) with the target: forward (every source vertex to its closest point
// `forward` on the target), backward when options.symmetric (every target vertex to its closest point on
// the source), pairs whose normals differ by more than options.maxNormalAngleDeg dropped, and for a
// partial target those Target describes; then landmarks.
std::vector<Pair> correspondences(const MatrixX3d& X, const MatrixX3i& Fs, const std::vector<ClosestPoint>& forward,
                                  const Target& target, const std::vector<SkinLandmark>& landmarks,
                                  const SkinRegistrationOptions& options);

// Steps 2-4 of registerSkin from the rest shape Q (the aligned source, #Vs by 3): the deformed source, the
// mean distances before each iteration, and in `reached` (#Vs) whether a pair reached each vertex in the
// last iteration.
MatrixX3d deformOntoTarget(const MatrixX3d& Q, const MatrixX3i& Fs, const Target& target,
                           const std::vector<SkinLandmark>& landmarks, const SkinRegistrationOptions& options,
                           std::vector<double>& meanDistance, std::vector<char>& reached);

// Throws UsageError on impossible options (registerSkin's checks).
void checkOptions(const SkinRegistrationOptions& options);

// Mean and largest distance of the points to their closest points.
std::pair<double, double> distances(const std::vector<ClosestPoint>& closest);

// The source point of a pair, Σ b_k x_{v_k}.
Eigen::Vector3d sourcePoint(const MatrixX3d& X, const Pair& p);

// The transform x -> second(first(x)).
SimilarityTransform compose(const SimilarityTransform& second, const SimilarityTransform& first);

}  // namespace vesalius::transfer::detail
