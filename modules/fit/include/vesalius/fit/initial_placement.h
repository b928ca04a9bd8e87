// Initial placement of a template (Wang et al.'s Fig. 1 starts from a rigidly aligned template): a similarity
// transform from template space to the scan. With three or more landmark pairs, the least-squares
// similarity of the pairs (Umeyama 1991). Otherwise a similarity ICP of the template surface to the ICP
// markers, started from each of the four proper principal-axis alignments of the surface and the marker
// cloud (axis signs are ambiguous: a template in its own frame, e.g. the Visible Human cadaver frame, may
// face any way), keeping the one with the smallest RMS marker distance.
//
// Where the scan's field of view cuts the organ (ours): the markers cover only the part the scan shows,
// and pulling them to the template alone matches the whole template to that part, shrunk (a kidney cut
// through its middle placed at 0.9 of its size per axis). With a PlacementView the ICP is two-sided inside
// the scan: the template's vertices that fall inside the scan's grid are pulled to the organ's surface
// there too, each side weighing half. The template can then reach beyond the cut but not bulge into the
// scan where the organ is not. Its starts are the four above, the markers-alone placement, and the
// template as it is turned (library templates are in mm LPS, as the organ lies) at that placement's
// scale and 1.3 times it: the principal axes of a cut kidney's visible top lie across the kidney.
#pragma once

#include "vesalius/linalg/similarity_transform.h"

#include "vesalius/core/grid.h"
#include "vesalius/core/mesh.h"

#include <Eigen/Core>

namespace vesalius::fit {

struct Placement {
  SimilarityTransform transform;
  double rmsError = 0;  // mm: landmark pairs, or marker-to-surface distances
  int iterations = 0;   // ICP iterations of the kept start (0 for landmarks)
};

// The scan that cuts the organ: its grid (inside: within half a voxel of its voxel centres' box) and the
// organ's surface inside it (the label's boundary without the faces on the grid's edge), on which the ICP
// markers lie.
struct PlacementView {
  GridGeometry grid;
  TriMesh surface;
};

// surface: the template's boundary in template space. templateLandmarks/scanLandmarks: #L by 3 pairs;
// icp: #I by 3 scan points; view: where the scan cuts the organ, for the two-sided ICP (landmark pairs
// ignore it). Throws BadInput if neither 3 landmark pairs nor 3 ICP markers are given.
Placement placeTemplate(const TriMesh& surface, const MatrixX3d& templateLandmarks, const MatrixX3d& scanLandmarks,
                        const MatrixX3d& icp, const PlacementView* view = nullptr);

}  // namespace vesalius::fit
