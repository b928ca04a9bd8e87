// The scan's edge along each normal of a roughly placed surface: where `vesalius markers suggest` proposes
// ICP markers (issue 5) for a radiologist to accept, in the spirit of active shape models' profile search
// (Cootes, Taylor, Cooper and Graham, "Active shape models — their training and application", CVIU 61(1),
// 1995, §4: each model point moves along its normal to the strongest edge nearby).
//
// Method: the scan (cropped around the points) is blurred by a Gaussian of `sigmaMm` (ITK's recursive
// Gaussian); for each point p with unit normal n the profile e(s) = ±∂I/∂n at p + s n, s in
// [-searchMm, searchMm] every stepMm, is the central difference of the blurred scan (trilinear) over
// ±stepMm/2 — a derivative-of-Gaussian along n. The signed derivative along the normal, rather than the
// gradient magnitude, lets an edge of the wrong polarity (a bright vessel just outside a dark organ) and
// an edge parallel to the search line be ignored. The point moves to the largest interior local maximum
// of e; a maximum at either end of the window is an edge beyond the search, not found.
// Polarity: Falling keeps intensity dropping from inside to outside (e = −∂I/∂n), Rising the reverse,
// Either |∂I/∂n|; Auto picks Falling or Rising by which gives the larger peak at more of the points, so
// the polarity is the same over the surface.
// Tissue check: where the template is off the organ, the strongest edge is often between two other
// tissues (fat and muscle). The organ's intensity is learned from the scan itself: the median and MAD of
// the blurred scan searchMm + sideMm inside every point (most of a roughly placed template's inside is
// the organ), at least 1 % of the profiles' value range wide either way. Then each profile keeps its
// strongest edge whose inner side lies within the organ's band and whose outer side lies contrastMads
// robust deviations beyond the inner side in the edge's polarity (darker for Falling), as an active shape
// model's grey-level profile model would (Cootes et al. 1995 §5), without a training set. The step is
// measured from the inner side rather than asking the outer side to leave the band: tissue just below the
// organ's band (muscle against liver on CT) can then be the outer side of the organ's edge, and a small
// step out of the band's lower end (from muscle to something slightly darker) is not an edge of the
// organ. Changes within round-off of the blur (1e-5 of the value per step) are not edges.
// Plateaus: the edge must be one step between two plateaus, as a profile model's mean profile across an
// organ's boundary is (Cootes et al. 1995 §5). For a falling edge, no value over plateauMm behind the
// inner side may be more than plateauMads deviations darker than the inner side, and none over plateauMm
// beyond the outer side more than plateauMads darker than the outer side (brighter, for a rising edge).
// Darker tissue behind the inner side makes the inner side a brighter layer on the organ (diaphragm,
// costal cartilage and ribs on the liver) and the edge that layer's against fat; a profile that keeps
// falling beyond the outer side (muscle to fat to air at the body wall, a bowel wall over fat and gas)
// makes the edge one step of a ramp across several tissues, not the organ's against its neighbour.
// Confidence = contrast · closeness, in [0, 1]: contrast = (peak − median) / (peak + median) with the
// median of |∂I/∂n| over the profile (0 for a flat or noisy profile, 1 for one isolated edge), closeness
// = 1 − |s| / (2 searchMm) (an edge far from the template is less likely the organ's).
#pragma once

#include "vesalius/core/grid.h"
#include "vesalius/core/mesh.h"

#include <Eigen/Core>

#include <vector>

namespace vesalius::segmentation {

enum class EdgePolarity { Auto, Falling, Rising, Either };

struct NormalEdgeOptions {
  double sigmaMm = 2.0;    // Gaussian blur before differentiating; best of 1-3 mm on a 3 mm CT (see docs)
  double searchMm = 8.0;   // half-length of the search along each normal
  double stepMm = 0.25;    // profile sample spacing; a fraction of a voxel, the peak is not interpolated
  EdgePolarity polarity = EdgePolarity::Auto;
  // Keep only edges with the organ's tissue on the inner side and another on the outer side, sideMm away
  // (see above); the organ's intensity band is median ± bandMads robust deviations of the inner sides.
  bool checkTissue = true;
  double sideMm = 3.0;
  double bandMads = 2.0;      // narrower than 3: muscle and spleen are close to liver on CT
  double contrastMads = 2.0;  // the outer side this many robust deviations beyond the inner (see above);
                              // 2 measured best on the test CT (docs/methods/marker-suggestions.md)
  double plateauMm = 9.0;     // the plateaus' reach beyond each side (0: no plateau check); three voxels
  double plateauMads = 0.5;   // of the test CT; the tolerance in robust deviations (see above and docs)
};

struct NormalEdge {
  bool found = false;                                  // false: no interior peak, or the profile leaves the scan
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // LPS mm; the input point when not found
  double offsetMm = 0;                                 // s of the edge along the normal
  double strength = 0;                                 // |∂I/∂n| at the edge, scan units per mm (HU/mm for CT)
  double confidence = 0;                               // in [0, 1]; 0 when not found
};

struct NormalEdges {
  std::vector<NormalEdge> edges;                 // one per point, in order
  EdgePolarity polarity = EdgePolarity::Either;  // the polarity used (Auto resolved)
};

// points, normals: #P by 3, LPS mm; normals point from inside to outside (need not be unit). Throws
// UsageError on mismatched shapes, a zero normal or options that are not positive and finite.
NormalEdges findNormalEdges(const Image& scan, const MatrixX3d& points, const MatrixX3d& normals,
                            const NormalEdgeOptions& options = {});

}  // namespace vesalius::segmentation
