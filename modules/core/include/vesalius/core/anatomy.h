// A reference anatomy as anatomy transfer takes it (Dicko et al. 2013, §3, Fig. 2.c): a skin with bones, muscles
// and organs inside it, and named points (muscle path points, joint centres) fixed to them.
// On disk it is a folder with reference.json (io/reference_anatomy_io.h; docs/formats.md).
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace vesalius {

// A plane through `point` with unit `normal`; for a body, the sagittal plane with the normal to its left.
struct Plane {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
};

enum class TissueKind { Bone, Muscle, Organ, Other };
const char* tissueKindName(TissueKind kind);
// Throws UsageError for a name other than bone, muscle, organ, other.
TissueKind tissueKindFromName(const std::string& name);

// Display colours (sRGB 0..255) shared by every picture and model file we make of an anatomy, so a
// tissue looks the same in a PNG and in a glTF viewer: bone ivory, muscle red, organ and other brown.
using DisplayColour = std::array<std::uint8_t, 3>;
DisplayColour tissueKindColour(TissueKind kind);
inline constexpr DisplayColour kSkinColour{230, 190, 160};

struct ReferenceTissue {
  std::string name;
  TissueKind kind = TissueKind::Other;
  // Bones with the same non-empty group move by one affine map (e.g. "pelvis" for both hip bones and the
  // sacrum); a bone with an empty group is a group of its own.
  std::string group;
  // Trunk bones (skull, spine, sternum, pelvis, rib cage) move by maps symmetric about the sagittal plane
  // (Dicko et al. 2013, §8, rule R2). Every tissue of a group must agree.
  bool symmetric = false;
  TriMesh mesh;  // closed surface, mm, LPS
};

struct ReferencePoint {
  std::string name;
  std::string tissue;  // the tissue it is fixed to; a bone's points move with the bone (rule R7)
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
};

struct ReferenceAnatomy {
  std::string name;
  TriMesh skin;  // closed body surface
  // Skin vertices that are not skin: where a scan's field of view cut the body (the caps of a torso
  // CT). They carry no fat, so erosion leaves them in place. Ascending indices into skin.V.
  std::vector<int> skinCutVertices;
  Plane sagittal;
  std::vector<ReferenceTissue> tissues;
  std::vector<ReferencePoint> points;

  // Throws BadInput naming `source` on an empty skin, a broken mesh, duplicate tissue names, a point on
  // an unknown tissue, a cut vertex out of range, a group whose tissues disagree on `symmetric` or are not bones, or a zero normal.
  void validate(const std::string& source) const;
};

}  // namespace vesalius
