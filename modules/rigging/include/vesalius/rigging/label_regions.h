// Nested region surfaces of a label map for TetGen (Sujar et al. 2018, §3.2: the inside of the body as one region,
// its bones nested in it), shared by `tetmesh --labels [--body]` and `rig --labels`.
//
// The body is every labelled voxel with its holes filled (air pockets such as bowel gas are inside), as
// one closed surface (optionally made solid, see LabelRegionOptions::solidBody). The chosen labels are surfaced one by one (label_surface.h) after two peels that
// keep the surfaces apart, since TetGen takes nested or disjoint surfaces but no touching ones:
// - a label voxel next to the body's outside (26-neighbourhood; the map's edge counts as outside) is
//   dropped, so a bone reaching the body surface or the scan's edge stays nested in the body;
// - a label voxel next to a voxel of another chosen label listed later is dropped, so touching labels (a
//   femoral head in its acetabulum, a vertebra on the next) are a voxel apart and the later one keeps its
//   voxels whole (rig: the distal bone, which moves rigidly as a whole).
// Deviation from Sujar et al. 2018: its bone voxels are apart by construction; it does not say how.
#pragma once

#include "vesalius/core/label_map.h"
#include "vesalius/core/progress.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/meshing/tetrahedralize.h"

#include <string>
#include <vector>

namespace vesalius::rigging {

struct LabelRegionOptions {
  int body = 0;                        // region label of the body around the labels; 0: no body region
  // A solid body: closed by three voxels before its holes are filled (a segmentation's organs leave gaps
  // and tunnels between them, handles that keep a decimated surface far above its target), then cut to its
  // largest face-connected part (parts touching at an edge or a corner are separate surface pieces; crumbs
  // give tets no bone weighs). Label voxels outside it are
  // dropped by the peel.
  bool solidBody = false;
  // The body cut to its largest face-connected part also when it is not made solid (rig --reference: a
  // finger that the voxels cut off the hand would be a shell of tets that no bone weighs).
  bool largestBodyPartOnly = false;
  meshing::SurfaceOptions bodySurface;   // how the body is surfaced (e.g. decimated)
  meshing::SurfaceOptions labelSurface;  // how each label is surfaced
  // With labelFaces > 0, the labels' surfaces share this many faces in proportion to their voxel faces
  // (triangles of about one size on all of them), at least minLabelFaces each; labelSurface.targetFaces
  // is then not used.
  long labelFaces = 0;
  int minLabelFaces = 100;
  // With labelFaces > 0 and a body: a label whose surface stays above twice its share is closed (into the
  // body's voxels of no chosen label) by one voxel, then by two, four, ... until it meets that bound or
  // the radius would pass a quarter of the label's extent; the shares stay those of the labels before
  // any closing. Decimation keeps a surface's handles (a rib cage's ribs on the spine and sternum, each a
  // loop): closing fills the tissue between them, which then is a part of the label's region.
  bool closeOverBudget = false;
  // Each label kept to its largest face-connected part after the peel (crumbs of a bone left by the peel
  // or by voxels coarser than its plates, such as ribs at 8 mm, would each be a surface of a few faces).
  bool largestPartOnly = false;
};

// The fewest triangles budgetSurfaces gives a body surface.
constexpr int kMinBodyFaces = 1000;

// Face budgets for a mesh of about targetTets tets made with TetGen's keepSurface (-Y), where the
// surfaces' own triangles set the count: a quarter of targetTets faces in all, half on the body (at least
// kMinBodyFaces), half on the labels (labelFaces, at least minLabelFaces each; see the .cpp for the
// measurements).
void budgetSurfaces(LabelRegionOptions& options, long targetTets);

// How much a rig's bone budgets grow for each retry where coarse surfaces cross (body_rig.cpp).
constexpr double kCrossingGrowth = 1.5;

// The smallest targetTets whose budget (a quarter of it in faces) holds the surfaces' floors within 2x,
// the bones' grown once where coarse surfaces cross: twice the faces of a body of bodyFaces and `labels`
// labels of kCrossingGrowth × options.minLabelFaces each. Below it the floors alone give more than twice
// the target (the test CT's 10 bone labels at 4,000 tets, their floors crossing at 100-110 faces and
// grown to 110-386: 9,104 tets).
long leastTargetTets(const LabelRegionOptions& options, std::size_t labels, long bodyFaces = kMinBodyFaces);

// The label voxels peeled as above: `labels` less its voxels next to a zero of `body` or the grid's edge
// (with body null: neither) and, for a label of rank r, next to a label of larger rank. rank: per label
// value (65536), -1 for labels not chosen (kept whole, ignored as neighbours). body: same grid as labels.
Grid<Label> peeledLabels(const Grid<Label>* body, const Grid<Label>& labels, const std::vector<int>& rank);

// Region surfaces of `ids` (in this order; empty: every label of the table) with region label = label
// id, preceded by the body's (label options.body) if options.body > 0. `source` names the map in the
// regions' names (TetGen's error messages). Throws UsageError if options.body is one of the labels,
// BadInput if the body is empty.
std::vector<meshing::RegionSurface> labelRegionSurfaces(const LabelMap& map, const std::vector<Label>& ids,
                                                        const LabelRegionOptions& options, const std::string& source,
                                                        Progress* progress = nullptr);

}  // namespace vesalius::rigging
