// Binary-mask operations on label maps, shared by the CT and MRI tissue classifiers.
//
// A Mask is a Grid<std::uint8_t> holding 0 (outside) or 1 (inside) with the geometry of the scan it came
// from. Distances and radii are millimetres measured between voxel centres in world space (spacing
// honoured, so anisotropic voxels are handled); the direction matrix is orthonormal and does not change
// distances. Voxels beyond the grid are treated as unknown, never as background: a mask touching the
// edge of the volume is not eroded or given a boundary there (a scan's field of view cuts the body,
// it does not end it).
#pragma once

#include "vesalius/core/grid.h"
#include "vesalius/core/label_map.h"

#include <cstdint>
#include <limits>

namespace vesalius::segmentation {

using Mask = Grid<std::uint8_t>;

// Voxels of `labels` equal to `id` (1), others 0.
Mask maskOf(const Grid<Label>& labels, Label id);
// Voxels of `labels` that are not 0.
Mask nonZeroMask(const Grid<Label>& labels);
// Voxels with lo <= value <= hi.
Mask thresholdMask(const Grid<float>& image, float lo, float hi);
// Sets the voxels of `labels` inside `mask` to `id`; throws BadInput on a size mismatch.
void paintMask(Grid<Label>& labels, const Mask& mask, Label id);
// A label map holding `entry.id` inside `mask` and 0 elsewhere, with a one-entry table.
LabelMap labelMapOf(const Mask& mask, const LabelEntry& entry);

// Elementwise logic on masks of equal geometry; throws BadInput on a size mismatch.
Mask maskAnd(const Mask& a, const Mask& b);
Mask maskOr(const Mask& a, const Mask& b);
Mask maskAndNot(const Mask& a, const Mask& b);  // a and not b
std::int64_t countVoxels(const Mask& mask);

// Dice overlap 2|A∩B| / (|A|+|B|); 1 when both are empty.
double diceCoefficient(const Mask& a, const Mask& b);

// Which voxels are neighbours: the 6 that share a face, or all 26 that share a face, an edge or a corner.
enum class Connectivity { Face, Full };

// The largest component (ITK ConnectedComponentImageFilter, then RelabelComponentImageFilter). Empty
// input gives an empty mask. Face connectivity keeps what a surface of the mask bounds as one shell:
// parts joined to it only at an edge or a corner would be separate shells of a voxel or two.
Mask largestComponent(const Mask& mask, Connectivity connectivity = Connectivity::Full);
// Drops 26-connected components with fewer than `minVoxels` voxels.
Mask removeSmallComponents(const Mask& mask, std::int64_t minVoxels);

// The 26-connected components of `mask` that contain at least one voxel of `seeds` (geodesic
// reconstruction of the seeds inside the mask).
Mask componentsTouching(const Mask& mask, const Mask& seeds);

// Fills background regions that do not reach the edge of the volume: a flood fill of the background
// from the border, 6-connected (so a 26-connected foreground wall closes a hole).
Mask fillHoles3d(const Mask& mask);
// The same per 2-D slice normal to index axis `axis` (0, 1 or 2), 4-connected background: closes
// cavities that open to the volume edge only through the cut faces (lungs, bowel gas at the last slice).
// Holes with an area above maxHoleAreaMm2 (in the slice, mm^2) stay open: a bone's marrow is filled but
// not the pelvic cavity that the bones of the pelvic ring enclose.
Mask fillHolesSliceWise(const Mask& mask, int axis,
                        double maxHoleAreaMm2 = std::numeric_limits<double>::infinity());
// A body made solid: holes filled in axial slices (so air cut open by the first or last slice, such as
// bowel gas, is filled too), then in 3-D.
Mask fillBodyHoles(const Mask& body);
// The index axis whose world direction is closest to superior-inferior: slices normal to it are axial.
int axialAxis(const GridGeometry& geometry);

// Euclidean distance (mm) from each voxel centre to the nearest voxel centre of `mask` (0 inside it),
// by ITK's SignedMaurerDistanceMapImageFilter (Maurer, Qi, Raghavan, PAMI 25(2) 2003), exact and linear
// time. Where `mask` is empty every value is +infinity.
Grid<float> distanceToMaskMm(const Mask& mask);

// Morphology with a Euclidean ball of radius `radiusMm` (voxel centres within the radius), computed by
// thresholding distance maps rather than by structuring elements, so the ball is round in mm whatever the
// spacing. Dilation: voxels within radiusMm of the mask. Erosion: mask voxels farther than radiusMm from
// any background voxel inside the grid.
Mask dilateMm(const Mask& mask, double radiusMm);
Mask erodeMm(const Mask& mask, double radiusMm);
Mask openMm(const Mask& mask, double radiusMm);   // erode, then dilate: removes parts thinner than 2r
Mask closeMm(const Mask& mask, double radiusMm);  // dilate, then erode: bridges gaps narrower than 2r

}  // namespace vesalius::segmentation
