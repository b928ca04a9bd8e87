// Bone registration (Dicko et al. 2013, §8): each bone moves by one affine map attracted to where the skin's
// interpolated displacement puts it, so bones stay straight (rule R1) while they scale to the body;
// trunk bones move by maps symmetric about the sagittal plane (rule R2).
//
// Dicko et al. 2013 attaches "all the voxels of the reference bone to a common affine frame" and attracts them to
// their interpolated positions by linear springs, integrated with an implicit solver. The springs' rest
// state is the least-squares affine map
//   min over (A, t) of  Σ_i |A p_i + t − q_i|²        (p_i on the reference bone, q_i its attractor),
// which we solve in closed form instead of integrating towards it (same result, no time step). We use the
// bone mesh's vertices as the p_i rather than its voxels.
// Springs of different stiffness w_i make it Σ_i w_i |A p_i + t − q_i|² (the weighted fits below; the
// transfer stiffens those of vertices its map would put outside the target's skin, anatomy_transfer.h).
//
// "Transformations centered in the sagittal plane": a map T is symmetric about the plane when it commutes
// with the mirror, S' T = T S, S the reference plane's mirror and S' the target's. In frames whose first
// axis is the plane's normal and whose origin lies on the plane, T is x' = a x, (y', z') = B (y, z) + b:
// the normal axis only scales, the in-plane part is a 2-D affine map. A symmetric bone stays symmetric.
// The target's sagittal plane is the image of the reference's under the one affine map that best fits all
// symmetric bones together (targetSagittalPlane), so that every trunk bone shares one plane.
//
// Long bones (a group of them only, as the forearm's radius or the shank's tibia and fibula) move by a
// rotation, one scale along the bone's axis and one across it, the latter no larger than the former: §8,
// "changes of character size mainly scale up or down the bones, while the changes of soft tissue do not
// modify the bones". The interpolated field of a limb with more muscle widens the bone across its axis and
// not along it; an affine map takes that in (the muscular body's forearms tripled their volume and their
// centre lines bent from 4 to 6 % of their length: the map scales a slightly bowed shaft's bow by its
// scale across, the length by its scale along). Capped at the scale along, a bone is at most as stout
// as the reference's and its centre line no more bent. Below the cap the scale across stays free: a thin
// limb leaves no room at the subcutaneous epicondyles and styloids for a bone as stout as the reference's
// (a similarity there shortened the thin body's humerus by 12 % to keep it inside, rule R6).
//
// Flat or thin bones leave some directions of A undetermined; a ridge term λ |A − s I|² with
// λ = 1e-6 · trace of the points' covariance and s the ratio of the two point clouds' RMS radii picks the
// uniform scale there and changes a well-determined fit by less than 1e-6 relative.
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/mesh.h"

#include <Eigen/Core>

namespace vesalius::transfer {

struct AffineMap {
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  MatrixX3d apply(const MatrixX3d& P) const;  // #P by 3 → #P by 3: A p + t per row
  Eigen::Vector3d apply(const Eigen::Vector3d& p) const { return A * p + t; }
};

// P, Q: #P by 3 (#P >= 4, P not all on one point). Throws BadInput on mismatched rows, fewer than 4
// points or non-finite values.
AffineMap fitAffineMap(const MatrixX3d& P, const MatrixX3d& Q);
// The same with a weight per point (#P, positive): min Σ_i w_i |A p_i + t − q_i|² (the springs of
// different stiffness). Throws BadInput also on a weight that is not positive and finite.
AffineMap fitAffineMap(const MatrixX3d& P, const MatrixX3d& Q, const Eigen::VectorXd& weights);

// A long bone's map (see above): A = R (s_along a aᵀ + s_across (I − a aᵀ)), a the (weighted) principal
// axis of P, R a rotation, s_across ≤ s_along; the least-squares fit in that class, unweighted and
// weighted (a local minimum, reached by alternating from the least-squares similarity). Same inputs and
// errors as fitAffineMap.
AffineMap fitLongBoneMap(const MatrixX3d& P, const MatrixX3d& Q);
AffineMap fitLongBoneMap(const MatrixX3d& P, const MatrixX3d& Q, const Eigen::VectorXd& weights);

// The least-squares affine map that is symmetric from `reference` to `target` (see above), unweighted
// and weighted.
AffineMap fitSymmetricAffineMap(const MatrixX3d& P, const MatrixX3d& Q, const Plane& reference,
                                const Plane& target);
AffineMap fitSymmetricAffineMap(const MatrixX3d& P, const MatrixX3d& Q, const Eigen::VectorXd& weights,
                                const Plane& reference, const Plane& target);

// The plane `reference` is carried to by map: point A p + t, normal A^{-T} n normalized.
Plane mapPlane(const AffineMap& map, const Plane& reference);

}  // namespace vesalius::transfer
