// Scans and label maps on disk, read and written through ITK.
//
// Formats by extension: NIfTI (.nii, .nii.gz), NRRD (.nrrd, .nhdr; .seg.nrrd read as a label map),
// MetaImage (.mha, .mhd), a single DICOM file (.dcm or any file GDCM recognises) and a DICOM series given
// as its folder. .nhdr and .mhd keep their voxels in a data file beside the header, named after its stem.
//
// Space: geometry is ITK's physical space, LPS in mm (core/grid.h). NIfTI stores RAS; ITK converts on read
// and on write, so origin, spacing and direction — oblique ones included — survive a round trip.
// Volumes are 3-D and scalar; 2-D files read as one slice, 4-D files with one volume as 3-D.
#pragma once

#include "vesalius/core/atomic_file.h"
#include "vesalius/core/grid.h"
#include "vesalius/core/label_map.h"

#include <optional>
#include <string>
#include <vector>

namespace vesalius::io {

struct ScanReadOptions {
  // For a DICOM folder: the Series Instance UID to read (see dicom_series.h). Empty reads the folder's
  // only series; a folder with two or more series then throws BadInput listing them.
  std::string seriesUid;
};

// Reads a scan; values become float (HU for CT DICOM, rescaled by GDCM) and Image::fileType records the
// stored component type. DICOM slices are ordered by position along the slice normal.
// Throws BadInput naming the path for a missing file, an unknown extension, an unreadable or truncated
// file, a 4-D or multi-component image, invalid geometry (GridGeometry::validate) and an ambiguous or
// empty DICOM folder; UsageError if options.seriesUid names no series of the folder or is given for a file.
Image readScan(const std::string& path, const ScanReadOptions& options = {});

// Writes NIfTI, NRRD or MetaImage (by extension) with the component type image.fileType; integer types
// get values rounded and clamped to their range. Atomic and no-clobber (core/atomic_file.h); UsageError
// for other extensions.
void writeScan(const std::string& path, const Image& image, const WriteOptions& options = {});

struct ValueRange {
  double minimum = 0, maximum = 0;
};

// What `vesalius info` prints about a scan.
struct ScanInfo {
  std::string format;  // "NIfTI", "NRRD", "MetaImage", "DICOM file" or "DICOM series"
  GridGeometry geometry;
  std::string orientation;  // geometry.orientationCode(), e.g. "LPS"
  PixelType pixelType = PixelType::Float32;
  int components = 1;                    // values per voxel; > 1 for RGB or vector images
  std::optional<ValueRange> valueRange;  // of the voxel values; absent for multi-component images
};

// Describes a scan: the header alone for multi-component images (which readScan rejects), else the
// whole scan, for the value range. Throws as readScan.
ScanInfo describeScan(const std::string& path, const ScanReadOptions& options = {});

// Reads a label map (NIfTI, NRRD, MetaImage) as uint16 labels. Stored values of any type must be whole
// numbers in 0..65535 (TotalSegmentator v1 stores float64), else BadInput naming a voxel.
// The table comes from `tablePath` if given, else from the first label table found beside the file:
// `<stem>.tsv`, `<stem>.ctbl`, `<stem>.label.txt`, `<stem>.csv` if it is a Slicer colour table (a marker
// CSV is passed over), `<stem>.txt` (label_table_io.h); labels present in the image but not in the table are
// named "label_<id>" with defaultLabelColor(id).
// A 3D Slicer segmentation (.seg.nrrd) names its own segments (slicer_segmentation.h); its layers are
// merged into one map, and overlapping segments throw BadInput naming them. A DICOM file is read as a DICOM
// SEG (dicom_seg.h); any other DICOM file throws BadInput (an RT Structure Set has no grid: it is read onto
// a scan's with readDicomRtStruct, dicom_rtstruct.h).
LabelMap readLabelMap(const std::string& path, const std::string& tablePath = "");

// Writes the labels (uint8 if every id is below 256, else uint16) and the table three times beside them,
// so that 3D Slicer and ITK-SNAP find names and colours too (labelTableSidecarPaths: our TSV, a Slicer
// colour table, an ITK-SNAP label description file), all or none (writeFilesAtomically); none is written if
// any exists and !options.force.
// A path ending .seg.nrrd is written as a Slicer segmentation carrying the table itself, without sidecars;
// one ending .rtstruct.dcm as an RT Structure Set without a source series (dicom_rtstruct.h), and any other
// ending .dcm as a DICOM SEG without one (dicom_seg.h), both also without sidecars.
void writeLabelMap(const std::string& path, const LabelMap& labelMap, const WriteOptions& options = {});

// The files writeLabelMap(path) writes: the path, then its sidecar tables (none for .seg.nrrd, .dcm), so that a
// caller can write them together with other outputs (writeFilesAtomically).
std::vector<std::string> labelMapFiles(const std::string& path);

// The file that holds a label map's table: "<stem>.tsv" beside it ("seg/body.nii.gz" -> "seg/body.tsv"),
// or the path itself for a .seg.nrrd or .dcm.
std::string labelTableSidecarPath(const std::string& labelMapPath);

// Every table writeLabelMap writes beside a label map: "seg/body.nii.gz" -> "seg/body.tsv",
// "seg/body.ctbl" (3D Slicer), "seg/body.label.txt" (ITK-SNAP); none for a .seg.nrrd or .dcm.
std::vector<std::string> labelTableSidecarPaths(const std::string& labelMapPath);

}  // namespace vesalius::io
