// DICOM Segmentation objects (DICOM PS3.3 A.51 Segmentation IOD; C.8.20 Segmentation Series and
// Segmentation Image modules; frame geometry in the Plane Position, Plane Orientation and Pixel Measures
// functional groups, C.7.6.16.2), written and read through DCMTK's dcmseg, so a label map can go to PACS.
//
// Written: a binary SEG (1 bit per pixel, Explicit VR Little Endian), one segment per label present, in
// ascending id order. Per segment: Segment Label = the table's name ("label_<id>" if unlisted), Segment
// Description "label <id>" (segment numbers must run 1, 2, ...; the description keeps the id), Recommended
// Display CIELab Value = the table's colour (sRGB → CIELab, D65), algorithm type AUTOMATIC named
// "Vesalius", and Segmented Property Category and Type both SCT 85756007 "Tissue": a generic code from
// CID 7150/7151 (3D Slicer's default for a segment), since a table's free-text name maps to no code.
// Frames: one per segment and slice where the segment has voxels, and an empty frame of the first segment on
// the grid's first and last slices when no segment reaches them, so the frames span the whole grid. Each
// frame has its Image Position (Patient) and Frame Content (dimension indices: segment number, slice);
// Image Orientation (Patient), Pixel Spacing, Slice Thickness and Spacing Between Slices are shared. Grid
// axis i is a DICOM row (Columns = size i), j a column; positions are LPS mm, which DICOM's patient space is.
//
// With a source series (the scan was a DICOM series): the SEG takes the source's Study Instance UID,
// Frame of Reference UID, patient and study attributes, lists the source's instances in the Referenced
// Series Sequence (Common Instance Reference module) and gives each frame a Derivation Image functional
// group referring to the source slice at its position (nearest along the slice normal, within a quarter of
// a slice). A source without a Series Instance UID (anonymised) gives its frame of reference and patient
// only, as its images cannot be listed under a series; one without a Study Instance UID, a new study.
// Without a source: a new study, series and frame of reference.
#pragma once

#include "vesalius/core/atomic_file.h"
#include "vesalius/core/label_map.h"

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace vesalius::io {

// One image of the series a segmentation was made from.
struct DicomSourceImage {
  std::string sopClassUid, sopInstanceUid;
  std::optional<Eigen::Vector3d> position;  // Image Position (Patient), LPS mm, where known
};

// What a SEG copies from the series it was made from.
struct DicomSourceSeries {
  std::string studyInstanceUid, seriesInstanceUid, frameOfReferenceUid;
  std::string patientName, patientId, patientBirthDate, patientSex;
  std::string studyDate, studyTime, studyId, accessionNumber, referringPhysicianName, studyDescription;
  std::vector<DicomSourceImage> images;
};

// True for an output path ending ".dcm" (any case) but not ".rtstruct.dcm" (dicom_rtstruct.h): label maps
// written there are DICOM SEG objects.
bool isDicomSegPath(const std::string& path);

// True if `path` is a readable DICOM file (named .dcm, or with the DICOM preamble) whose SOP Class is
// Segmentation Storage.
bool isDicomSegFile(const std::string& path);

// The series a scan or segmentation at `path` comes from: for a DICOM folder, the series readScan reads
// (`seriesUid`, or the folder's only series); for a DICOM image file, its own series; for a DICOM SEG, the
// series it refers to. nullopt for any other file. Throws BadInput naming `path` for unreadable DICOM, a
// folder without DICOM series or with several and no `seriesUid`; UsageError if `seriesUid` names none.
std::optional<DicomSourceSeries> readDicomSource(const std::string& path, const std::string& seriesUid = "");

// Writes `labelMap` as a binary DICOM SEG (see above), atomically and no-clobber (core/atomic_file.h).
// `source` may be null. Throws BadInput naming `path` for a map without labels, a grid whose i and j
// axes are not perpendicular or longer than 65535 voxels, and DCMTK failures.
void writeDicomSeg(const std::string& path, const LabelMap& labelMap, const DicomSourceSeries* source,
                   const WriteOptions& options = {});

struct DicomSegmentation {
  LabelMap labelMap;
  std::optional<DicomSourceSeries> source;  // absent if the SEG refers to no series
};

// Reads a binary DICOM SEG. Segment ids come from a description "label <id>" (as written above), else the
// segment number; names from Segment Label; colours from the CIELab value (else defaultLabelColor).
// The grid: i along the rows' direction, j the columns', k from the first to the last frame position
// along the slice normal, spaced by the frames' step. References (study, frame of reference, series,
// instances, with the positions of the frames derived from them) go into `source`.
// Throws BadInput naming `path` for a truncated or non-DICOM file, another SOP class, a fractional SEG,
// frames that differ in orientation or do not lie on one grid, and overlapping segments.
DicomSegmentation readDicomSeg(const std::string& path);

}  // namespace vesalius::io
