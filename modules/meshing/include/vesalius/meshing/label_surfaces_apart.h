// Closed surfaces that stand for touching labels of one label map, moved apart where they cross.
// labelSurface makes each label's surface on its own (smoothed, decimated, its voxel volume given back by a
// normal offset), so two labels that share voxel faces get two surfaces that cross where one bulges more
// than the other: by up to about two thirds of a voxel on the shipped CT (the right lung's lower lobe and
// the ninth rib, the small bowel and the colon, the iliac arteries and veins); bones brought each onto its
// own label cross the same way (the hip bones at the symphysis). The label map puts their boundary between
// them: each vertex of one surface inside another (winding number at least 1/2) moves out of it towards
// the other's closest point, by half its depth and half the margin, and the other's vertices inside the
// first likewise, all at once, in rounds until none is inside or the rounds run out. A vertex inside
// several surfaces takes its largest move. With a field of view (the label map's grid), vertices the scan
// does not see (GridGeometry::seesPoint: the caps where the scan cut a label) stay on the scan's edge;
// without one, as for bones that go on beyond the scan, every vertex counts and may move. Surfaces can be
// held fixed (the scan's own tissues, against bones brought onto their labels). Not in the
// papers: Dicko et al. 2013's rule that no two tissues interpenetrate, for tissues made from one label map
// (sharedLabelSurfaces shares their boundaries exactly, but undecimated).
#pragma once

#include "vesalius/core/grid.h"
#include "vesalius/core/mesh.h"

#include <vector>

namespace vesalius::meshing {

struct LabelSurfacesApartOptions {
  double marginMm = 0.1;  // how far apart the two sides of a crossing should end
  int rounds = 8;         // at most
  // Per surface (empty: none), those that keep their place; a vertex inside one moves all the way out of it.
  std::vector<bool> fixed;
};

struct LabelSurfacesApart {
  long insideBefore = 0, insideAfter = 0;          // vertices of a surface inside another (that the scan sees)
  double deepestBeforeMm = 0, deepestAfterMm = 0;  // the deepest of them
  double largestMoveMm = 0;                        // the largest move of a vertex over all rounds
  int rounds = 0;                                  // rounds that moved vertices
};

// surfaces: closed surfaces in world mm (labelSurface's), moved in place; fieldOfView: the label map's grid,
// or null (above). Throws UsageError for a null surface or options out of range.
LabelSurfacesApart moveLabelSurfacesApart(const std::vector<TriMesh*>& surfaces, const GridGeometry* fieldOfView,
                                          const LabelSurfacesApartOptions& options = {});

}  // namespace vesalius::meshing
