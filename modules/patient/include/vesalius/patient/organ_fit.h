// An organ template fitted to a patient's organ label (Wang et al. 2021): ICP markers spread over the label's
// boundary inside the scan, as a radiologist would pick them, the template tetrahedralized within its tet
// budget (meshing/tet_budget.h), placed by a similarity ICP to the markers (fit/initial_placement.h),
// fitted by plastic strains (fit/plastic_fit.h), then fitted again from the shape reached while a marker
// is far (fit/refit.h, ours), each refit's mesh within the same budget. The template's own surface is
// carried through every round (fit::carriedSurface).
#pragma once

#include "vesalius/core/label_map.h"
#include "vesalius/core/mesh.h"
#include "vesalius/core/progress.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace vesalius::patient {

struct OrganFitOptions {
  int markers = 300;      // ICP markers spread over the label's boundary
  int seed = 1;           // of their spreading
  long targetTets = 5000; // tets of the template and of each refit (within 2x)
  int refits = 3;         // refits after the first fit (0: Wang et al.'s fit alone)
};

struct OrganFit {
  TriMesh surface;           // the fitted boundary (after refits the last round's), mm LPS, closed
  TriMesh carriedTemplate;   // the template's own triangles carried through every round
  // The last round's fitted tet mesh (V #V by 3 fitted positions, mm LPS; T #T by 4, positively oriented):
  // `surface` is its boundary. Organs that touch are separated on it (organ_separation.h).
  TetMesh tets;
  MatrixX3d markers;         // #M by 3 ICP markers on the label's boundary
  Eigen::VectorXd errorBefore, errorAfter;  // #M marker-to-surface distances of the placed and fitted organ, mm
  std::vector<long> tetsPerRound;
  std::vector<double> meanErrorPerRound;     // mm
};

// labels: the patient's organ segmentation; id: the organ's label; templateSurface: a closed surface of
// the organ in any frame and scale (the similarity placement brings it to the markers). Throws BadInput
// naming `labelsSource` when the label has no boundary inside the scan, and what the fit throws.
OrganFit fitOrganToLabel(const TriMesh& templateSurface, const LabelMap& labels, Label id,
                         const OrganFitOptions& options, const std::string& labelsSource,
                         Progress* progress = nullptr);

}  // namespace vesalius::patient
