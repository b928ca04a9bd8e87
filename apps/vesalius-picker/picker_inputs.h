// Everything the picker reads before it opens a window, each failure a one-line BadInput naming the file.
#pragma once

#include "picker_options.h"

#include "vesalius/core/label_map.h"
#include "vesalius/core/markers.h"
#include "vesalius/core/mesh.h"

#include <string>
#include <vector>

namespace vesalius::picker {

// Appends one undefined landmark per name in `path` (one name a line; blank lines and lines starting
// with '#' are skipped) unless a landmark of that label is already in `markers`.
void addNamedLandmarks(MarkerSet& markers, const std::string& path);

// The markers to start from: the autosave sidecar when it is newer than the markers input and the
// restore policy (or the user, for "ask") says so, else the markers input, else none. `restored` tells
// which happened.
MarkerSet initialMarkers(const PickerOptions& options, const std::string& autosavePath, bool& restored);

// A surface mesh, or the boundary of a tetrahedral one, for an overlay.
TriMesh readOverlaySurface(const std::string& path);

}  // namespace vesalius::picker
