// Initial placement of a template (Wang et al.'s Fig. 1 starts from a rigidly aligned template): a similarity
// transform from template space to the scan. With three or more landmark pairs, the least-squares
// similarity of the pairs (Umeyama 1991). Otherwise a similarity ICP of the template surface to the ICP
// markers, started from each of the four proper principal-axis alignments of the surface and the marker
// cloud (axis signs are ambiguous: a template in its own frame, e.g. the Visible Human cadaver frame, may
// face any way), keeping the one with the smallest RMS marker distance.
#pragma once

#include "vesalius/linalg/similarity_transform.h"

#include "vesalius/core/mesh.h"

#include <Eigen/Core>

namespace vesalius::fit {

struct Placement {
  SimilarityTransform transform;
  double rmsError = 0;  // mm: landmark pairs, or marker-to-surface distances
  int iterations = 0;   // ICP iterations of the kept start (0 for landmarks)
};

// surface: the template's boundary in template space. templateLandmarks/scanLandmarks: #L by 3 pairs;
// icp: #I by 3 scan points. Throws BadInput if neither 3 landmark pairs nor 3 ICP markers are given.
Placement placeTemplate(const TriMesh& surface, const MatrixX3d& templateLandmarks, const MatrixX3d& scanLandmarks,
                        const MatrixX3d& icp);

}  // namespace vesalius::fit
