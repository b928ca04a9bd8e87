// The plain-data seam between the ITK translation units (image_io_itk.cpp, dicom_series.cpp) and
// image_io.cpp, which fills the core types.
//
// Why a seam: ITK 5.2 bundles Eigen 3.3 under the same namespace and include guards as the system
// Eigen 3.4 that core/grid.h includes, so a file that sees both silently compiles against whichever came
// first (docs/design.md, "Two Eigens"). Nothing here may include Eigen or ITK headers.
//
// Geometry follows ITK's physical space (LPS, mm): world = origin + direction · diag(spacing) · index.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace itk {
class ExceptionObject;
}

namespace vesalius::io::itk_seam {

// The stored component type of a file, in the order of vesalius::PixelType.
enum class StoredType { UInt8, Int8, UInt16, Int16, UInt32, Int32, Float32, Float64 };

struct RawHeader {
  std::array<int, 3> size{{0, 0, 0}};
  std::array<double, 3> origin{{0, 0, 0}};
  std::array<double, 3> spacing{{1, 1, 1}};
  std::array<double, 9> direction{{1, 0, 0, 0, 1, 0, 0, 0, 1}};  // row-major; column c is axis c
  StoredType storedType = StoredType::Float32;
  int components = 1;  // values per voxel; > 1 for RGB or vector images
};

template <class T>
struct RawVolume {
  RawHeader header;
  std::vector<T> values;  // header.size product values, i fastest
};

// Registers the NIfTI, NRRD, MetaImage and GDCM IO factories once (idempotent, thread-safe), so reading
// does not depend on ITK_USE_FILE having been included by the build.
void registerImageFactories();

// A one-line reason from an ITK exception: the first line of its description without ITK's
// "ITK ERROR: Class(0x...):" prefix.
std::string itkErrorReason(const itk::ExceptionObject& error);

// True if `path` has "DICM" after the 128-byte preamble, as every DICOM Part 10 file has: 132 bytes read,
// nothing parsed.
bool hasDicomPreamble(const std::string& path);

// True if GDCM recognises `path` as a DICOM file (for files without a known extension).
bool isDicomFile(const std::string& path);

// Walks the data elements of a DICOM file (any transfer syntax but deflated) and throws BadInput naming
// `path` if an element, item or fragment is longer than what is left of the file: GDCM aborts the
// process on some such files and reads others with missing pixels (dicom_series.cpp).
void checkDicomFileStructure(const std::string& path);

// Header of an image file (NIfTI, NRRD, MetaImage, single DICOM file) without reading its voxels.
// Throws BadInput naming `path` if ITK cannot read it or it has more than three non-trivial dimensions.
RawHeader readImageHeader(const std::string& path);

// The voxels of a scalar image file, converted to T (instantiated for float, double, std::uint16_t).
// Throws BadInput for multi-component images and for any ITK failure.
template <class T>
RawVolume<T> readImageFile(const std::string& path);

// Writes `values` (header.size product, i fastest) to `path` with the component type header.storedType;
// integer types receive rounded values clamped to their range. The format follows the extension.
void writeImageFile(const std::string& path, const RawHeader& header, const std::vector<float>& values);

// The DICOM series in `folder` (not recursive): series instance UID and file names sorted by slice
// position along the slice normal (dicom_series.cpp). Throws BadInput naming `folder` on ITK failures.
struct RawDicomSeries {
  std::string uid;
  std::vector<std::string> files;
  std::string description;  // (0008,103E), may be empty
  std::string modality;     // (0008,0060), may be empty
};
std::vector<RawDicomSeries> findDicomSeries(const std::string& folder);

// Reads the given slices of one series into a volume, rescaled to modality units (HU for CT); errors
// name `folder` (image_io_itk.cpp).
RawVolume<float> readDicomSlices(const std::string& folder, const std::vector<std::string>& files);

}  // namespace vesalius::io::itk_seam
