// The anatomical rules of Dicko et al. 2013 (§3: R1 bones straight, R2 the trunk symmetric, R5
// and R6 tissue kept inside the body, with no structure lost) measured on a whole anatomy, for
// `vesalius transfer`'s report and the virtual patient's. The paper states the rules and builds its
// transfer to keep them; it measures none. Interpenetration is not among the paper's rules; the virtual
// patient asks for it (no two tissues into one another by more than 1 mm). What is measured, per rule:
//  - outside (R5, R6): tissue vertices outside the skin, by the body's signed distance with its cavities
//    counted as inside (meshing/body_distance.h), as the transfer's bone maps count "inside". Of those,
//    the ones whose nearest skin triangle has a cut vertex (ReferenceAnatomy::skinCutVertices, where a
//    scan's field of view cut the body) are outside through the cut, which is not skin. With the
//    reference: those outside the reference's own skin already, and those pushed out (inside the
//    reference's skin, outside the transferred one), `deepMm` or more deep before apart.
//  - folds: det(I + ∇u) of the displacement field (displacement_field.h, jacobianDeterminant): the
//    paper's condition for organs not to intersect (§8).
//  - symmetry (R2): the trunk's bones (tissues marked symmetric, each group as one mesh, a bone with no
//    group as its own) mirrored in the anatomy's sagittal plane: mirrorAsymmetry (anatomy_checks.h).
//  - straightness (R1): the long bones' (isLongBone on the reference mesh; not the trunk's) centre-line
//    deviation against the reference's, on the reference's slabs (centreLineDeviation).
//  - interpenetration: for each pair of tissues whose boxes overlap, the deepest vertex of either inside
//    the other: inside where the other's generalized winding number is at least 1/2
//    (meshing/winding_number.h), its depth the distance to the other's surface. The winding number holds
//    on meshes with small holes, non-manifold edges or crossings, as OpenSim's bone meshes have
//    (rigging/bone_mesh_labels.h takes their inside the same way); near a hole a vertex reads under 1/2 and
//    is not counted. Tissues without triangles (muscle lines) have no inside and are skipped. Vertices
//    only: a thin part crossing another between its vertices is not seen. A pair that both carry the
//    reference's mesh is measured against the reference's own overlap, as OpenSim's bones overlap at
//    their joints (docs/methods/anatomy-transfer.md, "The rules as numbers").
// A tissue of `transferred` carries the reference's mesh when the reference has a tissue of its name
// with the same triangles and as many vertices (the rows then correspond). The others, and tissues
// that exist only in `transferred`, are checked by the rules that need no reference: outside (without
// the pushed-out counts), symmetry and interpenetration (against 0).
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/grid.h"
#include "vesalius/transfer/displacement_field.h"

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace vesalius::transfer {

struct AnatomyRulesOptions {
  // The transferred and the reference body's signed distance (mm, negative inside, cavities inside) and
  // cavities (1 in a sealed cavity), each pair on one grid, as meshing::bodySignedDistance makes them
  // (not copied). A distance without its cavities counts no vertex in a cavity. Without a distance the
  // function makes the body from the skin (a 2 mm grid: seconds for a full body); the reference's
  // only when some tissue carries the reference's mesh. The grids cover the body with a margin: a vertex
  // off a grid is outside, by its distance to the skin's triangles.
  const Grid<float>* skinDistance = nullptr;
  const Grid<std::uint8_t>* skinCavities = nullptr;
  const Grid<float>* referenceSkinDistance = nullptr;
  const Grid<std::uint8_t>* referenceSkinCavities = nullptr;
  // A pushed-out vertex at least this deep inside the reference's skin counts as deep (mm; `vesalius
  // transfer` gives its field voxel: shallower ones cross the skin by the field's first-order error).
  double deepMm = 3.0;
  // Which rules to measure.
  bool outside = true, folds = true, symmetry = true, straightness = true, interpenetration = true;
  // When each rule holds (AnatomyRules::*.holds):
  double symmetryToleranceMm = 1.0;      // R2: asymmetry at most this much above the reference's
  double straightnessTolerance = 0.01;   // R1: deviation at most this fraction of the length above the reference's
  double interpenetrationToleranceMm = 1.0;  // no vertex deeper than this inside another tissue, beyond the
                                             // reference's overlap of the pair
};

constexpr double kNotMeasured = std::numeric_limits<double>::quiet_NaN();

// R5, R6. Counts are tissue vertices; depths mm, clamped at the signed distance grid's band (6 mm for
// meshing::bodySignedDistance).
struct OutsideRule {
  bool measured = false;
  long vertices = 0;                 // tissue vertices checked
  long outside = 0, outsideAtCut = 0, inCavities = 0;
  double worstMm = 0;                // how far the farthest one is outside (0 if none)
  int worstTissue = -1;              // index into transferred.tissues
  Eigen::Vector3d worstAt = Eigen::Vector3d::Zero();  // that vertex (mm, LPS)
  // With the reference (tissues carrying its mesh only):
  long referenceVertices = 0;
  long referenceOutside = 0, referenceOutsideAtCut = 0, referenceInCavities = 0;
  long pushedOut = 0, pushedOutDeep = 0;
  double pushedOutWorstMm = 0;
  bool holds = true;                 // no vertex outside other than through a cut
};

struct FoldRule {
  bool measured = false;             // a field was given
  JacobianSummary jacobian;          // minimum, where, non-positive cells, and the same over the interior
  bool holds = true;                 // no cell with det(I + ∇u) <= 0
};

// R2, one symmetric group.
struct SymmetricGroup {
  std::string group;                 // the tissues' group, or the tissue's name for a bone of its own
  std::vector<int> tissues;          // indices into transferred.tissues
  double asymmetryMm = 0;            // mean distance of the mirrored group to itself (mm)
  double referenceAsymmetryMm = kNotMeasured;  // the same group in the reference, if every tissue carries its mesh
};

struct SymmetryRule {
  bool measured = false;
  std::vector<SymmetricGroup> groups;
  double worstExcessMm = 0;          // largest asymmetryMm − referenceAsymmetryMm (− 0 without the reference)
  std::string worstGroup;
  bool holds = true;                 // worstExcessMm <= symmetryToleranceMm
};

// R1, one long bone.
struct StraightBone {
  int tissue = -1;                   // index into transferred.tissues
  double deviation = 0;              // centre-line deviation, a fraction of the bone's length
  double referenceDeviation = 0;     // the reference bone's own
};

struct StraightnessRule {
  bool measured = false;
  std::vector<StraightBone> bones;
  double worstExcess = 0;            // largest deviation − referenceDeviation (fraction of the length)
  int worstTissue = -1;
  bool holds = true;                 // worstExcess <= straightnessTolerance
};

// Interpenetration of two tissues: the deepest vertex of either inside the other.
struct Interpenetration {
  int a = -1, b = -1;                // indices into transferred.tissues, a < b
  double depthMm = 0;
  long vertices = 0;                 // vertices of either inside the other
  Eigen::Vector3d at = Eigen::Vector3d::Zero();  // the deepest vertex (mm, LPS)
  double referenceDepthMm = kNotMeasured;  // the same pair in the reference (0 if apart), if both carry its mesh
  double excessMm() const { return std::isnan(referenceDepthMm) ? depthMm : depthMm - referenceDepthMm; }
};

struct InterpenetrationRule {
  bool measured = false;
  std::vector<int> skippedTissues;   // without triangles (muscle lines): no inside
  std::vector<int> openTissues;      // measured, but with boundary edges
  long boxPairs = 0;                 // pairs whose boxes overlap (the candidates)
  std::vector<Interpenetration> pairs;  // the pairs with a vertex inside the other, largest excess first
  double worstMm = 0;                // deepest over the pairs (0 if none)
  double worstExcessMm = 0;          // pairs.front().excessMm(), or 0
  bool holds = true;                 // worstExcessMm <= interpenetrationToleranceMm
};

// Per tissue of `transferred`.
struct TissueRules {
  int referenceTissue = -1;          // the reference tissue whose mesh it carries, or -1
  long vertices = 0;
  long outside = 0, outsideAtCut = 0, inCavities = 0;
  double outsideWorstMm = 0;
  long referenceOutside = 0, referenceInCavities = 0, pushedOut = 0, pushedOutDeep = 0;
  double centreLineDeviation = kNotMeasured, referenceCentreLineDeviation = kNotMeasured;  // R1, long bones
  bool closed = false;               // no boundary edge (interpenetration)
  double interpenetrationMm = 0;     // its deepest interpenetration with another tissue
  int interpenetrates = -1;          // with which (index into transferred.tissues)
};

struct AnatomyRules {
  OutsideRule outside;
  FoldRule folds;
  SymmetryRule symmetry;
  StraightnessRule straightness;
  InterpenetrationRule interpenetration;
  std::vector<TissueRules> tissues;  // per transferred tissue
  std::vector<std::pair<std::string, double>> stageSeconds;  // wall time per rule, in the order measured
  bool holds() const {
    return outside.holds && folds.holds && symmetry.holds && straightness.holds && interpenetration.holds;
  }
};

// reference: the anatomy transferred from (may be `transferred` itself, for a reference's own rules);
// transferred: the anatomy to check, its tissues matched to the reference's by name; field: the final
// displacement field (reference space), or nullptr (folds not measured). Throws BadInput if a skin is
// empty or open (when the outside rule needs its body), and as the distances do.
AnatomyRules checkAnatomyRules(const ReferenceAnatomy& reference, const ReferenceAnatomy& transferred,
                               const DisplacementField* field, const AnatomyRulesOptions& options = {});

}  // namespace vesalius::transfer
