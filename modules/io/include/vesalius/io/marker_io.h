// Reading and writing marker files, picking the format by extension (vesalius::fileExtension):
//   ".mrk.json"  3D Slicer markups JSON        ".fcsv"   legacy 3D Slicer fiducial CSV
//   ".csv"       plain table label,l,p,s,...   ".annot"  ITK-SNAP annotations (voxel coordinates)
// See marker_formats.h for what each format holds. Positions are LPS millimetres in memory and in every
// file we write.
#pragma once

#include "vesalius/core/atomic_file.h"
#include "vesalius/core/grid.h"
#include "vesalius/core/markers.h"

#include <string>
#include <vector>

namespace vesalius::io {

struct MarkerReadOptions {
  // Kind of markers whose file does not say (.fcsv, .annot, a markup without a kind name, ...).
  MarkerKind defaultKind = MarkerKind::Landmark;
  // Geometry of the scan the markers were picked on; required for .annot (voxel coordinates).
  const GridGeometry* scanGeometry = nullptr;
};

// Reads and validates (MarkerSet::validate) a marker file. Throws BadInput naming `path` for an unknown
// extension, an unreadable or malformed file, or a .annot file without options.scanGeometry.
MarkerSet readMarkers(const std::string& path, const MarkerReadOptions& options = {});

// Writes `set` atomically (writeAtomically). `scanGeometry` is required for .annot. Throws UsageError
// for an unknown extension, a missing geometry, or an existing file without options.force.
void writeMarkers(const std::string& path, const MarkerSet& set, const WriteOptions& options = {},
                  const GridGeometry* scanGeometry = nullptr);

// True if `path` has one of the extensions above.
bool isMarkerFile(const std::string& path);

// What of `set` a marker file at `path` has no place for (marker_formats.h), as words for a person:
// e.g. {"kinds", "template positions"} for .fcsv. Empty when the format keeps all that `set` holds or
// the extension is unknown.
std::vector<std::string> markerFieldsNotKept(const std::string& path, const MarkerSet& set);

}  // namespace vesalius::io
