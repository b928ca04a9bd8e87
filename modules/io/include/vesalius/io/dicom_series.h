// The DICOM series a folder holds, so a user can choose one (readScan reads a folder through
// ScanReadOptions::seriesUid, image_io.h).
#pragma once

#include <string>
#include <vector>

namespace vesalius::io {

struct DicomSeries {
  std::string uid;          // Series Instance UID (0020,000E)
  int sliceCount = 0;       // files of the series in the folder
  std::string description;  // Series Description (0008,103E), may be empty
  std::string modality;     // Modality (0008,0060), e.g. "CT", may be empty
};

// Series found directly in `folder` (not in subfolders), in the order GDCM lists them; files that are not
// DICOM are ignored. Throws BadInput naming `folder` if it cannot be scanned.
std::vector<DicomSeries> listDicomSeries(const std::string& folder);

}  // namespace vesalius::io
