// ICP markers suggested where a scan has an edge near a roughly placed template organ (Wang et al. 2021, §3.1,
// §4.1.1: points on the organ's boundary the fitted surface must pass through), for a radiologist to
// accept; what `vesalius markers suggest` runs (docs/methods/marker-suggestions.md).
//
// Method, in the spirit of active shape models (Cootes, Taylor, Cooper and Graham, "Active shape models —
// their training and application", CVIU 61(1), 1995, §4):
// 1. the template is placed on the targets by similarity ICP (fit::placeTemplate), then affine ICP
//    (fit::refineAffineIcp);
// 2. `rounds` rounds: `roundPoints` points spread over the template within the scan search for an edge
//    along their outward normals (segmentation::findNormalEdges) within a distance that shrinks
//    geometrically from `searchMm` to `finalSearchMm`; the template is bent onto the edges found by a
//    smooth displacement weighted by their confidence (fit::smoothDisplacement, `smoothness`);
// 3. `count · candidatesPerSuggestion` candidates spread over the bent template within the scan search
//    within `finalSearchMm` (`searchMm` without rounds);
// 4. the most confident edges are kept, each at least half of sqrt(area / count) from those kept before it
//    (area: the bent template's within the scan), then, if fewer than `count`, the most confident others.
// Deviation from the paper: one template and a membrane stand in for a trained shape model and its
// grey-level profile model, which one template cannot give.
#pragma once

#include "vesalius/core/grid.h"
#include "vesalius/core/mesh.h"
#include "vesalius/fit/initial_placement.h"
#include "vesalius/segmentation/normal_edges.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace vesalius::patient {

struct MarkerSuggestionOptions {
  int count = 100;                   // suggestions wanted
  int candidatesPerSuggestion = 8;   // candidates of the last search per suggestion
  int rounds = 4;                    // rounds of edge search and bending (0: no bending)
  int roundPoints = 1000;            // points searched in each round
  double searchMm = 8.0;             // search along each normal, both ways, in the first round
  double finalSearchMm = 3.0;        // in the last search, after bending
  double sigmaMm = 2.0;              // Gaussian blur before differentiating
  double smoothness = 1.0;           // stiffness of the bending (membrane weight per point weight)
  segmentation::EdgePolarity polarity = segmentation::EdgePolarity::Auto;
  std::uint64_t seed = 1;            // of the spread points and candidates
  std::string templateName;          // the template's file, named when it misses the scan
};

struct MarkerSuggestions {
  fit::Placement placement;          // the similarity placement (before affine ICP)
  TriMesh placed;                    // the template placed and bent onto the edges: #V by 3 LPS mm
  segmentation::NormalEdges found;   // the last search: one edge per candidate
  std::vector<std::size_t> kept;     // indices into found.edges of the suggestions, most confident first
  double area = 0;                   // mm², of the bent template within the scan
  std::vector<std::pair<std::string, double>> stageSeconds;  // "placement", "bending and edge search"
};

// scan: the scan the edges are searched in; templ: a closed template surface facing outward, any frame;
// targets: #P by 3 LPS mm points on the organ the template is placed on (at least 3). Throws
// BadInput(options.templateName, …) when the placed template has no triangle within the scan, and what
// findNormalEdges throws (UsageError) for bad search options.
MarkerSuggestions suggestMarkers(const Image& scan, const TriMesh& templ, const MatrixX3d& targets,
                                 const MarkerSuggestionOptions& options = {});

}  // namespace vesalius::patient
