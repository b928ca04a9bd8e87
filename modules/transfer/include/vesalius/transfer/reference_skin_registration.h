// A reference anatomy's skin registered onto a target body's skin, as `vesalius transfer` does it
// (Dicko et al. 2013, §4): ICP with shape matching (skin_registration.h), after the articulated stage
// (articulated_registration.h: the skin cut into parts by its bones, limbs turned about their joints)
// unless options.articulated is false; landmarks, if any, are §4's optional manual initialisation.
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/mesh.h"
#include "vesalius/transfer/articulated_registration.h"
#include "vesalius/transfer/skin_registration.h"

#include <vector>

namespace vesalius::transfer {

struct ReferenceSkinRegistrationOptions {
  ArticulatedRegistrationOptions registration;  // .registration alone when not articulated
  bool articulated = true;
};

// Vt: #Vt by 3, Ft: #Ft by 3, the target skin (mm, LPS); parts: skinPartsFromBones(reference), unused when
// not articulated. Throws as registerSkin and registerSkinArticulated do.
SkinRegistration registerReferenceSkin(const ReferenceAnatomy& reference, const SkinParts& parts, const MatrixX3d& Vt,
                                       const MatrixX3i& Ft, const ReferenceSkinRegistrationOptions& options = {},
                                       const std::vector<SkinLandmark>& landmarks = {});

// Landmarks for the registration from point pairs (#L by 3 each, row i of `onSkin` paired with row i of
// `onTarget`): each point on the skin taken as the vertex of V (#V by 3) nearest to it (the first of equals).
std::vector<SkinLandmark> landmarksAtNearestVertices(const MatrixX3d& V, const MatrixX3d& onSkin,
                                                     const MatrixX3d& onTarget);

}  // namespace vesalius::transfer
