#include "vesalius/patient/transfer_into_body.h"

#include "vesalius/core/error.h"
#include "vesalius/core/stage_clock.h"
#include "vesalius/fat/erode_skin.h"
#include "vesalius/meshing/mesh_volume.h"
#include "vesalius/transfer/skin_registration.h"


namespace vesalius::patient {
namespace {

// No fat where the scan's field of view cut the body: those vertices are not skin.
Eigen::VectorXd withoutCut(const ReferenceAnatomy& reference, Eigen::VectorXd thickness) {
  for (const int v : reference.skinCutVertices) thickness[v] = 0;
  return thickness;
}

// The grid of the displacement field: it covers the reference skin and every tissue.
GridGeometry fieldGrid(const ReferenceAnatomy& reference, double voxelSize) {
  std::vector<const TriMesh*> meshes{&reference.skin};
  for (const ReferenceTissue& t : reference.tissues) meshes.push_back(&t.mesh);
  meshing::CoveringGridOptions grid;
  grid.voxelSizeMm = voxelSize;
  grid.marginMm = 3 * voxelSize;
  grid.maxSize = Eigen::Vector3i(400, 400, 800);
  return meshing::coveringGrid(meshes, grid);
}

transfer::SkinRegistration registerOnto(const ReferenceAnatomy& reference, const transfer::SkinParts& parts,
                                        const MatrixX3d& Vt, const MatrixX3i& Ft, const TransferIntoBodyOptions& o) {
  if (!o.articulated)
    return transfer::registerSkin(reference.skin.V, reference.skin.F, Vt, Ft, o.registration.registration);
  return transfer::registerSkinArticulated(reference.skin.V, reference.skin.F, parts, Vt, Ft, o.registration).registration;
}

ReferenceAnatomy transferredAnatomy(const ReferenceAnatomy& reference, const transfer::TransferredAnatomy& result,
                                    const MatrixX3d& targetSkin) {
  ReferenceAnatomy out = reference;
  out.name = "transferred from " + reference.name;
  out.skin.V = targetSkin;
  out.sagittal = result.sagittal;
  for (std::size_t t = 0; t < out.tissues.size(); ++t) out.tissues[t].mesh.V = result.tissues[t];
  for (std::size_t p = 0; p < out.points.size(); ++p) out.points[p].position = result.points.row(Eigen::Index(p)).transpose();
  return out;
}

}  // namespace

TransferIntoBody transferIntoBody(const ReferenceAnatomy& reference, const MatrixX3d& registeredSkin,
                                  const Eigen::VectorXd& fatThickness, const transfer::SkinParts& parts,
                                  const TransferIntoBodyOptions& options, Progress* progress) {
  if (registeredSkin.rows() != reference.skin.V.rows() || fatThickness.size() != reference.skin.V.rows())
    throw BadInput("", "transfer: the registered skin and the fat need one row per reference skin vertex");
  if (!registeredSkin.allFinite() || !fatThickness.allFinite())
    throw BadInput("", "transfer: the registered skin or the fat is not finite");
  TransferIntoBody r;
  StageClock clock(r.stageSeconds);
  r.erodedSkin = registeredSkin;
  r.eroded = fatThickness.size() > 0 && fatThickness.maxCoeff() > 0;
  if (r.eroded) {
    const fat::ErodedSkin e = fat::erodeSkin(registeredSkin, reference.skin.F, withoutCut(reference, fatThickness));
    r.erodedSkin = e.V;
    r.erosionMeanMm = e.meanDisplacement;
    r.erosionLimited = long(e.limited);
    r.erosionNewSelfIntersections = long(e.newSelfIntersections);
    clock.end("erosion");
    const transfer::SkinRegistration subFat = registerOnto(reference, parts, r.erodedSkin, reference.skin.F, options);
    r.subFatMeanDistanceMm = subFat.finalMeanDistance;
    r.subFatScale = subFat.alignment.scale;
    r.erodedSkin = subFat.V;
    clock.end("sub-fat registration");
  }

  if (progress) progress->begin("transfer", "interpolation, bone registration, final interpolation");
  r.grid = fieldGrid(reference, options.voxelSizeMm);
  const Grid<std::uint8_t> inside = meshing::meshInsideMask(reference.skin, r.grid);
  clock.end("inside mask");
  // Rule R6 in the bone registration: bones are kept inside the eroded skin, and as deep as they were in
  // the reference's.
  TriMesh erodedMesh = reference.skin;
  erodedMesh.V = r.erodedSkin;
  r.erodedBody = meshing::bodySignedDistance(erodedMesh);
  clock.end("eroded skin distance");
  r.referenceBody = meshing::bodySignedDistance(reference.skin);
  clock.end("reference skin distance");
  transfer::AnatomyTransferOptions transferOptions = options.transfer;
  transferOptions.targetSkinDistance = &r.erodedBody.signedDistance;
  transferOptions.referenceSkinDistance = &r.referenceBody.signedDistance;
  r.transferred = transfer::transferAnatomy(reference, r.erodedSkin, inside, transferOptions);
  if (progress) progress->end();
  r.stageSeconds.emplace_back("skin field", r.transferred.secondsSkinField);
  r.stageSeconds.emplace_back("bone registration", r.transferred.secondsBones);
  r.stageSeconds.emplace_back("final field", r.transferred.secondsFinalField);
  r.anatomy = transferredAnatomy(reference, r.transferred, registeredSkin);
  return r;
}

}  // namespace vesalius::patient
