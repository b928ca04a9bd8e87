// Fitted organs separated where they touch (Wang et al. 2021, §4.1.4, Fig. 19). Each organ is fitted to its own
// label alone (organ_fit.h), so two organs that touch overlap where their markers disagree by a voxel or
// two. Every pair is pushed apart by fit::removeInterpenetrations on the last round's fitted tets (each
// mesh moved only in an FEM-solved contact region around its penetrating vertices; nothing else moves),
// later organs against earlier ones, in sweeps until no pair penetrates. Each fit's `surface` becomes the
// boundary of its moved tets, and its `carriedTemplate` moves with them: embedded in the fitted tets before
// the separation and carried to their positions after it (fit/embedding.h, Wang et al. 2021, §4.3), so a template
// vertex away from the contact regions stays where it was.
//
// The promise (fit/interpenetration.h): afterwards no boundary vertex of either organ of a pair lies in
// a tet of the other, unless `solver.maxRounds` ran out first, which the report shows as vertices still
// penetrating. A pushed vertex aims `solver.clearance` (0.05 mm by default) beyond the other's surface, so
// where they were pushed the surfaces end up about that far apart. Deviations from Wang et al. 2021 are fit's: penalty
// springs re-aimed in rounds stand in for a contact simulation. Only vertices are tested: a triangle of
// one organ may still cross an edge of the other by less than an edge's sag.
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/fit/interpenetration.h"
#include "vesalius/patient/organ_fit.h"
#include "vesalius/transfer/tissues_bent_apart.h"

#include <cstddef>
#include <string>
#include <vector>

namespace vesalius::patient {

struct OrganSeparationOptions {
  fit::InterpenetrationOptions solver;  // rings of the contact regions, rounds, clearance, stiffnesses
};

// One pair of organs (indices into the list given), measured on the fitted tets before and after.
struct OrganPairSeparation {
  std::size_t first = 0, second = 0;  // indices into the organs, first < second
  long penetratingBefore = 0, penetratingAfter = 0;  // boundary vertices of either inside the other's tets
  double maxDepthBefore = 0, maxDepthAfter = 0;      // mm, deepest of them below the other's surface (0: none)
  int rounds = 0;                // FEM solves (fit::InterpenetrationReport::rounds, over all sweeps)
  double maxDisplacement = 0;    // mm, the largest vertex move of either organ in this pair's solves
};

// organs: fits from fitOrganToLabel (each with its `tets`), in world mm; their tets, surface and
// carriedTemplate move in place. Returns one report per pair in fit::removeInterpenetrations' order
// ((1,0), (2,0), (2,1), (3,0), …). Throws UsageError for a null entry or a fit without tets, and what
// fit::removeInterpenetrations throws (NumericalFailure, e.g. an organ wholly inside another: then no fit
// has moved).
std::vector<OrganPairSeparation> separateOrgans(const std::vector<OrganFit*>& organs,
                                                const OrganSeparationOptions& options = {});

// The fitted organs bent out of the tissues of the organ map's other labels, which do not move. A template
// fitted to markers on its own label follows that label between the markers only as far as its shape allows:
// where a neighbour presses a notch into the organ that the template lacks (the colon and the caval and
// portal veins against a liver template without their grooves) the fitted surface crosses into the
// neighbour's label by several millimetres. The bend is transfer::bendTissuesApart's (Dicko et al. 2013's
// rule that tissues do not interpenetrate; not in Wang et al. 2021, whose organs are fitted alone and
// separated from each other only): smooth and local, the fitted tissues the only ones that move, ending
// options.marginMm apart. Where a label's tissue lies inside a fitted organ (a vessel in the groove the
// template lacks) the organ is dented inward where its surface is nearest (transfer::Straddle::Dent). Where the scan cuts
// a label the cap that closes its tissue is the scan's edge, not tissue: no obstacle to an organ that goes
// on beyond the scan. Nor is the scan's skin a bound here: it is closed across the same cut.
//
// anatomy: the scan's anatomy, the tissue named names[i] holding fits[i]'s surface; every other tissue with
// triangles is fixed. scan: the grid of the labels. The fits' tets, surfaces and carried templates move
// with the bend, and their tissues take the moved surfaces. Throws UsageError for lists of different
// lengths, a null fit or a name that is no tissue of the anatomy.
transfer::TissuesBentApart bendOrgansOffLabels(ReferenceAnatomy& anatomy, const std::vector<std::string>& names,
                                               const std::vector<OrganFit*>& fits, const GridGeometry& scan,
                                               const transfer::InsideSkinWarpOptions& options);

}  // namespace vesalius::patient
