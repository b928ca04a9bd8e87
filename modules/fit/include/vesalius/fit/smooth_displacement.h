// A smooth displacement of a surface's vertices that carries points on the surface to targets: the
// re-placement step of an active shape model's search (Cootes, Taylor, Cooper and Graham, "Active shape
// models — their training and application", CVIU 61(1), 1995, §4: after each profile search the model is
// moved onto the found edges, then searched again). `vesalius markers suggest` uses it to bend a roughly
// placed template onto the scan's edges (issue 5).
//
// Method: the vertex displacements U (#V by 3) minimise
//   Σ_p w_p ||Σ_j b_pj U_j − d_p||²  +  λ Σ_{edges ij} ||U_i − U_j||²,
// with b_p the barycentric weights of point p's closest surface point and d_p its wanted displacement:
// a least-squares fit regularised by the membrane energy of the uniform graph Laplacian L (the stiffness
// term of Amberg, Romdhani and Vetter, "Optimal step nonrigid ICP", CVPR 2007, for translations only).
// Normal equations (Bᵀ W B + λ L) U = Bᵀ W D, one sparse Cholesky factorisation for the three columns.
// Deviation from Cootes et al.: no trained shape model (there is one template, no training set); the
// Laplacian stands in for the shape prior. λ = smoothness · Σ w_p / #V, so the balance of the two terms
// does not depend on how many points there are; larger smoothness spreads each point's pull over more
// edges. A vertex no point reaches (unreferenced, or its component has no weighted point) stays put: a
// 1e-9 λ diagonal keeps the system definite.
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Core>

namespace vesalius::fit {

struct SmoothDisplacementOptions {
  double smoothness = 1.0;  // λ relative to the mean point weight per vertex (see above)
};

// surface: V #V by 3, F #F by 3, mm. points: #P by 3 on or near the surface; displacements: #P by 3, mm;
// weights: #P, non-negative (0: the point does not pull). Returns U, #V by 3 (zero when every weight is
// 0). Throws UsageError on mismatched shapes, a negative or non-finite weight, non-finite points or
// displacements, or an empty surface.
MatrixX3d smoothDisplacement(const TriMesh& surface, const MatrixX3d& points, const MatrixX3d& displacements,
                             const Eigen::VectorXd& weights, const SmoothDisplacementOptions& options = {});

}  // namespace vesalius::fit
