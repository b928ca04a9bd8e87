// Raises the smallest dihedral angles TetGen leaves behind by moving interior vertices (Freitag and
// Ollivier-Gooch, "Tetrahedral mesh improvement using swapping and smoothing", IJNME 40, 1997: the
// smoothing half, with a derivative-free pattern search in place of their steepest ascent).
#pragma once

#include "vesalius/core/mesh.h"

namespace vesalius::meshing {

// For each tet whose smallest dihedral angle is below `targetDegrees`, each of its vertices that lies on
// no boundary and no interface between tet labels (kLabel) is moved where the worst dihedral angle of the
// tets around it is largest, never inverting one nor growing one beyond `maxVolume` (0: no bound).
// A bad tet whose four vertices all lie on boundaries or interfaces first has its longest edge that lies
// on none of them split at the midpoint (with the tets around that edge), giving it a vertex to move; the
// boundaries and interfaces are unchanged. `passes` bounds the sweeps (split, then smooth).
void improveDihedrals(TetMesh& mesh, double targetDegrees, double maxVolume, int passes = 4);

}  // namespace vesalius::meshing
