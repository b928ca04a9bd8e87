// Re-posing a scan or a label map with its tet mesh (Sujar et al. 2018, §5, Fig. 11: "we determine the pixels inside
// each tetrahedron in the deformed configuration and then, they are mapped back to the non-deformed
// configuration using the inverse of the displacement field ... we iterate over each tetrahedron's bounding
// box and we use the barycentric coordinates to identify the pixels inside the tetrahedron").
//
// Each posed tet is rasterized over the output voxel centres in its bounding box. A centre with barycentric
// coordinates λ in the posed tet (all λ >= 0) is the point Σ λ_a restV_a of the rest tet, the inverse of
// the piecewise affine displacement field, and takes the input's value there: nearest voxel for labels
// (no new labels appear at boundaries), trilinear for intensities. A rest point outside the input grid
// (beyond half a voxel from its edge voxel centres) and a centre covered by no posed tet get the background.
//
// Where posed tets overlap (a fold, or a centre on a shared face) the tet with the lowest index wins, so
// the result does not depend on the thread count: the output is cut into z-slabs, each slab is filled by
// one task, which visits the tets touching it in index order.
//
// Parts that move rigidly (bones with their joints) may be given as a map on the output grid: a voxel of
// part p takes the input's value at restFromPosed[p - 1] · x, x its centre, before any tet is visited.
// The tets around a bone follow it only as well as skinning keeps them rigid (a femur label re-posed
// through the tets of a whole body loses a few per cent of Dice against its rigidly moved mesh).
#pragma once

#include "vesalius/core/grid.h"
#include "vesalius/core/label_map.h"
#include "vesalius/core/mesh.h"

#include <Eigen/Geometry>

#include <optional>
#include <vector>

namespace vesalius::posing {

// The rigidly moving parts of a posed volume (see above).
struct RigidParts {
  Grid<Label> parts;  // on the output grid: 0 where no part is, p for part p
  std::vector<Eigen::Isometry3d> restFromPosed;  // per part p, at p - 1: posed world point -> rest world point;
                                                 // empty: no parts (and `parts` may be empty too)
};

struct PosedVolumeOptions {
  // Grid of the posed volume; the input's geometry if not given (a pose that leaves the input's field of
  // view needs a larger one).
  std::optional<GridGeometry> outputGeometry;
  // Value of voxels no posed tet covers. Default: 0 (unlabelled) for label maps, the scan's minimum for
  // scans (air in CT). For labels it must be a valid Label.
  std::optional<double> background;
  // Parts moved rigidly, on the output grid; null: the tets carry everything.
  const RigidParts* rigid = nullptr;
};

// restV: #V by 3 rest tet mesh vertices (mm, LPS, the scan's space), T: #T by 4 tets, posedV: #V by 3
// posed vertices, scan: the rest-pose volume. Returns the posed scan (trilinear sampling), with the input's
// fileType. Throws BadInput if posedV is not #V by 3, a tet refers to a missing vertex, a geometry is
// invalid, the values do not fill the grid, the background is not finite, or the rigid parts are not on
// the output grid or name a part without a map.
Image poseImage(const MatrixX3d& restV, const MatrixX4i& T, const MatrixX3d& posedV, const Image& scan,
                const PosedVolumeOptions& options = {});

// Same for a label map (nearest-neighbour sampling); the label table is copied. Throws BadInput as above,
// and if the background is not a Label.
LabelMap poseLabels(const MatrixX3d& restV, const MatrixX4i& T, const MatrixX3d& posedV, const LabelMap& labels,
                    const PosedVolumeOptions& options = {});

}  // namespace vesalius::posing
