#include "vesalius/rigging/label_regions.h"

#include "vesalius/core/error.h"
#include "vesalius/core/label_boxes.h"
#include "vesalius/meshing/decimate_surface.h"
#include "vesalius/segmentation/label_ops.h"

#include <algorithm>
#include <map>
#include <optional>

namespace vesalius::rigging {

// With no points added on the surfaces (-Y) and TetGen's radius-edge bound 1.5, the tets are those the
// surface triangles need, about 3-4 per surface face when each surface meets its budget (rig --labels of
// the test CT: 3.3-3.5 tets per face over 6,000-7,700 faces; rig --reference at 8 mm: 3.1 at 2,900 faces).
// The volume bound barely changes the count (docs/methods/tetrahedral-meshes.md), so the face budget is
// what sets it: a quarter of the target, so that the count stays within 2x of it where a surface stops
// above its budget (where its handles need more triangles). Larger budgets grow
// faster than linearly: with surfaces a voxel apart, the smaller triangles make TetGen refine the gaps
// (rig --reference at 8 mm with 6,100 faces: 6.5 tets per face).
void budgetSurfaces(LabelRegionOptions& options, long targetTets) {
  const long faces = targetTets / 4;
  options.bodySurface.targetFaces = int(std::max<long>(kMinBodyFaces, faces / 2));
  options.labelFaces = std::max<long>(1, faces / 2);
}

long leastTargetTets(const LabelRegionOptions& options, std::size_t labels, long bodyFaces) {
  return long(2 * (double(bodyFaces) + kCrossingGrowth * double(labels) * options.minLabelFaces));
}

Grid<Label> peeledLabels(const Grid<Label>* body, const Grid<Label>& labels, const std::vector<int>& rank) {
  Grid<Label> peeled = labels;
  const auto& n = labels.geometry.size;
  // Whether the 26-neighbour (i, j, k) of a voxel of rank r makes it give way: outside, or a later label.
  auto yields = [&](int i, int j, int k, int r) {
    if (i < 0 || j < 0 || k < 0 || i >= n.x() || j >= n.y() || k >= n.z()) return body != nullptr;
    if (body && body->at(i, j, k) == 0) return true;
    return r >= 0 && rank[labels.at(i, j, k)] > r;
  };
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i) {
        const Label l = labels.at(i, j, k);
        for (int d = 0; d < 27 && l != 0 && peeled.at(i, j, k) != 0; ++d)
          if (yields(i + d % 3 - 1, j + d / 3 % 3 - 1, k + d / 9 - 1, rank[l])) peeled.at(i, j, k) = 0;
      }
  return peeled;
}

