// Registration of a source skin onto a target skin (Dicko et al. 2013, §4): a dense correspondence that moves every
// source vertex onto the target surface, so the source's topology and uv come along (the later steps
// need source and target skins sharing one uv space).
//
// Method, as §4 describes it: ICP closest-point correspondences (Besl and McKay 1992) each iteration; the
// source skin follows them through shape matching (Müller et al., "Meshless deformations based on shape
// matching", SIGGRAPH 2005: §3.3, linear §4.1, clusters §4.3) as in Gilles et al. 2010; the skin's
// stiffness decreases over the iterations; landmarks give a manual initialisation.
//  1. Alignment: a similarity transform (linalg/similarity_transform.h) of the source, from the landmarks
//     when 3 or more are given, else from the area-weighted centroids, refined by similarity ICP.
//  2. Each iteration: correspondences from every source vertex to its closest point on the target and,
//     when symmetric, from every target vertex to its closest point on the source (spread over that
//     triangle's corners by barycentric weight); pairs whose normals differ by more than maxNormalAngle
//     are dropped. Landmarks add pairs of weight landmarkWeight. Each vertex's wanted position y is the
//     weighted mean of its pairs' targets (its current position when it has none).
//  3. Shape matching: cluster k is the r-ring of vertex k on the rest shape q (the aligned source). Its
//     transform T_k = β A_k + (1 − β) R_k blends the rotation R_k of the polar decomposition of
//     A_pq = Σ (y_i − ȳ)(q_i − q̄)ᵀ with the affine fit A_k (Müller §4.1); the goal g_i is the mean of
//     T_k (q_i − q̄_k) + ȳ_k over the clusters holding i, and x_i ← s g_i + (1 − s) y_i.
//  4. Stiffness: s goes linearly from stiffnessStart to stiffnessEnd and the cluster size r from
//     ringsStart to ringsEnd over the iterations: large stiff clusters first carry the gross
//     differences (height, limb length) across the body, small soft ones then fit the details.
// Deviations, stated plainly: §4 gives no parameters; those below were chosen on MakeHuman bodies
// (docs/methods/skin-registration.md). Clusters are graph rings, not Euclidean balls, so an arm's cluster
// never takes in the torso. Müller's affine fit A_pq A_qq⁻¹ is singular for a surface patch (no spread
// along its normal), so A_k = (A_pq + ε R_k)(A_qq + ε I)⁻¹ with ε = 10⁻² tr(A_qq), which keeps the rotation
// along the normal; and A_k is not scaled to det 1, because skins of different people differ in size.
// The paper's stiffness decrease is realised by the two schedules above; the symmetric pairs and the
// normal test are common ICP refinements the paper does not mention.
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/linalg/similarity_transform.h"

#include <Eigen/Core>

#include <vector>

namespace vesalius::transfer {

struct SkinRegistrationOptions {
  int iterations = 30;
  double stiffnessStart = 0.9;  // s of the first iteration, in [0, 1]: weight of the shape-matching goal
  double stiffnessEnd = 0.0;    // s of the last iteration, <= stiffnessStart; 0 ends on the target
  int ringsStart = 8;           // cluster size (graph rings) of the first iteration
  int ringsEnd = 2;             // ... of the last, 1 <= ringsEnd <= ringsStart
  double beta = 0.5;            // 0: rigid clusters, 1: affine (Müller's β)
  bool symmetric = true;        // also pull the source towards every target vertex
  double maxNormalAngleDeg = 60;  // pairs whose normals differ more are dropped; in (0, 180]
  bool align = true;              // similarity alignment before deforming (step 1)
  int alignIterations = 10;       // similarity-ICP iterations of the alignment
  double landmarkWeight = 20;     // a landmark pair weighs as many closest-point pairs, >= 0
};

// A manual correspondence: source vertex `sourceVertex` belongs at `target` (mm, on or near the target).
struct SkinLandmark {
  int sourceVertex = -1;
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
};

struct SkinRegistration {
  MatrixX3d V;                       // #Vs by 3: source vertex i moved onto the target, mm
  SimilarityTransform alignment;  // step 1's transform of the source (identity when align is off)
  std::vector<double> meanDistance;  // #iterations: mean distance of the vertices to the target before each, mm
  double finalMeanDistance = 0;      // mean and largest distance of V to the target surface, mm
  double finalMaxDistance = 0;
};

// Step 1 alone: the similarity transform that aligns the source to the target (landmarks or centroids,
// then options.alignIterations of similarity ICP). Arguments and errors as registerSkin's.
SimilarityTransform alignSkin(const MatrixX3d& Vs, const MatrixX3i& Fs, const MatrixX3d& Vt, const MatrixX3i& Ft,
                                   const SkinRegistrationOptions& options = {},
                                   const std::vector<SkinLandmark>& landmarks = {});

// Vs: #Vs by 3, Fs: #Fs by 3 (source skin); Vt: #Vt by 3, Ft: #Ft by 3 (target skin); mm, LPS, triangles
// counter-clockwise seen from outside. Throws BadInput on an empty mesh, a non-finite coordinate, a face
// index out of range or a bad landmark; UsageError on impossible options. Deterministic: the result does
// not depend on the number of threads.
SkinRegistration registerSkin(const MatrixX3d& Vs, const MatrixX3i& Fs, const MatrixX3d& Vt,
                              const MatrixX3i& Ft, const SkinRegistrationOptions& options = {},
                              const std::vector<SkinLandmark>& landmarks = {});

}  // namespace vesalius::transfer
