// Surfaces of many labels at once that share their boundaries where labels touch: SurfaceNets for
// multi-label segmentations (Frisken, "SurfaceNets for multi-label segmentations with preservation of
// sharp boundaries", JCGT 11(1), 2022). Where two labels touch there is one sheet of triangles, used by
// both (with opposite orientations), so touching organs neither cross nor leave a gap, and the whole
// set can be meshed as one conforming multi-region tet mesh (tetrahedralize.h).
//
// 1. The chosen labels are cropped to their box and padded with background; other labels count as
//    background (0). The map is made well-composed for every chosen label (Latecki, "3D well-composed
//    pictures", 1997): no label may meet itself across a voxel edge or corner only, or leave two
//    diagonally opposite voxels of a 2x2x2 block to others. Then each label's voxel boundary is a closed
//    2-manifold. Repairs move single voxels between labels, always to the stronger one (background is
//    the weakest, then labels from the largest to the smallest), so they end: the label in trouble takes
//    the voxel (or, for two opposite corners, the two voxels of a path) it misses where it is the
//    stronger, and otherwise gives one of its own to its stronger neighbour.
// 2. One vertex per voxel corner whose eight voxels are not all one label, placed at the corner; one
//    quad per face between two voxels of different labels.
// 3. Frisken's constrained smoothing: a vertex moves towards the mean of its neighbours whose set of
//    labels (among their eight voxels) contains its own, so an interface vertex (two labels) follows its
//    interface, a junction vertex (three) its junction line, and a corner of four or more labels stays;
//    each vertex is then clamped to its cell (within 0.45 voxel of its corner, per axis), which keeps
//    the surface within about half a voxel of the voxel boundary. Means are taken in mm.
// 4. Quads are split along their shorter diagonal; both labels of a face use the same two triangles.
// 5. Each label gets its voxel volume back (as counted before the repairs): the vertices it alone shares
//    with the background move along their volume gradients by one distance per label (two Newton steps);
//    vertices between labels stay, so the sharing is kept.
// 6. Smoothing can fold a few triangles through others; their vertices are moved back towards their
//    corners until no triangle crosses another (the voxel faces never do).
// Deviations from Frisken: the vertex types come from the label sets directly (she classifies by face
// count per cell), with the same effect, sharp junctions kept; the smoothing steps are Taubin's λ/μ pairs
// rather than plain averaging, which shrank 3 mm organs by 5-15%; steps 5 and 6 are ours.
#pragma once

#include "vesalius/core/label_map.h"
#include "vesalius/core/mesh.h"
#include "vesalius/core/progress.h"

#include <vector>

namespace vesalius::meshing {

struct SharedSurfaceOptions {
  int smoothingIterations = 16;  // Taubin pairs of constrained smoothing (0: the voxel faces themselves)
};

struct SharedLabelSurfaces {
  MatrixX3d V;            // #V by 3, mm (LPS)
  MatrixX3i F;            // #F by 3, counter-clockwise seen from the side of sides(f, 1)
  Eigen::MatrixX2i sides; // #F by 2: the label F's normal points out of, and the one it points into (0: outside)
  std::vector<Label> ids; // the labels with voxels, ascending
  long repairedVoxels = 0;  // voxels given to another label to make the map well-composed (step 1)
};

// The shared surfaces of the labels `ids` (every non-zero label present when empty). Throws BadInput if
// none of them has a voxel, UsageError on a negative iteration count. `progress` may be null.
SharedLabelSurfaces sharedLabelSurfaces(const LabelMap& labels, const std::vector<Label>& ids,
                                        const SharedSurfaceOptions& options = {}, Progress* progress = nullptr);

// The closed surface of label `id`: every face with `id` on one side, oriented outward, with only the
// vertices it uses; face attribute kLabel = id. Throws UsageError if `id` is not in surfaces.ids.
TriMesh surfaceOfLabel(const SharedLabelSurfaces& surfaces, Label id);

// Where label `id` touches label `other`: the faces with `id` on one side and `other` on the other,
// oriented out of `id`, with only the vertices they use (an open surface; empty when the two do not share
// a voxel face); face attribute kLabel = id. A muscle's insertion on a bone is the bone's interface with
// the muscle (Wang et al. 2021, §4.1.2). Throws UsageError if either label is not in surfaces.ids or they are the same.
TriMesh interfaceOfLabels(const SharedLabelSurfaces& surfaces, Label id, Label other);

}  // namespace vesalius::meshing
