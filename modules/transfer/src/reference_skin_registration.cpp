#include "vesalius/transfer/reference_skin_registration.h"

#include "vesalius/core/error.h"

namespace vesalius::transfer {

SkinRegistration registerReferenceSkin(const ReferenceAnatomy& reference, const SkinParts& parts, const MatrixX3d& Vt,
                                       const MatrixX3i& Ft, const ReferenceSkinRegistrationOptions& options,
                                       const std::vector<SkinLandmark>& landmarks) {
  if (!options.articulated)
    return registerSkin(reference.skin.V, reference.skin.F, Vt, Ft, options.registration.registration, landmarks);
  return registerSkinArticulated(reference.skin.V, reference.skin.F, parts, Vt, Ft, options.registration, landmarks)
      .registration;
}

std::vector<SkinLandmark> landmarksAtNearestVertices(const MatrixX3d& V, const MatrixX3d& onSkin,
                                                     const MatrixX3d& onTarget) {
  if (onSkin.rows() != onTarget.rows())
    throw UsageError("landmarks: " + std::to_string(onSkin.rows()) + " points on the skin and " +
                     std::to_string(onTarget.rows()) + " on the target");
  if (V.rows() == 0 && onSkin.rows() > 0) throw UsageError("landmarks: the skin has no vertices");
  std::vector<SkinLandmark> landmarks;
  for (Eigen::Index p = 0; p < onSkin.rows(); ++p) {
    Eigen::Index vertex = 0;
    (V.rowwise() - onSkin.row(p)).rowwise().squaredNorm().minCoeff(&vertex);
    landmarks.push_back({int(vertex), onTarget.row(p).transpose()});
  }
  return landmarks;
}

}  // namespace vesalius::transfer