namespace {

// Per label value, its voxels' faces towards another value or the grid's edge.
std::vector<long> voxelFacesOfLabels(const Grid<Label>& labels) {
  std::vector<long> faces(65536, 0);
  const Eigen::Vector3i& n = labels.geometry.size;
  const int step[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i) {
        const Label l = labels.at(i, j, k);
        if (l == 0) continue;
        for (const auto& d : step) {
          const int a = i + d[0], b = j + d[1], c = k + d[2];
          if (!labels.geometry.contains(a, b, c) || labels.at(a, b, c) != l) ++faces[l];
        }
      }
  return faces;
}

// Voxels of `id` outside its largest face-connected part set to 0.
void keepLargestPart(Grid<Label>& labels, Label id) {
  const segmentation::Mask mask = segmentation::maskOf(labels, id);
  const segmentation::Mask kept = segmentation::largestComponent(mask, segmentation::Connectivity::Face);
  for (std::size_t v = 0; v < labels.values.size(); ++v)
    if (mask.values[v] && !kept.values[v]) labels.values[v] = 0;
}

// Per label value (65536), its share of options.labelFaces among `ids` in proportion to its voxel faces,
// at least options.minLabelFaces; 0 for a label without voxels (see LabelRegionOptions).
std::vector<long> labelShares(const Grid<Label>& labels, const std::vector<Label>& ids,
                              const LabelRegionOptions& options) {
  const std::vector<long> faces = voxelFacesOfLabels(labels);
  long total = 0;
  for (Label id : ids) total += faces[id];
  std::vector<long> shares(65536, 0);
  for (Label id : ids)
    if (faces[id] > 0) shares[id] = std::max<long>(options.minLabelFaces, options.labelFaces * faces[id] / total);
  return shares;
}

// Per label value (65536), the diagonal of its voxels' bounding box, mm.
std::vector<double> labelExtents(const Grid<Label>& labels) {
  const std::vector<LabelBox> boxes = labelBoxes(labels);
  std::vector<double> extent(65536, 0.0);
  for (std::size_t l = 0; l < boxes.size(); ++l)
    if (boxes[l].voxels > 0)
      extent[l] = (boxes[l].hi - boxes[l].lo + Eigen::Vector3i::Ones()).cast<double>().cwiseProduct(labels.geometry.spacing).norm();
  return extent;
}

// `map` with each label of closing[id] > 0 closed by that radius (mm) into the voxels of `inside` that
// carry no chosen label (rank -1).
Grid<Label> closedLabels(const Grid<Label>& map, const segmentation::Mask& inside, const std::vector<int>& rank,
                         const std::vector<double>& closing) {
  Grid<Label> closed = map;
  for (std::size_t id = 0; id < closing.size(); ++id) {
    if (closing[id] <= 0) continue;
    const segmentation::Mask grown = segmentation::closeMm(segmentation::maskOf(map, Label(id)), closing[id]);
    for (std::size_t v = 0; v < grown.values.size(); ++v)
      if (grown.values[v] && inside.values[v] && rank[map.values[v]] < 0) closed.values[v] = Label(id);
  }
  return closed;
}

// Surfaces decimated one by one can cross where they lie a voxel apart (a coarse body over the bones under
// it). They are then made again undecimated and decimated together to the faces each has, with no
// collapse letting one meet another (decimateSurfacesApart). regions: the body's first when `body` is given,
// then one per id of `ids` (labels of `peeled`).
void decimateApart(std::vector<meshing::RegionSurface>& regions, const LabelMap* body, const LabelMap& peeled,
                   const std::vector<Label>& ids, const LabelRegionOptions& options) {
  std::vector<TriMesh> fine;
  meshing::SurfaceOptions undecimated = options.bodySurface;
  undecimated.targetFaces = 0;
  if (body) fine.push_back(meshing::labelSurface(*body, 1, undecimated));
  undecimated = options.labelSurface;
  undecimated.targetFaces = 0;
  for (meshing::LabelSurface& s : meshing::labelSurfaces(peeled, ids, undecimated)) fine.push_back(std::move(s.mesh));
  std::vector<const TriMesh*> surfaces;
  std::vector<int> targets;
  for (std::size_t i = 0; i < fine.size(); ++i) {
    surfaces.push_back(&fine[i]);
    targets.push_back(int(regions[i].surface.F.rows()));
  }
  std::vector<TriMesh> apart = meshing::decimateSurfacesApart(surfaces, targets);
  for (std::size_t i = 0; i < apart.size(); ++i) {
    // A label's surface carries its id on every triangle (label_surface.h).
    const auto id = fine[i].faceAttributes.integer.find(kLabel);
    if (id != fine[i].faceAttributes.integer.end() && id->second.size() > 0)
      apart[i].faceAttributes.integer[kLabel] = Eigen::VectorXi::Constant(apart[i].F.rows(), id->second[0]);
    regions[i].surface = std::move(apart[i]);
  }
}

}  // namespace

