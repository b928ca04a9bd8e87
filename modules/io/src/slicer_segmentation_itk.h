// The plain-data seam for 3D Slicer segmentation files (.seg.nrrd): their voxels and key-value fields read
// and written through ITK's NRRD IO. Nothing here may include Eigen or ITK headers (image_io_itk.h says why).
#pragma once

#include "image_io_itk.h"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace vesalius::io::itk_seam {

struct RawSegmentationFile {
  RawHeader header;  // header.components = layers (1 for a 3-D file, N for a 4-D "list" axis of N layers)
  std::vector<std::pair<std::string, std::string>> fields;  // the "key:=value" fields whose key starts "Segment"
  std::vector<std::uint16_t> values;  // voxel-major, layer fastest: values[voxel * layers + layer]
};

// Reads a NRRD file of whole-number voxels 0..65535 with one or more components (layers). Throws BadInput
// naming `path` for ITK failures, more than three spatial axes and voxels that are not such labels.
RawSegmentationFile readSegmentationFile(const std::string& path);

// Writes a 3-D single-layer NRRD (uint8 if every value is below 256, else uint16, gzip) carrying `fields`
// as "key:=value" lines, then reads it back to check every voxel arrived. Throws BadInput naming `path`.
void writeSegmentationFile(const std::string& path, const RawHeader& header,
                           const std::vector<std::pair<std::string, std::string>>& fields,
                           const std::vector<std::uint16_t>& values);

}  // namespace vesalius::io::itk_seam
