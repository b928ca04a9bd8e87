// Tet meshes that keep their tet target on any closed surface, however finely it is triangulated.
//
// TetGen keeps every input triangle, so the tets of a fine surface are many whatever the volume bound: a
// 30,000-triangle muscle gives about 157,000 tets for a target of 20,000, a 12,000-triangle brain about
// 280,000. The surface handed to TetGen is therefore coarsened first (edge collapses that keep it closed,
// decimate_surface.h; closed by its winding number instead where the decimation crosses itself,
// closed_surface.h) to facesForTets(target) triangles, and again to half as many while the tets are more
// than twice the target. At 200 triangles TetGen's radius-edge bound is first relaxed to its own default
// (2.0), and only then is the surface halved further, down to 50 triangles. Where decimation can take no
// more faces off and the tets are still more than twice the target, TetGen's refinement has split the
// surface triangles it encroached on (a thin MakeHuman body's 4 mm voxel surface stops at 12,000 triangles
// and gave 485,077 tets for 100,000 asked); with TetrahedralizeOptions::keepSurfaceOverBudget the surface
// is then given to TetGen to keep as it is (-Y: 96,151 tets), when that gives fewer tets within the point
// budget. (Not for fits: a fitted liver's tets made so gave a refit surface that TetGen could not mesh
// within its budget.) The caller keeps the full surface and carries its detail by embedding it in the
// coarse tets, as Wang et al. 2021, §4.3, fits a coarse tet mesh and carries the detailed surface.
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/meshing/tetrahedralize.h"

#include <string>

namespace vesalius::meshing {

// Triangles a closed surface may keep for about targetTets tets: a tenth of the target, at least 200.
// Decimated triangles are less regular than a mesher's, and TetGen refines around the small ones: a
// 500-triangle decimated ellipsoid gives 7,600-8,300 tets for a target of 5,000 where 1,000 triangles
// give more than 10,000 (tests/meshing/tet_budget_test.cpp).
int facesForTets(long targetTets);

// `surface` (closed, #V by 3, #F by 3) decimated to about `faces` triangles (unchanged when it has no more),
// or, where that crosses itself, closed by its winding number at that count (a fitted organ can touch
// itself in a cleft it was pulled into).
TriMesh coarsenedSurface(const TriMesh& surface, int faces);

struct BudgetedTets {
  TetMesh tets;
  long surfaceFaces = 0;     // triangles TetGen was given
  int coarsenings = 0;       // 0: the surface as it was given
  bool surfaceKept = false;  // TetGen kept the surface's triangles (-Y) to stay nearer the target
};

// options.targetTets must be positive (UsageError). Throws what tetrahedralize throws, naming `source`.
BudgetedTets tetrahedralizeWithinBudget(const TriMesh& surface, const TetrahedralizeOptions& options,
                                        const std::string& source = "surface");

}  // namespace vesalius::meshing
