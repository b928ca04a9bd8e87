// The anatomical rules of Dicko et al. 2013 (§3, R1–R7) as numbers, for the transfer report and its tests.
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/grid.h"
#include "vesalius/core/mesh.h"
#include "vesalius/transfer/bones_inside_skin.h"

#include <Eigen/Core>

namespace vesalius::transfer {

// R1, bones straight: the bone's reference vertices (#V by 3) are cut into `slices` slabs across their
// principal axis (the outer 10 % of the length at either end are skipped, as the epiphyses bend the
// centre line of any real bone); the centroids of the same vertices in `V` (the bone moved, same rows)
// are fitted by a line, and the largest distance of a centroid from it is returned as a fraction of the
// moved bone's length along that line. Slabs are chosen on the reference so that an affine map, which
// maps centroids to centroids, changes the value only by the change of scale: a bent bone shows up.
double centreLineDeviation(const MatrixX3d& reference, const MatrixX3d& V, int slices = 20);

// Whether R1's centre line applies to the bone V (#V by 3): a long bone, whose extent along its principal
// axis is at least `minElongation` times its largest extent across it. A short or flat bone (patella,
// talus, carpals, pelvis) has no shaft, and the slabs' centroids of one about as long as it is wide follow
// its outline, not a centre line (the talus reads 26 % of its length, the patella 38 %). Rajagopal's
// femur, tibia, fibula, humerus, radius and ulna measure 5.2–12.3 and metacarpals II–V 3.5–4.5; the
// phalanges 1.5–3.2 and the foot's combined meshes 1.7–2.3.
bool isLongBone(const MatrixX3d& V, double minElongation = 3.0);

// R2, trunk symmetric: the mean distance (mm) from the mesh's vertices mirrored in `plane` to the mesh.
// 0 for a mesh that is its own mirror image.
double mirrorAsymmetry(const MatrixX3d& V, const MatrixX3i& F, const Plane& plane);

// R5, R6: a signed distance grid (mm, negative inside, as meshing::meshSignedDistance makes) sampled
// trilinearly at each row of V (#V by 3); `offGrid` where a row lies off the grid.
Eigen::VectorXd sampleSignedDistance(const Grid<float>& distance, const MatrixX3d& V, double offGrid);

// The same with each row's outward direction: the sampled field's gradient by central differences of half
// the finest spacing, normalized. A row off the grid reads 0 with no direction (neither in nor out), as
// does the gradient where the field is clamped (beyond its band of exact distances).
SkinDistances sampleSkinDistances(const Grid<float>& distance, const MatrixX3d& V);

}  // namespace vesalius::transfer
