#include "vesalius/patient/scan_anatomy.h"

#include "labels_with_voxels.h"

#include "vesalius/core/error.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/segmentation/label_ops.h"

#include <map>
#include <regex>
#include <set>

namespace vesalius::patient {

void classifyTissue(ReferenceTissue& tissue) {
  const std::string& n = tissue.name;
  const auto matches = [&n](const char* pattern) { return std::regex_match(n, std::regex(pattern)); };
  tissue.group.clear();
  tissue.symmetric = false;
  if (matches("(vertebrae(_.*)?|sacrum|hip_(left|right)|rib_(left|right)_.*|sternum|skull|costal_cartilages)")) {
    tissue.kind = TissueKind::Bone;
    tissue.symmetric = true;
    tissue.group = matches("vertebrae(_.*)?") ? n
                   : matches("(sacrum|hip_.*)") ? "pelvis"
                   : matches("skull") ? "skull" : "rib_cage";
  } else if (matches("(femur|humerus|scapula|clavicula|tibia|fibula|patella|radius|ulna)_.*")) {
    tissue.kind = TissueKind::Bone;
  } else if (matches("(gluteus|iliopsoas|autochthon)_.*")) {
    tissue.kind = TissueKind::Muscle;
  } else {
    tissue.kind = TissueKind::Organ;
  }
}

namespace {

const char* const kNoPairs = "no left/right pair of labels to find the sagittal plane from";

// The pairs among `names` of a name holding "left" and the same name with "right" in its place.
std::vector<std::pair<std::string, std::string>> leftRightPairs(const std::set<std::string>& names) {
  std::vector<std::pair<std::string, std::string>> pairs;
  const std::regex left("(.*)left(.*)");
  for (const std::string& name : names) {
    std::smatch m;
    if (!std::regex_match(name, m, left)) continue;
    const std::string partner = m[1].str() + "right" + m[2].str();
    if (names.count(partner)) pairs.emplace_back(name, partner);
  }
  return pairs;
}

}  // namespace

Plane sagittalPlaneOfPairs(const std::vector<ReferenceTissue>& tissues, const std::string& source) {
  std::map<std::string, Eigen::Vector3d> centroid;
  std::set<std::string> names;
  for (const ReferenceTissue& t : tissues) {
    centroid[t.name] = t.mesh.V.colwise().mean().transpose();
    names.insert(t.name);
  }
  const auto pairs = leftRightPairs(names);
  if (pairs.empty()) throw BadInput(source, kNoPairs);
  Eigen::Vector3d normal = Eigen::Vector3d::Zero(), point = Eigen::Vector3d::Zero();
  for (const auto& [left, right] : pairs) {
    normal += (centroid[left] - centroid[right]).normalized();
    point += 0.5 * (centroid[left] + centroid[right]);
  }
  return {point / double(pairs.size()), normal.normalized()};
}

std::vector<int> scanCutVertices(const TriMesh& skin, const Grid<std::uint8_t>& body) {
  const GridGeometry& g = body.geometry;
  Eigen::Array<bool, 3, 1> touchesFirst(false, false, false), touchesLast(false, false, false);
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i) {
        if (!body.at(i, j, k)) continue;
        const Eigen::Vector3i at(i, j, k);
        for (int a = 0; a < 3; ++a) touchesFirst[a] |= at[a] == 0, touchesLast[a] |= at[a] == g.size[a] - 1;
      }
  std::vector<int> cut;
  for (Eigen::Index v = 0; v < skin.V.rows(); ++v) {
    const Eigen::Vector3d index = g.worldToIndex(skin.V.row(v).transpose());
    bool isCut = false;
    for (int a = 0; a < 3; ++a)
      isCut |= (touchesFirst[a] && index[a] < -0.25) || (touchesLast[a] && index[a] > g.size[a] - 1 + 0.25);
    if (isCut) cut.push_back(int(v));
  }
  return cut;
}

TriMesh scanSkin(const Image& scan, const ScanAnatomyOptions& options, const std::string& source,
                 std::vector<int>& cutVertices) {
  segmentation::Mask body;
  try {
    body = segmentation::segmentBody(scan, options.modality);
  } catch (const BadInput& e) {
    if (!e.file().empty()) throw;
    throw BadInput(source, e.problem());
  }
  if (segmentation::countVoxels(body) == 0) throw BadInput(source, "the scan holds no body (no voxel above air)");
  meshing::SurfaceOptions surface;
  surface.targetFaces = options.skinFaces;
  TriMesh skin = meshing::labelSurface(segmentation::labelMapOf(body, {1, "body"}), 1, surface);
  skin.faceAttributes = {};
  cutVertices = scanCutVertices(skin, body);
  return skin;
}

ReferenceAnatomy scanAnatomy(const Image& scan, const LabelMap& labels, const ScanAnatomyOptions& options,
                             const std::string& scanSource, const std::string& labelsSource, Progress* progress) {
  if (labels.labels.geometry.size != scan.geometry.size)
    throw BadInput(labelsSource, "the label map's grid differs from the scan's (" + scanSource + ")");
  // Refused before the surfaces are made, which takes minutes on a large map.
  const LabelsWithVoxels withVoxels(labels);
  std::set<std::string> present;
  for (const LabelEntry& e : labels.table.entries)
    if (withVoxels.has(e.id)) present.insert(e.name);
  if (leftRightPairs(present).empty()) throw BadInput(labelsSource, kNoPairs);
  ReferenceAnatomy anatomy;
  if (progress) progress->begin("skin", "body mask and its surface");
  anatomy.skin = scanSkin(scan, options, scanSource, anatomy.skinCutVertices);
  if (progress) progress->end();
  meshing::SurfaceOptions tissueSurface;
  tissueSurface.targetFaces = options.tissueFaces;
  for (meshing::LabelSurface& s : meshing::labelSurfaces(labels, {}, tissueSurface, progress)) {
    ReferenceTissue tissue{s.name, TissueKind::Organ, "", false, std::move(s.mesh)};
    tissue.mesh.faceAttributes = {};
    classifyTissue(tissue);
    anatomy.tissues.push_back(std::move(tissue));
  }
  anatomy.sagittal = sagittalPlaneOfPairs(anatomy.tissues, labelsSource);
  return anatomy;
}

}  // namespace vesalius::patient
