// Tetrahedral meshes of closed surfaces through TetGen (Si, "TetGen, a Delaunay-based quality tetrahedral
// mesh generator", ACM TOMS 41(2), 2015): a constrained Delaunay tetrahedralization of the surface, refined
// by Delaunay refinement until every tet meets the radius-edge and volume bounds, then optimized by flips
// and vertex smoothing. TetGen 1.5 does not enforce its dihedral bound, so the tets it leaves below
// minDihedral are smoothed once more: their vertices off the surfaces move to raise the worst angle
// around them (Freitag and Ollivier-Gooch, IJNME 40, 1997); a bad tet with every vertex on a surface
// first gets an inner edge split so that it has a vertex to move.
//
// Several closed surfaces that are nested or apart (a body with bones inside it, Sujar et al. 2018, §3.2) give one
// conforming mesh: TetGen's region attributes (-A) mark every tet with the region it lies in, the region
// of a surface being its inside less the surfaces nested in it. Each region is found from a seed point:
// for each connected part of a surface, a ray from the centroid of one of its largest triangles is cast
// inward to the first surface it meets, and the midpoint with the largest clearance is used. The cavity
// of an inward-facing inner shell (a hollow in a bone) belongs to the smallest other surface around it
// (the body); cavities no other surface holds are removed.
//
// Labels that touch (shared_label_surfaces.h) give one conforming mesh too: each shared triangle goes to
// TetGen once, and each connected part of a label's surface gets a seed by the same inward ray, cast into
// the label's side of one of its triangles.
//
// Input is checked before TetGen sees it, because TetGen aborts or loops on bad surfaces: every surface
// must be a closed 2-manifold, and no triangle may cross another of any surface (self_intersections.h).
// Violations are BadInput naming the surface; TetGen's own failures become NumericalFailure.
//
// TetGen never runs unbounded. Options it may not finish with are refused before it starts (UsageError):
// a radius-edge bound below kMinRadiusEdge, a volume bound that needs more than maxTets tets. While it
// runs, it may add at most a budget of points (TetGen -S): maxTets / 5 (a tet mesh has about six tets per
// vertex), and with targetTets at most 2 targetTets + 50,000. A mesh that used up its budget did not meet
// its bounds and is refused (BadInput naming the surface); with targetTets the next attempt's looser volume
// bound usually meets them.
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/meshing/shared_label_surfaces.h"

#include <string>
#include <vector>

namespace vesalius::meshing {

// Below this radius-edge bound TetGen's Delaunay refinement need not terminate (its manual: the bound must
// be above 1; near 1 it may run for ever).
constexpr double kMinRadiusEdge = 1.1;

struct TetrahedralizeOptions {
  double radiusEdge = 1.5;    // TetGen -q: largest circumradius / shortest edge; 0 disables quality refinement
  double minDihedral = 12.0;  // TetGen -q and the smoothing: smallest dihedral angle aimed for, degrees
  double maxVolume = 0.0;     // TetGen -a: largest tet volume in mm^3; 0 for no bound
  long targetTets = 0;        // aim for about this many tets (±15%) by choosing maxVolume; 0 to use maxVolume
  bool keepSurface = false;   // TetGen -Y: no Steiner points on the surfaces (their triangles stay as given)
  // tetrahedralizeWithinBudget (tet_budget.h) only: -Y where coarsening alone leaves more than twice the target.
  bool keepSurfaceOverBudget = false;
  int optimizationLevel = 4;  // TetGen -O: rounds of flips and smoothing (0..9)
  double maxDihedral = 130.0;  // TetGen -o/: optimization removes dihedral angles above this, degrees
  long maxTets = 5'000'000;    // the budget above: no mesh of more tets is attempted
};

struct RegionSurface {
  TriMesh surface;   // closed, outward (counter-clockwise seen from outside), mm
  int label = 1;     // stored in the tets of its region
  std::string name;  // names the surface in error messages
};

// One region per surface. Output: V #V by 3 (only vertices of kept tets), T #T by 4
// positively oriented, tet attribute kLabel = the label of the region holding the tet.
TetMesh tetrahedralizeRegions(const std::vector<RegionSurface>& regions, const TetrahedralizeOptions& options = {});

// The labels of `surfaces` as regions: tet attribute kLabel = the label of the region holding the tet;
// background (0) is left empty, cavities of it included. Throws BadInput naming `source` if a label's
// surface is not a closed 2-manifold or triangles cross.
TetMesh tetrahedralizeLabels(const SharedLabelSurfaces& surfaces, const TetrahedralizeOptions& options = {},
                             const std::string& source = "labels");

// One closed surface (possibly of several parts); every tet gets label 1, or the surface's face label
// kLabel when all its faces carry the same one. `source` names it in error messages.
TetMesh tetrahedralize(const TriMesh& surface, const TetrahedralizeOptions& options = {},
                       const std::string& source = "surface");

// The checks above alone: throws BadInput naming the first surface that is open, non-manifold, empty or
// crossed by a triangle (of itself or of another surface).
void checkTetgenInput(const std::vector<RegionSurface>& regions);

// Whether a triangle of one of the surfaces crosses another triangle (of its own surface or another).
bool surfacesCross(const std::vector<RegionSurface>& regions);

}  // namespace vesalius::meshing
