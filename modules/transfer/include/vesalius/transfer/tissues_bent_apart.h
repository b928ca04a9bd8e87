// Tissues bent out of the tissues they reach into, and kept inside the skin: the interpenetration that
// Dicko et al. 2013 rule out, removed by one smooth displacement of the tissues that may move
// (bones_warped_into_skin.h's kernel bend, with the other tissues and the space beyond the skin as the
// side to leave). Not in the papers: the transfer keeps tissues apart where the reference has them apart;
// this is for anatomies whose tissues come from different sources (a patient's labels and fitted organs
// with the reference's bones beyond the scan; one CT's organs with OpenSim's bones).
//
// What counts as reaching in, measured on points of each bent tissue (its vertices, edge midpoints and
// face centroids, so that a long triangle across a curved surface is seen between its corners):
//  - a point inside a fixed tissue (winding number at least 1/2): its depth, to be moved out along the
//    direction from the fixed surface's closest point;
//  - a fixed tissue's vertex inside a bent tissue (the bent tissue straddles the fixed one where it is
//    thinner than the points are apart): by Straddle::MoveOff, the bent tissue's point nearest it, moved
//    along the fixed tissue's outward normal by the vertex's depth (a rib across the rim of a gallbladder,
//    moved off it); by Straddle::Dent, the bent tissue's point nearest its closest point on the bent
//    surface, moved inward by the vertex's depth (an organ template without the groove of a vessel that
//    runs in it: the fixed tissue's normals there point every way around the vessel, the directions to the
//    organ's own surface one way);
//  - a point outside the skin (transfer::SkinDistanceFunction): its distance, moved inside.
// The bend is smooth (C²) and local: fixed tissues do not move, bent ones move wherever they are within its
// reach of a moved point, and points fixed to a bent tissue (ReferencePoint::tissue) move with it.
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/grid.h"
#include "vesalius/transfer/bones_inside_skin.h"
#include "vesalius/transfer/bones_warped_into_skin.h"

#include <vector>

namespace vesalius::transfer {

enum class BendRole { Fixed, Bent, Untouched };
enum class Straddle { MoveOff, Dent };  // as above

// The straddle case (above): the rule, and where fixed vertices count. With a field of view (a scan's grid),
// only the fixed vertices within the box of its voxel centres: a label's tissue cut by the scan is closed
// half a voxel beyond them, and that cap is the scan's edge, not tissue, while a fitted organ may go on.
struct StraddleOptions {
  Straddle rule = Straddle::MoveOff;
  const GridGeometry* fieldOfView = nullptr;  // the caller's; none: every fixed vertex counts
};

struct TissuesBentApart {
  // Points of the bent tissues that reached in (as above), before and after the bend.
  long insideBefore = 0, insideAfter = 0;
  double largestMoveMm = 0;  // the bend's largest move of a point of a bent tissue
  // The displacement (empty when nothing reached in), for geometry that moves with the bent tissues.
  InsideSkinWarp bend;
};

// roles: per anatomy.tissues. Only the bent tissues with triangles whose boxes meet a fixed tissue's are
// measured; fixed tissues without triangles are not obstacles. options: the bend's reaches and rounds and
// how far apart (marginMm) each point should end. Throws UsageError for roles of another length.
TissuesBentApart bendTissuesApart(ReferenceAnatomy& anatomy, const std::vector<BendRole>& roles,
                                  const SkinDistanceFunction& skin, const InsideSkinWarpOptions& options,
                                  const StraddleOptions& straddle = {});

}  // namespace vesalius::transfer
