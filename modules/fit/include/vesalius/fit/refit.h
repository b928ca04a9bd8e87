// Refits (ours, beyond Wang et al. 2021): the plastic fit run again with the shape it reached as a fresh template.
//
// Why: where the template is far from the organ (the SOFA liver against the test CT's liver is 22 mm off
// when placed), closest-point pulls crush tets to the plastic-stretch floor, and from then on the line
// search's trials invert them: the ICP stage stalls (docs/methods/plastic-fit.md, "Refits"). A new tet mesh
// of the fitted shape has none of those tets, and its plastic strains start again at the identity, so the
// smoothness term measures the change from the shape reached, not from the template: the stiffness is
// lowered in steps, as non-rigid ICP lowers its stiffness (Amberg, Romdhani, Vetter, CVPR 2007).
//
// Each refit: the last round's fitted boundary, tetrahedralized by the caller's `remesh` (the fit module
// knows no mesher), is the rest shape; landmarks' and attachments' template points are carried to where
// the last round put them; the stages run again from plastic strain identity with `icpIterations` ICP
// iterations at most (no constant-strain stage: the scale is already right).
#pragma once

#include "vesalius/fit/plastic_fit.h"

#include "vesalius/core/mesh.h"
#include "vesalius/core/progress.h"

#include <functional>
#include <vector>

namespace vesalius::fit {

struct RefitOptions {
  int refits = 0;         // most refits after the first fit
  int icpIterations = 3;  // ICP iterations of each refit: the first few gain most, before tets are crushed
  // A remeshed rest shape of more tets than this ends the refits (0: no bound). A fit can fold its surface
  // onto itself (a kidney the field of view cuts to its top 33 mm, pulled into a sheet at the cut), and
  // the closed, coarsened fold can keep far more triangles than the budget allows: 211,406 tets for a
  // target of 5,000, on which a refit takes more than ten minutes.
  long maxTets = 0;
};

// One fit: its rest tet mesh (V: rest positions, in template space for the first round and in the scan's
// space for refits), the markers it fitted (template-side points in that rest space) and its result.
struct FitRound {
  TetMesh rest;
  FitMarkers markers;
  FitResult result;
};

// fittedBoundary: the last round's fitted boundary surface (its own vertices only). Returns the next
// round's rest tet mesh.
using Remesh = std::function<TetMesh(const TriMesh& fittedBoundary)>;

// The markers of `markers` with their template-side points (template landmarks, attachment material
// points) carried from `rest` to the fitted positions `fittedV`; the scan-side points are unchanged.
FitMarkers carriedMarkers(const FitMarkers& markers, const TetMesh& rest, const MatrixX3d& fittedV);

// A surface in the first round's rest (template) space carried through every round: by the template's
// tets (embedding.h, Wang et al. 2021, §4.3), then through each refit by a smooth displacement of its vertices
// (smooth_displacement.h) that moves it as the refit moved its boundary vertices. Embedding it in a
// refit's tets instead tangles it where the refit crushed tets near the surface.
TriMesh carriedSurface(const TriMesh& surface, const std::vector<FitRound>& rounds);

// first: the first round (fitPlasticStrains on the template). Runs up to options.refits refits, each only
// while the last round left a marker farther than fitOptions.maxIcpError and its remeshed rest shape has at
// most options.maxTets tets, and keeps a refit only if it lowered the mean ICP error by at least
// fitOptions.minIcpGain of it (the last kept round is the result).
// Returns the rounds kept, the first one first.
std::vector<FitRound> refit(FitRound first, const FitOptions& fitOptions, const RefitOptions& options,
                            const Remesh& remesh, Progress* progress = nullptr);

}  // namespace vesalius::fit
