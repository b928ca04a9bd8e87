// The tets of an organ template given as a surface, and of the fitted shapes a fit refits from
// (fit/refit.h), at a tet target however finely the surface is triangulated.
//
// A surface that is not a closed 2-manifold, or whose triangles cross (OpenSim's bones are such), cannot
// be tetrahedralized: it is closed by its winding number first (closed_surface.h) at `faces` triangles or,
// without them, at its own count. A surface that encloses (next to) no volume has no inside for TetGen to
// fill, and TetGen searches for one for minutes, so it is refused first: flat when the root of the smallest
// variance of its vertices, or its enclosed volume, is below a millionth of its bounding box's diagonal
// (or of its cube). A sphere encloses a tenth of that cube; a plate a hundredth of its width thick still
// 3e-5. TetGen meshes the closed surface decimated to `faces` triangles, or as the tet target allows
// (tet_budget.h); the caller carries the full surface's detail by embedding it in the tets (Wang et al. 2021, §4.3).
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/meshing/tet_budget.h"

#include <optional>
#include <string>

namespace vesalius::meshing {

struct TemplateTetsOptions {
  // About this many tets: with `faces` 0, within twice it unless the surface is coarsened to the 50
  // triangles below which tet_budget.h stops, or decimation cannot take it there (a thin waist or a fold
  // then still refines past it).
  long targetTets = 20000;
  int faces = 0;            // decimate the surface to about this many triangles first; 0: as targetTets allows
};

// What made a surface template unfit for TetGen, and what closed it.
struct SurfaceRepair {
  long boundaryEdges = 0, nonManifoldEdges = 0, crossingTrianglePairs = 0;
  long closedTriangles = 0;  // of the closed surface
};

struct TemplateTets {
  TetMesh tets;                         // V #V by 3 in the surface's space, T #T by 4 positively oriented
  TriMesh surface;                      // the closed surface the tets fill: the template itself, or its repair
  std::optional<SurfaceRepair> repair;  // set when the template had to be closed
  long tetrahedralizedFaces = 0;        // triangles TetGen was given
};

// surface: closed, #V by 3, #F by 3, mm. Decimated to options.faces (when positive) or within the budget of
// options.targetTets, then tetrahedralized. Throws what tetrahedralize throws, naming `source`; UsageError
// for a target that is not positive.
BudgetedTets closedSurfaceTets(const TriMesh& surface, const TemplateTetsOptions& options,
                               const std::string& source = "surface");

// surface: a template surface, #V by 3, #F by 3, mm, closed or not. Throws BadInput naming `source` for a
// flat surface or one that cannot be closed, and what closedSurfaceTets throws.
TemplateTets templateTets(const TriMesh& surface, const TemplateTetsOptions& options,
                          const std::string& source = "template");

}  // namespace vesalius::meshing
