// The signed distance to a closed body surface on which rules R5 and R6 (Dicko et al. 2013, §3: tissue inside the
// skin) are measured, shared by the transfer pipeline (patient/transfer_into_body.h: its bone maps and
// `vesalius transfer`'s report) and `reference full-body` (its bones moved inside the skin), so that all
// count "inside" alike.
//
// The body is the skin with its cavities (meshing/sealed_cavities.h): MakeHuman's mouth and eye sockets
// are pockets of the skin surface reaching into the head, in which the reference's teeth, palate and
// orbits lie; they count as inside. Pockets whose opening is narrower than kCavityOpeningMm are sealed:
// the neutral skin's lips close to within 6 mm, but the reference skin registered onto another body opens
// them to 10-12 mm at this grid's 2.5 mm voxels (docs/methods/anatomy-transfer.md, "The body's cavities").
#pragma once

#include "vesalius/core/grid.h"
#include "vesalius/core/mesh.h"

#include <cstdint>

namespace vesalius::meshing {

// Exact within this distance of the surface, clamped to ±it beyond (mm).
constexpr double kDistanceBandMm = 6.0;
// Openings of the skin narrower than this are sealed (mm; at most 2 kDistanceBandMm).
constexpr double kCavityOpeningMm = 12.0;

struct BodyDistance {
  Grid<float> signedDistance;      // mm, negative inside the body (cavities included)
  Grid<std::uint8_t> cavities;     // 1 in the sealed cavities (the same grid)
  double cavitiesMl = 0;           // their volume
};

// The body's signed distance on a 2 mm grid covering `body` (closed, #V by 3 mm LPS). Throws BadInput
// as meshing::meshSignedDistance does.
BodyDistance bodySignedDistance(const TriMesh& body);

// How many rows of V (#V by 3, mm) lie in the body's cavities (their nearest voxel).
long verticesInCavities(const BodyDistance& body, const MatrixX3d& V);

}  // namespace vesalius::meshing