std::vector<meshing::RegionSurface> labelRegionSurfaces(const LabelMap& map, const std::vector<Label>& ids,
                                                        const LabelRegionOptions& options, const std::string& source,
                                                        Progress* progress) {
  if (options.body > 0 && std::find(ids.begin(), ids.end(), Label(options.body)) != ids.end())
    throw UsageError("the body's label " + std::to_string(options.body) + " is one of the chosen labels");
  std::vector<int> rank(65536, -1);
  for (std::size_t r = 0; r < ids.size(); ++r) rank[ids[r]] = int(r);
  if (ids.empty())
    for (std::size_t l = 1; l < rank.size(); ++l) rank[l] = int(l);
  std::vector<meshing::RegionSurface> regions;
  std::optional<LabelMap> body;
  if (options.body > 0) {
    const double voxel = map.labels.geometry.spacing.maxCoeff();
    segmentation::Mask inside = segmentation::nonZeroMask(map.labels);
    if (options.solidBody) inside = segmentation::closeMm(inside, 3 * voxel);
    inside = segmentation::fillBodyHoles(inside);
    if (options.solidBody || options.largestBodyPartOnly)
      inside = segmentation::largestComponent(inside, segmentation::Connectivity::Face);
    body = segmentation::labelMapOf(inside, {1, "body"});
    regions.push_back({meshing::labelSurface(*body, 1, options.bodySurface), options.body,
                       source + " body (all labels, holes filled)"});
  }
  const auto peel = [&](const Grid<Label>& labels) {
    LabelMap peeled = map;
    peeled.labels = peeledLabels(body ? &body->labels : nullptr, labels, rank);
    if (options.largestPartOnly)
      for (Label id : ids) keepLargestPart(peeled.labels, id);
    return peeled;
  };
  std::vector<meshing::LabelSurface> surfaces;
  LabelMap peeled;  // the labels that the surfaces are of
  if (options.labelFaces <= 0 || ids.empty()) {
    peeled = peel(map.labels);
    surfaces = meshing::labelSurfaces(peeled, ids, options.labelSurface, progress);
  } else {
    // LabelRegionOptions::closeOverBudget: the radius doubles from a voxel while a label's surface stays
    // above twice its budget, up to a quarter of the label's extent (a hand's bones, scattered and each
    // a closed surface, would otherwise be closed into the whole arm).
    const std::vector<double> extent = labelExtents(map.labels);
    const double voxel = map.labels.geometry.spacing.maxCoeff();
    // The shares are those of the labels as they are, and a label whose voxels a round left as they were
    // keeps its surface.
    std::vector<double> closing(65536, 0.0);
    std::vector<long> shares;
    std::map<Label, meshing::LabelSurface> budgeted;
    Grid<Label> previous;
    for (;;) {
      peeled = peel(body ? closedLabels(map.labels, segmentation::maskOf(body->labels, 1), rank, closing) : map.labels);
      std::vector<bool> changed(65536, shares.empty());
      if (shares.empty()) {
        shares = labelShares(peeled.labels, ids, options);
      } else {
        for (std::size_t v = 0; v < previous.values.size(); ++v)
          if (previous.values[v] != peeled.labels.values[v])
            changed[previous.values[v]] = changed[peeled.labels.values[v]] = true;
      }
      for (Label id : ids) {
        if (!changed[id] || shares[id] == 0) continue;
        budgeted.erase(id);
        meshing::SurfaceOptions surface = options.labelSurface;
        surface.targetFaces = int(shares[id]);
        for (meshing::LabelSurface& s : meshing::labelSurfaces(peeled, {id}, surface))
          budgeted.emplace(id, std::move(s));
      }
      previous = peeled.labels;
      bool again = false;
      for (const auto& [id, s] : budgeted) {
        double& r = closing[id];
        const double wider = 2 * std::max(r, voxel / 2);
        if (!options.closeOverBudget || !body || s.mesh.F.rows() <= 2 * shares[id] || wider > extent[id] / 4)
          continue;
        r = wider;
        again = true;
      }
      if (!again) break;
    }
    for (Label id : ids)
      if (auto found = budgeted.find(id); found != budgeted.end()) surfaces.push_back(std::move(found->second));
  }
  std::vector<Label> regionIds;
  for (meshing::LabelSurface& s : surfaces) {
    regions.push_back({std::move(s.mesh), int(s.id), source + " label '" + s.name + "'"});
    regionIds.push_back(s.id);
  }
  if (meshing::surfacesCross(regions)) decimateApart(regions, body ? &*body : nullptr, peeled, regionIds, options);
  return regions;
}

}  // namespace vesalius::rigging
