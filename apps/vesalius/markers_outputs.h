// What `vesalius markers` writes (docs/cli.md, docs/methods/marker-suggestions.md): the marker files of
// `sample`, `suggest` (and its placed template) and `convert`, the report's metrics and the summary lines.
#pragma once

#include "common.h"

#include "vesalius/core/grid.h"
#include "vesalius/core/markers.h"
#include "vesalius/io/report.h"
#include "vesalius/patient/marker_suggestions.h"

#include <string>

namespace vesalius::cli {

// The label a `sample` spreads markers over: its boundary within the scan (and the part cut off by the
// scan's edge), with the label's name and how the messages name it ("label 'liver' (5)").
struct SampledBoundary {
  std::string name, named;
  double area = 0, edgeArea = 0;  // mm², of the boundary within the scan and of the cap on the scan's edge
};

// The ICP markers icp-1, icp-2, … at the rows of `points` (#P by 3, LPS mm) written to `out` (`count`: the
// number asked for, which gives the ideal spacing sqrt(area / count)), then the report and the summary.
void writeSampledMarkers(const std::string& out, const MatrixX3d& points, const SampledBoundary& boundary, int count,
                         const GridGeometry& scan, const CommonOptions& common, io::Report& report);

// What `suggest` was asked to write: the suggestions' file, the placed template's (empty: none), the
// template's file (its stem names the marker set), the --polarity and --count asked for.
struct SuggestOutputs {
  std::string out, placedOut, templ, polarity;
  int count = 0;
};

// The kept edges as preview ICP markers suggested-1, suggested-2, … with their confidence in each
// description, the bent template with `placedOut`, then the report and the summary.
void writeSuggestions(const patient::MarkerSuggestions& suggested, const SuggestOutputs& outputs,
                      const GridGeometry& scan, const CommonOptions& common, io::Report& report);

// `convert`: the markers read from `in` written to `out` (geometry: the --scan's, or null), the report,
// the summary line (how many lack a position) and the fields the output's format does not keep.
void writeConvertedMarkers(const std::string& in, const std::string& out, const MarkerSet& set,
                           const GridGeometry* geometry, const CommonOptions& common, io::Report& report);

}  // namespace vesalius::cli
