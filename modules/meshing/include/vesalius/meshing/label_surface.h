// Triangle surfaces of labels in a label map.
//
// Method: the label's voxels (cropped to their bounding box and padded by one background voxel on every
// side, so masks touching the volume edge still give closed surfaces) are contoured at 0.5 by
// vtkDiscreteFlyingEdges3D, mapped from index to LPS world space by the map's GridGeometry
// (origin + direction · diag(spacing) · index, so oblique and flipped directions are honoured exactly),
// smoothed with vtkWindowedSincPolyDataFilter (Taubin, Zhang, Golub, "Optimal surface smoothing as filter
// design", ECCV 1996; coordinates normalised, feature edges and boundary not treated specially), optionally
// decimated to a target face count by edge collapses that keep it closed (decimate_surface.h), oriented
// outward (the enclosed signed volume is made positive), and finally moved along
// its vertex normals by the one uniform distance that makes it enclose the label's voxel volume.
// That last step exists because marching cubes cuts the corners of every voxel and smoothing shrinks
// thin parts: on the demo CT's bone (3 mm voxels) the surface would otherwise enclose 2.6% less than its
// voxels. It is skipped when the distance would exceed half a voxel (a label only a voxel or two thick,
// such as a skin shell, cannot carry its volume as a smooth surface; mesh the body instead).
// Smoothing can pull the two sides of a thin part through each other, and the offset can push a thin flap
// or two close pieces through each other. So that every surface can be handed to TetGen, the smoothing
// is halved (20, 10, 5, 2, 0) until the smoothed surface has no crossing triangles
// (core/self_intersections.h), and the offset is then undone around any triangles it makes cross.
// Output: V in mm (LPS), F counter-clockwise seen from outside, face attribute kLabel = the label id.
#pragma once

#include "vesalius/core/label_map.h"
#include "vesalius/core/mesh.h"
#include "vesalius/core/progress.h"

#include <string>
#include <vector>

namespace vesalius::meshing {

struct SurfaceOptions {
  int smoothingIterations = 20;  // windowed-sinc iterations, 0 or >= 2; 0 keeps the staircase surface
  double passBand = 0.05;        // windowed-sinc pass band in (0, 2); lower smooths more
  int targetFaces = 0;           // decimate to about this many faces; 0 keeps them all
  bool preserveVolume = true;    // restore the voxel volume by a normal offset (see above)
  bool avoidSelfIntersections = true;  // less smoothing, and no offset where it crosses (see above)
};

// The surface of label `id`. Throws BadInput if no voxel carries `id`, UsageError on bad options or id 0
// (the background).
TriMesh labelSurface(const LabelMap& labels, Label id, const SurfaceOptions& options = {});

struct LabelSurface {
  Label id = 0;
  std::string name;  // from the label table; the id as text if the table does not name it
  TriMesh mesh;
};

// One surface per id in `ids`, in that order, skipping ids without voxels; with `ids` empty, every
// label of the table (then every non-zero label present, if the table is empty). One scan of the map
// finds every label's box; the labels are then surfaced in parallel (TBB), each exactly as labelSurface
// would. `progress` may be null and gets one stage, "surfaces", whose fraction is the labels done.
std::vector<LabelSurface> labelSurfaces(const LabelMap& labels, const std::vector<Label>& ids,
                                        const SurfaceOptions& options = {}, Progress* progress = nullptr);

}  // namespace vesalius::meshing
