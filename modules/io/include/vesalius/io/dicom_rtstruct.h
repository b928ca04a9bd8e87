// DICOM RT Structure Sets (DICOM PS3.3 A.19 RT Structure Set IOD; C.8.8.5 Structure Set, C.8.8.6 ROI
// Contour and C.8.8.8 RT ROI Observations modules), written and read through DCMTK's dcmrt, so a label map
// can go to a radiotherapy planning system. An RT Structure Set holds contours in patient space and no
// grid of its own: it is read back onto a grid the caller gives (the scan's).
//
// Written: Implicit VR Little Endian (PS3.5 A.1: every DICOM reader takes it; in Explicit VR, Contour Data
// could not hold a contour longer than some 1500 points), one ROI per label present, in ascending id order. Per ROI: ROI Number 1, 2, ... (Structure Set
// ROI Sequence), ROI Name = the table's name ("label_<id>" if unlisted), ROI Description "label <id>" (the
// numbers must run 1, 2, ...; the description keeps the id, as a DICOM SEG's segment description does),
// ROI Display Color = the table's colour, one RT ROI Observations item with an empty interpreted type
// (a table's free-text name says nothing of whether a label is an organ, a target or an external).
// Contours: CLOSED_PLANAR polygons, LPS mm (DICOM's patient space), on the plane through the voxel
// centres of each slice k where the label has voxels. They trace the voxel boundaries of the label's mask
// on that slice (the lines between voxel centres' cells, at half-integer i and j): one polygon per closed
// boundary, so a region with a hole gives its outer boundary and a separate polygon around the hole.
// RTSTRUCT has no hole flag; a slice's polygons of one ROI are meant by the even-odd rule (a point is
// inside when it is within an odd number of them), which most planning systems apply. Outer boundaries
// run counter-clockwise and holes clockwise in the (i, j) index plane, for readers that go by winding.
// Where two regions of the mask touch only at a corner, the boundary is traced as two polygons meeting
// there. Polygons keep only their corners (collinear boundary points are dropped).
//
// With a source series (the scan was a DICOM series, dicom_seg.h's readDicomSource): the structure set
// takes the source's Study Instance UID, Frame of Reference UID, patient and study attributes; its
// Referenced Frame of Reference Sequence lists the source's study, series and every image (RT Referenced
// Study and Series Sequences, Contour Image Sequence), and each contour's Contour Image Sequence names
// the source image on its slice (nearest along the slice normal, within a quarter slice). A source
// without a Series Instance UID (anonymised) gives its frame of reference and patient only; one without a
// Study Instance UID, a new study. Without a source: a new study, series and frame of reference.
//
// Read: each ROI's CLOSED_PLANAR contours, rasterized per slice of the grid by the even-odd rule (a voxel
// is the ROI's when its centre lies inside an odd number of the ROI's polygons on its slice). POINT
// contours enclose nothing and are skipped. Ids from descriptions "label <id>" when every ROI has a distinct
// one, else the ROI Numbers; names from ROI Name; colours from ROI Display Color (else defaultLabelColor).
// Where ROIs overlap (an external contour around the organs, as planning systems keep), a voxel goes to the
// ROI with the fewest voxels, so the organs inside an outline keep theirs; ties go to the earlier ROI.
#pragma once

#include "vesalius/core/atomic_file.h"
#include "vesalius/core/grid.h"
#include "vesalius/core/label_map.h"
#include "vesalius/io/dicom_seg.h"

#include <string>

namespace vesalius::io {

// True for a path ending ".rtstruct.dcm" (any case): label maps written there are RT Structure Sets.
bool isDicomRtStructPath(const std::string& path);

// True if `path` is a regular file holding a DICOM RT Structure Set, whatever its name (PACS exports often
// have none or ".IMA"): a file named .dcm, or one with the DICOM Part 10 preamble ("DICM" at byte 128),
// whose SOP Class is RT Structure Set Storage. Other files cost the 132 bytes of the preamble check only;
// folders are not opened.
bool isDicomRtStructFile(const std::string& path);

// Writes `labelMap` as an RT Structure Set (see above), atomically and no-clobber (core/atomic_file.h).
// `source` may be null. Throws BadInput naming `path` for a map without labels and DCMTK failures.
void writeDicomRtStruct(const std::string& path, const LabelMap& labelMap, const DicomSourceSeries* source,
                        const WriteOptions& options = {});

// Reads an RT Structure Set onto `grid` (see above). Every contour must lie on the plane of one of the
// grid's slices, within a quarter slice. Throws BadInput naming `path` for a truncated or non-DICOM file,
// another SOP class, a structure set without ROIs, a contour of another type than CLOSED_PLANAR or POINT,
// with fewer than three points, not planar (a point more than 0.02 mm off the contour's plane), or off
// every slice of the grid.
LabelMap readDicomRtStruct(const std::string& path, const GridGeometry& grid);

// Reads an RT Structure Set onto the grid of the scan at `scanPath` (any scan describeScan reads,
// image_io.h), with an explicit table as readLabelMap takes one for a DICOM SEG: the table at `tablePath`,
// if given, replaces the ROIs' names and colours whole, and labels present that it leaves out are named
// "label_<id>".
// Frame of reference: a scan that has a Frame of Reference UID (a DICOM series or image) must be in every
// frame of reference the structure set's ROIs refer to (their Referenced Frame of Reference UIDs, else
// those of its Referenced Frame of Reference Sequence): contours in another frame are in another patient
// space and would fill the wrong voxels without any other sign of it. A NIfTI, NRRD or MetaImage scan has
// no such UID; its grid is taken to be in the structure set's patient space, as is a structure set that
// names no frame. Throws BadInput naming both files and both UIDs when the frames differ, and as
// readDicomRtStruct, describeScan, readDicomSource (dicom_seg.h) and readLabelTable (label_table_io.h).
LabelMap readDicomRtStructOntoScan(const std::string& path, const std::string& scanPath,
                                   const std::string& tablePath = "");

}  // namespace vesalius::io
