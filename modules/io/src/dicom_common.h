// What the DICOM writers and readers built on DCMTK share (dicom_seg.cpp, dicom_rtstruct.cpp): DCMTK's log
// silenced, its conditions turned into BadInput, decimal strings, the attributes copied from a source
// series, the source image at a slice, and a saved file checked to be whole. Private to io.
#pragma once

#include "vesalius/core/grid.h"
#include "vesalius/core/label_map.h"
#include "vesalius/io/dicom_seg.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcitem.h>

#include <Eigen/Core>

#include <optional>
#include <string>

namespace vesalius::io::dicom {

// Silences DCMTK's own log (once per process), so a problem reaches the user once, as a BadInput.
void quietDcmtk();

// Throws BadInput(path, what + ": " + DCMTK's reason) if `condition` is bad.
void check(const OFCondition& condition, const std::string& path, const std::string& what);

// The element's value (all of them, backslash-separated), "" if absent.
std::string text(DcmItem& item, const DcmTagKey& tag);

// A decimal string (DS, PS3.5 6.2: at most 16 characters) holding the most digits that fit.
std::string decimal(double value);

// Image Position (Patient), LPS mm, where the item has one.
std::optional<Eigen::Vector3d> imagePosition(DcmItem& item);

// Patient, study, series and frame of reference attributes of a dataset; no images.
DicomSourceSeries sourceAttributes(DcmItem& data);

// Loads a DICOM file (its header elements only unless `withPixels`); BadInput naming `path` if it is not
// one or its elements run past its end.
void loadDicom(DcmFileFormat& file, const std::string& path, bool withPixels);

// The SOP Class UID of the dataset, else of the file meta header.
std::string sopClassOf(DcmFileFormat& file);

// True if `path` is a regular file, named .dcm or with the DICOM Part 10 preamble ("DICM" at byte 128),
// whose SOP Class is `sopClass`. Any other file costs the 132 bytes of the preamble check; a folder nothing.
bool isDicomFileOfClass(const std::string& path, const std::string& sopClass);

// "label <id>": the description that keeps a label's id where DICOM numbers its segments or ROIs 1, 2, ...
std::string labelDescription(Label id);
// The id in such a description; 0 for any other text or an id outside 1..65535.
Label labelOfDescription(const std::string& description);

// A fresh UID under DCMTK's site root.
std::string newUid();

// The source image at slice k of `g`: nearest along the slice normal, within a quarter slice. None when
// there is no source or it has no Series Instance UID (an anonymised series): DICOM objects list the
// images they refer to under their series, so they cannot name them.
const DicomSourceImage* sourceImageAt(const DicomSourceSeries* source, const GridGeometry& g, int k);

// Saves `file` to `path` in `syntax` and checks that its length is what DCMTK says it wrote (a full disk
// can cut a file without DCMTK noticing). Errors name `reportedPath` and `what`.
void saveWhole(DcmFileFormat& file, E_TransferSyntax syntax, const std::string& path, const std::string& reportedPath,
               const std::string& what);

}  // namespace vesalius::io::dicom
