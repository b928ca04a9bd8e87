// Removing interpenetrations between fitted organs that touch (Wang et al. 2021, §4.1.4, Fig. 19).
//
// Organs are fitted one at a time, so two that touch (muscles in continuous contact) overlap where the
// markers between them were imprecise. For a pair, as the paper does: the boundary vertices of each mesh
// that lie inside the other's volume are found; each mesh's tets around them, grown by `rings` rings of
// tets that share a vertex, form its contact region; an FEM solve on each region alone pushes the surfaces
// apart, and nothing outside the regions moves.
//
// The FEM solve: the region is a stable neo-Hookean body, stress-free in its fitted shape; its vertices
// shared with the rest of the mesh are held by stiff springs (and put back exactly afterwards), and each
// penetrating vertex is pulled by a spring to a target beyond the other mesh's surface. Deviation from the
// paper, which runs a contact simulation: the contact is these penalty springs, re-aimed in rounds. A
// vertex of one mesh inside the other aims for the other's nearest surface point, only half-way when the
// other mesh penetrates this one too (both surfaces move, so they meet in the middle); rounds repeat
// with the regions grown by newly penetrating vertices until no boundary vertex of either mesh lies
// inside the other, or `maxRounds` have run.
//
// Chains (contact islands of several organs): the second mesh against the first, the third against the
// first two, and so on, in order, as in the paper; repeated, since a later pair can push a mesh back into
// an earlier one.
#pragma once

#include "vesalius/core/mesh.h"

#include <vector>

namespace vesalius::fit {

struct InterpenetrationOptions {
  int rings = 5;             // rings of tets added around the penetrating vertices' tets (Wang et al.'s 5-ring)
  int maxRounds = 20;        // re-detections and solves at most
  double clearance = 0.05;   // mm: a pushed vertex aims this far beyond the other surface
  double poissonRatio = 0.45;
  double contactStiffness = 1e2;  // springs to the targets, per μ·(mean edge length)
  double holdStiffness = 1e4;     // springs holding the region's border, per μ·(mean edge length)
  double anchorStiffness = 1e-2;  // springs holding every other region vertex where it was, per μ·(mean edge length)
};

struct InterpenetrationReport {
  long penetratingBefore = 0;  // boundary vertices of either mesh inside the other, before
  long penetratingAfter = 0;   // and after
  int rounds = 0;              // FEM solves per mesh
  long regionTets[2] = {0, 0};  // tets in each mesh's contact region (0 if it never moved)
  double maxDisplacement = 0;  // mm, largest vertex move in either mesh
};

// a, b: tet meshes in world mm (V #V by 3, T #T by 4, positively oriented); their V move in place.
// Throws NumericalFailure if a solve does not converge or would invert a tet (e.g. one mesh wholly
// inside the other), leaving both meshes as they were.
InterpenetrationReport removeInterpenetration(TetMesh& a, TetMesh& b, const InterpenetrationOptions& options = {});

// Every mesh against every earlier one, in order ((1,0), (2,0), (2,1), (3,0), ...), in sweeps until a
// sweep finds no pair penetrating (pushing one pair apart can push a third mesh into one of them), at most
// maxRounds sweeps. One report per pair, in that order: penetratingBefore from the first sweep, the rest
// over all sweeps (rounds summed, the largest region and displacement).
std::vector<InterpenetrationReport> removeInterpenetrations(std::vector<TetMesh>& meshes,
                                                            const InterpenetrationOptions& options = {});

}  // namespace vesalius::fit
