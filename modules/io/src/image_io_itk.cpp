// ITK side of image files: NIfTI, NRRD, MetaImage and single DICOM files through itk::ImageFileReader
// and itk::ImageFileWriter, DICOM series through itk::ImageSeriesReader, and the NIfTI checks ITK lacks.
// Exchanges plain data only (see image_io_itk.h for why).
#include "image_io_itk.h"

#include "vesalius/core/atomic_file.h"
#include "vesalius/core/error.h"

#include <itkGDCMImageIO.h>
#include <itkGDCMImageIOFactory.h>
#include <itkImageFileReader.h>
#include <itkImageFileWriter.h>
#include <itkImageIOFactory.h>
#include <itkImageSeriesReader.h>
#include <itkMetaImageIOFactory.h>
#include <itkNiftiImageIOFactory.h>
#include <itkNrrdImageIOFactory.h>
#include <itk_zlib.h>

#include <gdcm-3.0/gdcmTrace.h>  // GDCM as ITK ships it; its own headers include one another by quotes

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <type_traits>

namespace vesalius::io::itk_seam {

void registerImageFactories() {
  static std::once_flag once;
  std::call_once(once, [] {
    itk::NiftiImageIOFactory::RegisterOneFactory();
    itk::NrrdImageIOFactory::RegisterOneFactory();
    itk::MetaImageIOFactory::RegisterOneFactory();
    itk::GDCMImageIOFactory::RegisterOneFactory();
    // Messages are ours, one line each: GDCM's traces and ITK's warnings (non-uniform slices, short
    // files) would print around them, and what they warn of is checked and refused here instead.
    gdcm::Trace::SetDebug(false);
    gdcm::Trace::SetWarning(false);
    gdcm::Trace::SetError(false);
    itk::Object::GlobalWarningDisplayOff();
  });
}

std::string itkErrorReason(const itk::ExceptionObject& error) {
  std::string text = error.GetDescription();
  // ITK prefixes descriptions with "ITK ERROR: ClassName(0x55d0c...): "; the address helps nobody.
  for (const std::string prefix : {"ITK ERROR: ", "itk::ERROR: "})
    if (text.compare(0, prefix.size(), prefix) == 0) {
      const std::size_t close = text.find("): ");
      text = close == std::string::npos ? text.substr(prefix.size()) : text.substr(close + 3);
    }
  // NrrdImageIO says "ReadImageInformation: Error reading <file>:" and the reason on the next line.
  const std::string reading = "ReadImageInformation: Error reading ";
  if (text.compare(0, reading.size(), reading) == 0) {
    const std::size_t colonNewline = text.find(":\n");
    if (colonNewline != std::string::npos) text = text.substr(colonNewline + 2);
  }
  std::size_t start = text.find_first_not_of(" \t\r\n");
  if (start == std::string::npos) return "ITK could not process the file";
  std::size_t end = text.find_first_of("\r\n", start);
  text = text.substr(start, end == std::string::npos ? std::string::npos : end - start);
  while (!text.empty() && (text.back() == ' ' || text.back() == '.')) text.pop_back();
  return text;
}

namespace {

StoredType storedTypeOf(itk::IOComponentEnum component, const std::string& path) {
  using C = itk::IOComponentEnum;
  switch (component) {
    case C::UCHAR: return StoredType::UInt8;
    case C::CHAR: return StoredType::Int8;
    case C::USHORT: return StoredType::UInt16;
    case C::SHORT: return StoredType::Int16;
    case C::UINT: return StoredType::UInt32;
    case C::INT: return StoredType::Int32;
    case C::FLOAT: return StoredType::Float32;
    // 64-bit integers have no PixelType of their own; float64 is the closest type that keeps their range.
    case C::LONG:
    case C::ULONG:
    case C::LONGLONG:
    case C::ULONGLONG:
    case C::DOUBLE: return StoredType::Float64;
    default:
      throw BadInput(path, std::string("unsupported voxel component type ") +
                               itk::ImageIOBase::GetComponentTypeAsString(component));
  }
}

// NIfTI files that ITK reads without complaint although they are broken: it fills the missing voxels of a
// truncated file silently and reports a zero pixdim as "no orthonormal definition found". So we look at the
// header (NIfTI-1 or -2, either byte order, gzipped or not) and count the bytes ourselves.
struct NiftiLayout {
  int axes = 0;                    // dim[0], at most 3 counted
  std::array<double, 3> pixdim{};  // pixdim[1..axes]: voxel spacing
  std::uint64_t dataEnd = 0;       // vox_offset + voxel bytes; 0 when the voxel size is unknown
  std::string unusableTransform;   // the first transform field in use that is NaN, infinite or absurd, or empty
  int datatype = 0;                // NIFTI_TYPE_*: 16 float32, 64 float64
  std::uint64_t voxOffset = 0;
  std::array<std::int64_t, 3> size{{1, 1, 1}};
  bool swapped = false;
  int badDim = 0;                  // the first dim[n] (n from 1 to dim[0]) below 1, or 0
};

template <class T>
T headerField(const unsigned char* header, std::size_t offset, bool swapped) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, header + offset, sizeof(T));
  if (swapped) std::reverse(bytes, bytes + sizeof(T));
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

// A byte count computed from header numbers, saturated: a header may claim more bytes than 64 bits count
// (it is then as truncated as one that claims 2^64 - 1), and converting such a double is undefined.
std::uint64_t byteCount(double bytes) {
  constexpr double kTwoTo64 = 18446744073709551616.0;
  return bytes < kTwoTo64 ? std::uint64_t(bytes) : std::numeric_limits<std::uint64_t>::max();
}

// Bits per voxel of a NIfTI datatype (nifti1.h's NIFTI_TYPE_*), as nifticlib counts them.
std::optional<double> niftiDatatypeBits(int datatype) {
  switch (datatype) {
    case 2: case 256: return 8;                        // uint8, int8
    case 4: case 512: return 16;                       // int16, uint16
    case 8: case 16: case 768: case 2304: return 32;   // int32, float32, uint32, rgba32
    case 128: return 24;                               // rgb24
    case 32: case 64: case 1024: case 1280: return 64;  // complex64, float64, int64, uint64
    case 1536: case 1792: return 128;                  // float128, complex128
    case 2048: return 256;                             // complex256
    default: return std::nullopt;
  }
}

// Field offsets of the two header versions; the NIfTI-2 fields are 64-bit.
template <class DimType, class PixdimType, class OffsetType>
NiftiLayout niftiLayout(const unsigned char* header, bool swapped, std::size_t dimAt, std::size_t bitpixAt,
                        std::size_t pixdimAt, std::size_t offsetAt) {
  NiftiLayout layout;
  const auto dim = [&](int n) {
    return double(headerField<DimType>(header, dimAt + n * sizeof(DimType), swapped));
  };
  if (!(dim(0) >= 1 && dim(0) <= 7)) return layout;  // a NIfTI-2 dim is 64 bits: compared before the cast
  const int dimensions = int(dim(0));
  layout.axes = std::min(dimensions, 3);
  for (int n = 1; n <= dimensions && layout.badDim == 0; ++n)
    if (dim(n) < 1) layout.badDim = n;
  double voxels = 1;
  for (int n = 1; n <= dimensions; ++n) voxels *= std::max(dim(n), 1.0);
  for (int n = 0; n < layout.axes; ++n)
    layout.pixdim[n] =
        double(headerField<PixdimType>(header, pixdimAt + (n + 1) * sizeof(PixdimType), swapped));
  layout.datatype = headerField<std::int16_t>(header, bitpixAt - 2, swapped);
  // nifticlib sizes the voxels by datatype, not bitpix (which a header may leave 0 or get wrong); bitpix
  // only for a datatype it does not know.
  const double bitpix = niftiDatatypeBits(layout.datatype).value_or(headerField<std::int16_t>(header, bitpixAt, swapped));
  const double offset = double(headerField<OffsetType>(header, offsetAt, swapped));
  // A negative vox_offset is read from the header's end: counted from 0, the data's end is still a bound.
  if (bitpix > 0) layout.dataEnd = byteCount(std::max(offset, 0.0) + voxels * bitpix / 8);
  layout.voxOffset = offset >= 0 ? byteCount(offset) : 0;
  // Clamped below 2^63 before the cast; a size that large fails the byte count anyway.
  for (int n = 0; n < layout.axes; ++n) layout.size[n] = std::int64_t(std::clamp(dim(n + 1), 1.0, 9e18));
  layout.swapped = swapped;
  return layout;
}

std::string shortNumber(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

// Millimetres no scan reaches: beyond them a float matrix's squares overflow, and VNL's SVD of ITK's NIfTI
// orientation loops for ever (fuzz_nifti: an srow entry of -1.7e38).
constexpr double kLargestNiftiMm = 1e9;

// A qform (quatern_b..d, qoffset_x..z) or sform (srow_x..z) in use that holds NaN, infinity or a value
// beyond kLargestNiftiMm: nifticlib turns a non-finite qform into zeros without a word (a wrong origin),
// and VNL aborts or loops on such an sform. `codeAt` is qform_code; sform_code, the quaternion, the
// offsets and the rows follow it. Returns the field and what is wrong with it, or empty.
template <class CodeType, class ValueType>
std::string unusableTransformField(const unsigned char* header, bool swapped, std::size_t codeAt) {
  const std::size_t quaternAt = codeAt + 2 * sizeof(CodeType);
  const bool qform = headerField<CodeType>(header, codeAt, swapped) > 0;
  const bool sform = headerField<CodeType>(header, codeAt + sizeof(CodeType), swapped) > 0;
  static const char* const kQformNames[] = {"quatern_b", "quatern_c", "quatern_d", "qoffset_x", "qoffset_y", "qoffset_z"};
  static const char* const kRows[] = {"srow_x", "srow_y", "srow_z"};
  const auto problem = [](double value) -> std::string {
    if (!std::isfinite(value)) return " is not a finite number";
    if (std::abs(value) > kLargestNiftiMm) return " is " + shortNumber(value) + ", beyond ±1e9 mm";
    return {};
  };
  for (int n = 0; qform && n < 6; ++n)
    if (const std::string p = problem(double(headerField<ValueType>(header, quaternAt + n * sizeof(ValueType), swapped)));
        !p.empty())
      return kQformNames[n] + p;
  for (int n = 0; sform && n < 12; ++n)
    if (const std::string p =
            problem(double(headerField<ValueType>(header, quaternAt + (6 + n) * sizeof(ValueType), swapped)));
        !p.empty())
      return std::string(kRows[n / 4]) + "[" + std::to_string(n % 4) + "]" + p;
  return {};
}

std::optional<NiftiLayout> parseNiftiHeader(const unsigned char* header, int length) {
  if (length < 348) return std::nullopt;
  bool swapped = false;
  std::int32_t size = headerField<std::int32_t>(header, 0, false);
  if (size != 348 && size != 540) {
    swapped = true;
    size = headerField<std::int32_t>(header, 0, true);
  }
  // nifticlib takes the byte order from dim[0] (1 to 7 one way or the other) before sizeof_hdr, so a file
  // can say one order in sizeof_hdr and be read in the other; the checks must read it as nifticlib does.
  const auto orderOfDim0 = [&](std::size_t at, auto type) {
    using Dim = decltype(type);
    const auto plain = headerField<Dim>(header, at, false), reversed = headerField<Dim>(header, at, true);
    if (plain >= 1 && plain <= 7) swapped = false;
    else if (reversed >= 1 && reversed <= 7) swapped = true;
  };
  if (size == 348) orderOfDim0(40, std::int16_t{});
  if (size == 540) orderOfDim0(16, std::int64_t{});
  // Only .nii and .nii.gz files are checked, and nifticlib reads their voxels from the same file whatever
  // the magic says (one without "n+1" as ANALYZE 7.5): the data's end is always a bound.
  if (size == 348) {
    NiftiLayout layout = niftiLayout<std::int16_t, float, float>(header, swapped, 40, 72, 76, 108);
    layout.unusableTransform = unusableTransformField<std::int16_t, float>(header, swapped, 252);
    return layout;
  }
  if (size == 540 && length >= 540) {
    NiftiLayout layout = niftiLayout<std::int64_t, double, std::int64_t>(header, swapped, 16, 14, 104, 168);
    layout.unusableTransform = unusableTransformField<std::int32_t, double>(header, swapped, 344);
    return layout;
  }
  return std::nullopt;
}

using GzFile = std::unique_ptr<std::remove_pointer_t<gzFile>, decltype(&gzclose)>;

// Decompressed bytes left in `file`; throws BadInput if the gzip stream is cut short or corrupt.
std::uint64_t remainingBytes(gzFile file, const std::string& path) {
  std::vector<unsigned char> buffer(1 << 18);
  std::uint64_t total = 0;
  while (true) {
    const int n = gzread(file, buffer.data(), unsigned(buffer.size()));
    if (n < 0) {
      int code = 0;
      throw BadInput(path,
                     std::string("compressed data is cut short or corrupt (") + gzerror(file, &code) + ")");
    }
    if (n == 0) return total;
    total += std::uint64_t(n);
  }
}

// ITK's NIfTI reader turns NaN voxels into 0 without a word, so float voxels are looked at here, in the
// file (see checkFiniteValues in image_io.cpp for the other formats).
template <class T>
void checkNiftiFloats(gzFile file, const NiftiLayout& layout, const std::string& path) {
  if (gzrewind(file) != 0 || gzseek(file, z_off_t(layout.voxOffset), SEEK_SET) < 0) return;
  const std::int64_t count = layout.size[0] * layout.size[1] * layout.size[2];
  std::vector<T> buffer(1 << 16);
  for (std::int64_t done = 0; done < count;) {
    const std::int64_t want = std::min<std::int64_t>(std::int64_t(buffer.size()), count - done);
    const int bytes = gzread(file, buffer.data(), unsigned(want * std::int64_t(sizeof(T))));
    if (bytes < int(want * std::int64_t(sizeof(T)))) return;  // the count above reports short files
    for (std::int64_t n = 0; n < want; ++n) {
      T value = buffer[std::size_t(n)];
      if (layout.swapped) {
        unsigned char raw[sizeof(T)];
        std::memcpy(raw, &value, sizeof(T));
        std::reverse(raw, raw + sizeof(T));
        std::memcpy(&value, raw, sizeof(T));
      }
      if (std::isfinite(value)) continue;
      const std::int64_t index = done + n, nx = layout.size[0], ny = layout.size[1];
      throw BadInput(path, "voxel (" + std::to_string(index % nx) + ", " + std::to_string(index / nx % ny) + ", " +
                               std::to_string(index / (nx * ny)) + ") holds " + shortNumber(double(value)) +
                               "; scans must hold finite numbers");
    }
    done += want;
  }
}

// Throws BadInput for a non-positive spacing and, if `wholeFile`, for a file shorter than its header says.
void checkNiftiFile(const std::string& path, bool wholeFile) {
  GzFile file(gzopen(path.c_str(), "rb"), &gzclose);
  if (!file) return;  // ITK reports unreadable files
  gzbuffer(file.get(), 1 << 18);
  unsigned char header[540];
  const int length = gzread(file.get(), header, sizeof header);
  const std::optional<NiftiLayout> layout = parseNiftiHeader(header, length);
  // ITK takes a file as NIfTI by a magic string alone, so a wrong sizeof_hdr must not let it past the
  // checks: a .nii file is NIfTI-1 (348) or NIfTI-2 (540).
  if (!layout) {
    if (length < 348) return;  // ITK reports files too short for a header
    throw BadInput(path, "NIfTI header size (sizeof_hdr) is neither 348 nor 540 in either byte order");
  }
  // nifticlib reads a zero or negative size as 1 without a word.
  if (layout->badDim > 0)
    throw BadInput(path, "dim[" + std::to_string(layout->badDim) + "] is not a positive size");
  if (!layout->unusableTransform.empty())
    throw BadInput(path, "the orientation field " + layout->unusableTransform);
  for (int axis = 0; axis < layout->axes; ++axis)
    if (!(std::isfinite(layout->pixdim[axis]) && layout->pixdim[axis] > 0 && layout->pixdim[axis] <= kLargestNiftiMm))
      throw BadInput(path, "voxel spacing pixdim[" + std::to_string(axis + 1) + "] is " +
                               shortNumber(layout->pixdim[axis]) + " (must be positive, at most 1e9 mm)");
  if (!wholeFile || layout->dataEnd == 0) return;
  const bool compressed = !gzdirect(file.get());
  const std::uint64_t size = compressed ? std::uint64_t(length) + remainingBytes(file.get(), path)
                                        : std::uint64_t(std::filesystem::file_size(path));
  if (size < layout->dataEnd)
    throw BadInput(path, "file is truncated: " + std::to_string(size) + " of " +
                             std::to_string(layout->dataEnd) +
                             (compressed ? " bytes after decompression" : " bytes"));
  if (layout->datatype == 16) checkNiftiFloats<float>(file.get(), *layout, path);
  if (layout->datatype == 64) checkNiftiFloats<double>(file.get(), *layout, path);
}

bool isNifti(const std::string& path) {
  const std::string extension = fileExtension(path);
  return extension == ".nii" || extension == ".nii.gz";
}

bool isNrrd(const std::string& path) {
  const std::string extension = fileExtension(path);
  return extension == ".nrrd" || extension == ".nhdr" || extension == ".seg.nrrd";
}

bool isMetaImage(const std::string& path) {
  const std::string extension = fileExtension(path);
  return extension == ".mha" || extension == ".mhd";
}

std::string trimmed(std::string s) {
  s.erase(0, s.find_first_not_of(" \t\r"));
  s.erase(s.find_last_not_of(" \t\r") + 1);
  return s;
}

// The numbers of a header field, NaN for a word that is not one ("nan", "inf" and the like included).
std::vector<double> headerNumbers(const std::string& text) {
  std::vector<double> numbers;
  std::string word;
  std::istringstream words(text);
  while (words >> word) {
    char* end = nullptr;
    const double value = std::strtod(word.c_str(), &end);
    numbers.push_back(end == word.c_str() || *end != '\0' ? std::numeric_limits<double>::quiet_NaN() : value);
  }
  return numbers;
}

// Geometry fields ITK reads without complaint although they are wrong: a NaN spacing becomes 1 mm in
// NRRD, a negative MetaImage spacing becomes a flipped axis, a NaN origin or direction is carried on.
void checkGeometryNumbers(const std::string& path, const std::string& field, const std::vector<double>& numbers,
                          bool positive) {
  for (std::size_t n = 0; n < numbers.size(); ++n)
    if (!std::isfinite(numbers[n]) || (positive && numbers[n] <= 0))
      throw BadInput(path, field + " holds " + shortNumber(numbers[n]) +
                               (positive ? " (each must be a positive number of mm)" : " (must be a finite number)"));
}

std::string lowerCase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return text;
}

// `key: value` lines of a NRRD header up to its blank line (`#` lines are comments), keys in lower case:
// NrrdIO reads field names and enum values (the encoding) in any case, so "encOding: gzip" is gzip to it.
// `headerBytes`: where the data of a file with attached data begins.
std::map<std::string, std::string> nrrdFields(const std::string& path, std::uint64_t& headerBytes) {
  std::map<std::string, std::string> fields;
  headerBytes = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) return fields;  // ITK reports unreadable files
  std::string line;
  int lines = 0;
  while (std::getline(in, line) && ++lines < 4096) {
    headerBytes += line.size() + 1;
    // NrrdIO copies a line it cannot parse into a fixed buffer, NUL bytes and all: a long one smashes its
    // stack. Key/value pairs (`key:=value`, Slicer's long segmentation parameters) are stored, not parsed;
    // NrrdIO takes a line for one only where its ":=" comes before any ": " (else it is a field line).
    const std::size_t keyValue = line.find(":="), field = line.find(": ");
    if (line.size() > 512 && line[0] != '#' && (keyValue == std::string::npos || field < keyValue))
      throw BadInput(path, "NRRD header line " + std::to_string(lines) + " holds " + std::to_string(line.size()) +
                               " characters (a field line holds at most 512)");
    if (const std::size_t nul = line.find('\0'); nul != std::string::npos) line.resize(nul);  // NrrdIO reads C strings
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) break;
    if (line[0] == '#') continue;
    const std::size_t colon = line.find(": ");
    if (colon == std::string::npos || line.compare(colon, 3, ":=") == 0) continue;
    const std::string key = lowerCase(trimmed(line.substr(0, colon)));
    // NrrdIO reads the first of a repeated field, the checks here would read the last.
    if (!fields.emplace(key, trimmed(line.substr(colon + 2))).second)
      throw BadInput(path, "NRRD header gives '" + key.substr(0, 40) + "' twice");
  }
  return fields;
}

void checkNrrdHeader(const std::string& path) {
  std::uint64_t headerBytes = 0;
  std::map<std::string, std::string> fields = nrrdFields(path, headerBytes);
  // NrrdIO copies a field naming one of its words (a type, an encoding, a space) into a short buffer: a
  // long one smashes its stack (fuzz_nrrd).
  for (const char* key : {"type", "encoding", "endian", "space", "kinds", "centers", "centerings"})
    if (fields.count(key) && fields[key].size() > 100)
      throw BadInput(path, std::string("NRRD field '") + key + "' holds " + std::to_string(fields[key].size()) +
                               " characters (at most 100)");
  static const std::set<std::string> kEncodings = {"raw", "txt", "text", "ascii", "hex", "gz", "gzip", "bz2", "bzip2"};  // NrrdIO's
  if (fields.count("encoding") && !kEncodings.count(lowerCase(fields["encoding"])))
    throw BadInput(path, "NRRD encoding '" + fields["encoding"].substr(0, 40) + "' is none of raw, text, hex, gzip, bzip2");
  int dimension = 0;
  if (fields.count("dimension")) dimension = std::atoi(fields["dimension"].c_str());
  // A 4-D file's non-spatial axis (vector components) has the spacing "nan" by the NRRD standard.
  if (fields.count("spacings") && dimension <= 3)
    checkGeometryNumbers(path, "spacings", headerNumbers(fields["spacings"]), true);
  if (fields.count("space origin")) {
    std::string origin = fields["space origin"];
    std::replace_if(origin.begin(), origin.end(), [](char c) { return c == '(' || c == ')' || c == ','; }, ' ');
    checkGeometryNumbers(path, "space origin", headerNumbers(origin), false);
  }
  if (fields.count("space directions")) {
    std::string directions = fields["space directions"];
    std::size_t word = 0;
    while ((word = directions.find("none")) != std::string::npos) directions.erase(word, 4);
    std::replace_if(directions.begin(), directions.end(), [](char c) { return c == '(' || c == ')' || c == ','; }, ' ');
    checkGeometryNumbers(path, "space directions", headerNumbers(directions), false);
  }
}

// The `Key = value` fields of a MetaImage header up to ElementDataFile, its last field. A header is text
// with each key once: MetaIO reads C strings and keeps its own choice of a repeated key, so a NUL byte or
// a second NDims would make it read other sizes than the ones checked here. MetaIO ends a key at '=', ':'
// or the end of the line and takes its value from the next '=' or ':', wherever that is: "NDims" alone on
// a line above "TransformMatrix = 0 0 ..." sets NDims to 0. It copies keys and text values into 255-byte
// buffers unchecked. So each line that is not blank is one word of at most 64 characters, '=' or ':',
// and a value of at most 254.
std::map<std::string, std::string> metaImageFields(const std::string& path, std::uint64_t& headerBytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw BadInput(path, "cannot open");
  std::map<std::string, std::string> fields;
  std::string line;
  headerBytes = 0;
  for (int number = 1; std::getline(in, line) && headerBytes < (1 << 20); ++number) {
    headerBytes += line.size() + 1;
    const auto control = std::find_if(line.begin(), line.end(), [](char c) {
      return (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\r') || c == 0x7f;
    });
    if (control != line.end())
      throw BadInput(path, "MetaImage header line " + std::to_string(number) + " holds the control byte " +
                               std::to_string(int(static_cast<unsigned char>(*control))) + " (the header must be text)");
    const std::size_t equals = line.find_first_of("=:");
    const std::string key = trimmed(line.substr(0, equals));
    if (equals == std::string::npos ? !key.empty()
                                    : key.empty() || key.find_first_of(" \t") != std::string::npos)
      throw BadInput(path, "MetaImage header line " + std::to_string(number) + " is not 'Key = Value'");
    if (equals == std::string::npos) continue;  // a blank line
    const std::size_t valueStart = line.find_first_not_of("=: \t", equals);  // as MetaIO skips to a value
    const std::string value = valueStart == std::string::npos ? "" : trimmed(line.substr(valueStart));
    if (key.size() > 64 || value.size() > 254)
      throw BadInput(path, "MetaImage header line " + std::to_string(number) + " is too long (a key of " +
                               std::to_string(key.size()) + " characters, a value of " +
                               std::to_string(value.size()) + "; at most 64 and 254)");
    if (!fields.emplace(key, value).second)
      throw BadInput(path, "MetaImage header gives " + key.substr(0, 40) + " twice (line " + std::to_string(number) + ")");
    if (key == "ElementDataFile") break;  // data follows
  }
  return fields;
}

// MetaIO reads a yes/no field (CompressedData, BinaryData) by its first character alone.
bool metaImageTrue(const std::string& value) {
  return !value.empty() && (value[0] == 'T' || value[0] == 't' || value[0] == '1');
}

// The bytes of one element of a MetaImage's ElementType. MetaIO takes any type name that starts with a
// known one ("MET_UCHAR" followed by anything), so only the exact names are accepted.
std::uint64_t metaImageElementBytes(const std::string& path, const std::map<std::string, std::string>& fields) {
  static const std::map<std::string, std::uint64_t> kBytes = {
      {"MET_CHAR", 1}, {"MET_UCHAR", 1}, {"MET_SHORT", 2}, {"MET_USHORT", 2}, {"MET_INT", 4}, {"MET_UINT", 4},
      {"MET_LONG", 4}, {"MET_ULONG", 4}, {"MET_LONG_LONG", 8}, {"MET_ULONG_LONG", 8}, {"MET_FLOAT", 4},
      {"MET_DOUBLE", 8}};
  const auto field = fields.find("ElementType");
  if (field == fields.end()) throw BadInput(path, "MetaImage header without ElementType");
  const auto type = kBytes.find(field->second);
  if (type == kBytes.end())
    throw BadInput(path, "MetaImage ElementType '" + field->second.substr(0, 40) +
                             "' is not one of MET_CHAR, MET_UCHAR, MET_SHORT, MET_USHORT, MET_INT, MET_UINT, "
                             "MET_LONG, MET_ULONG, MET_LONG_LONG, MET_ULONG_LONG, MET_FLOAT, MET_DOUBLE");
  return type->second;
}

// MetaIO sizes its reads by DimSize but ITK sizes the image by NDims: NDims = 0 over DimSize = 4 3 2 makes
// MetaIO write 24 voxels into a buffer of one (a heap overflow). So DimSize must hold NDims positive whole
// numbers.
void checkMetaImageDimensions(const std::string& path, const std::map<std::string, std::string>& fields) {
  const auto ndims = fields.find("NDims"), dimSize = fields.find("DimSize");
  if (ndims == fields.end() || dimSize == fields.end()) throw BadInput(path, "MetaImage header without NDims or DimSize");
  const std::vector<double> count = headerNumbers(ndims->second), sizes = headerNumbers(dimSize->second);
  if (count.size() != 1 || !(count[0] >= 1 && count[0] <= 10) || count[0] != std::floor(count[0]))
    throw BadInput(path, "NDims is '" + ndims->second + "' (must be a whole number from 1 to 10)");
  if (sizes.size() != std::size_t(count[0]))
    throw BadInput(path, "DimSize holds " + std::to_string(sizes.size()) + " numbers but NDims is " + ndims->second);
  for (const double size : sizes)
    if (!(size >= 1 && size == std::floor(size)))
      throw BadInput(path, "DimSize holds " + shortNumber(size) + " (each must be a positive whole number)");
}

void checkMetaImageHeader(const std::string& path) {
  std::uint64_t headerBytes = 0;
  const std::map<std::string, std::string> fields = metaImageFields(path, headerBytes);
  checkMetaImageDimensions(path, fields);
  metaImageElementBytes(path, fields);
  for (const char* key : {"ElementSpacing", "ElementSize"})
    if (fields.count(key)) checkGeometryNumbers(path, key, headerNumbers(fields.at(key)), true);
  for (const char* key : {"Offset", "Origin", "Position", "TransformMatrix", "Rotation", "Orientation"})
    if (fields.count(key)) checkGeometryNumbers(path, key, headerNumbers(fields.at(key)), false);
}

void checkMetaImageBytes(const std::string& path);

// The bytes of stored data a file's voxels come from (the file after its header, or its one data file)
// and how many voxel bytes each can give at most: 1 raw, 8 as text (a value of up to 8 bytes takes a
// digit and a separator), 1032 through zlib/gzip (deflate's largest ratio), about 1.2e6 through bzip2
// (its run-length stage and block sort). Empty when the data is spread over files or encoded otherwise.
struct StoredData {
  std::uint64_t bytes = 0;
  double expansion = 1;
};

std::uint64_t sizeOfDataFile(const std::string& headerPath, const std::string& dataFile) {
  const std::filesystem::path data = std::filesystem::path(headerPath).parent_path() / dataFile;
  std::error_code error;
  const std::uint64_t size = std::filesystem::file_size(data, error);
  if (error) throw BadInput(headerPath, "data file '" + dataFile + "' unreadable (" + error.message() + ")");
  return size;
}

std::optional<StoredData> nrrdStoredData(const std::string& path) {
  std::uint64_t headerBytes = 0;
  std::map<std::string, std::string> fields = nrrdFields(path, headerBytes);
  static const std::map<std::string, double> kExpansion = {
      {"raw", 1}, {"hex", 1}, {"txt", 8}, {"text", 8}, {"ascii", 8}, {"gz", 1032}, {"gzip", 1032},
      {"bz2", 1.2e6}, {"bzip2", 1.2e6}};
  const auto expansion = kExpansion.find(lowerCase(fields["encoding"]));
  if (expansion == kExpansion.end()) return std::nullopt;
  StoredData stored;
  stored.expansion = expansion->second;
  std::string dataFile = fields.count("data file") ? fields["data file"] : fields["datafile"];
  if (dataFile.empty()) {
    const std::uint64_t size = std::filesystem::file_size(path);
    stored.bytes = size > headerBytes ? size - headerBytes : 0;
  } else {
    // "LIST" or a "%d" pattern with its numbers: one file per slice, not counted here.
    if (dataFile.rfind("LIST", 0) == 0 || dataFile.find(' ') != std::string::npos) return std::nullopt;
    stored.bytes = sizeOfDataFile(path, dataFile);
  }
  return stored;
}

std::optional<StoredData> metaImageStoredData(const std::string& path) {
  std::uint64_t headerBytes = 0;
  std::map<std::string, std::string> fields = metaImageFields(path, headerBytes);
  const std::string& dataFile = fields["ElementDataFile"];
  if (dataFile.empty()) throw BadInput(path, "MetaImage header names no data file (ElementDataFile is empty)");
  // MetaIO allocates the whole image before it reads the slices of a list or a numbered pattern, and
  // divides by zero on some patterns: one data file per image only.
  if (dataFile.rfind("LIST", 0) == 0 || dataFile.find('%') != std::string::npos)
    throw BadInput(path, "MetaImage data split over several files (ElementDataFile " + dataFile.substr(0, 40) +
                             ") is not supported; save the image with its data in one file");
  StoredData stored;
  stored.expansion = metaImageTrue(fields["CompressedData"]) ? 1032 : 1;
  if (dataFile != "LOCAL") {
    stored.bytes = sizeOfDataFile(path, dataFile);
  } else {
    const std::uint64_t size = std::filesystem::file_size(path);
    stored.bytes = size > headerBytes ? size - headerBytes : 0;
  }
  return stored;
}

// ITK allocates the voxels a NRRD or MetaImage header declares before it reads them, so a few hundred
// bytes declaring 10^9 voxels exhaust the memory (or overflow the count). Refused here when the data
// stored cannot hold them.
void checkDeclaredVoxelBytes(const itk::ImageIOBase& io, const std::string& path) {
  std::uint64_t declared = 0;
  try {
    declared = std::uint64_t(io.GetComponentSize()) * io.GetNumberOfComponents();
  } catch (const itk::ExceptionObject& error) {  // a component type ITK has no size for
    throw BadInput(path, itkErrorReason(error));
  }
  bool overflow = false;
  for (unsigned axis = 0; axis < io.GetNumberOfDimensions(); ++axis)
    overflow |= __builtin_mul_overflow(declared, std::uint64_t(io.GetDimensions(axis)), &declared);
  if (overflow) throw BadInput(path, "header declares more voxels than 64 bits can count");
  const std::optional<StoredData> stored = isNrrd(path) ? nrrdStoredData(path) : metaImageStoredData(path);
  if (stored && double(declared) > stored->expansion * double(stored->bytes))
    throw BadInput(path, "header declares " + std::to_string(declared) + " bytes of voxels, more than the " +
                             std::to_string(stored->bytes) + " bytes of data stored can hold");
}

// An ImageIO that has read the header of `path`; throws BadInput if no ITK reader accepts the file or our
// own NIfTI checks fail (`wholeFile`: also check that all voxel bytes are there).
itk::ImageIOBase::Pointer openImageIO(const std::string& path, bool wholeFile) {
  if (isNifti(path)) checkNiftiFile(path, wholeFile);
  if (isNrrd(path)) checkNrrdHeader(path);
  if (isMetaImage(path)) checkMetaImageHeader(path);
  if (!isNifti(path) && !isNrrd(path) && !isMetaImage(path)) checkDicomFileStructure(path);
  registerImageFactories();
  itk::ImageIOBase::Pointer io =
      itk::ImageIOFactory::CreateImageIO(path.c_str(), itk::IOFileModeEnum::ReadMode);
  if (!io) throw BadInput(path, "not an image file ITK can read (NIfTI, NRRD, MetaImage or DICOM)");
  io->SetFileName(path);
  try {
    io->ReadImageInformation();
  } catch (const itk::ExceptionObject& error) {
    throw BadInput(path, itkErrorReason(error));
  }
  if (wholeFile && (isNrrd(path) || isMetaImage(path))) checkDeclaredVoxelBytes(*io, path);
  if (wholeFile && isMetaImage(path)) {
    try {
      checkMetaImageBytes(path);
    } catch (const BadInput&) {
      throw;
    } catch (const std::exception& error) {  // a size that is not a number, a data file that is missing
      throw BadInput(path, std::string("MetaImage header or data file unreadable (") + error.what() + ")");
    }
  }
  return io;
}

// Rejects what a 3-D reader would silently cut: 4-D series (only their first volume would be read).
void check3D(const itk::ImageIOBase& io, const std::string& path) {
  for (unsigned axis = 3; axis < io.GetNumberOfDimensions(); ++axis)
    if (io.GetDimensions(axis) > 1)
      throw BadInput(path, std::to_string(io.GetNumberOfDimensions()) + "-D image with " +
                               std::to_string(io.GetDimensions(axis)) + " entries along axis " +
                               std::to_string(axis) + "; only 3-D scans are read");
}

// Rejects what a scalar reader would silently turn into grey values: RGB and vector voxels.
void checkScalar(const itk::ImageIOBase& io, const std::string& path) {
  if (io.GetNumberOfComponents() > 1)
    throw BadInput(path, std::to_string(io.GetNumberOfComponents()) +
                             " components per voxel (RGB or vector image); only scalar scans are read");
}

RawHeader headerOf(const itk::ImageIOBase& io, const std::string& path) {
  RawHeader header;
  const unsigned dimensions = std::min(io.GetNumberOfDimensions(), 3u);
  for (unsigned axis = 0; axis < 3; ++axis) header.size[axis] = 1;
  for (unsigned axis = 0; axis < dimensions; ++axis) {
    header.size[axis] = int(io.GetDimensions(axis));
    header.spacing[axis] = io.GetSpacing(axis);
    header.origin[axis] = io.GetOrigin(axis);
    const std::vector<double> column = io.GetDirection(axis);
    for (unsigned row = 0; row < dimensions; ++row) header.direction[3 * row + axis] = column[row];
  }
  header.storedType = storedTypeOf(io.GetComponentType(), path);
  header.components = int(io.GetNumberOfComponents());
  return header;
}

template <class ImageType>
void copyGeometry(const ImageType& image, RawHeader& header) {
  const auto size = image.GetLargestPossibleRegion().GetSize();
  for (unsigned axis = 0; axis < 3; ++axis) {
    header.size[axis] = int(size[axis]);
    header.spacing[axis] = image.GetSpacing()[axis];
    header.origin[axis] = image.GetOrigin()[axis];
    for (unsigned column = 0; column < 3; ++column)
      header.direction[3 * axis + column] = image.GetDirection()(axis, column);
  }
}

template <class T>
T toStored(float value) {
  if constexpr (std::is_integral_v<T>) {
    if (std::isnan(value)) return T(0);
    const double rounded = std::nearbyint(double(value));
    const double low = double(std::numeric_limits<T>::lowest()), high = double(std::numeric_limits<T>::max());
    return T(std::clamp(rounded, low, high));
  } else {
    return T(value);
  }
}

// Why `stored` bytes of `in`, a zlib or gzip stream, do not inflate to exactly `expected` bytes, or empty
// if they do. Inflates into a small buffer: memory does not grow with the image.
std::string checkInflates(std::istream& in, std::uint64_t stored, std::uint64_t expected) {
  z_stream stream{};
  if (inflateInit2(&stream, 15 + 32) != Z_OK) return "cannot be inflated (zlib failed to start)";
  std::vector<unsigned char> input(1 << 16), output(1 << 16);
  std::uint64_t produced = 0;
  int status = Z_OK;
  while (status == Z_OK) {
    if (stream.avail_in == 0 && stored > 0) {
      const std::uint64_t want = std::min<std::uint64_t>(stored, input.size());
      in.read(reinterpret_cast<char*>(input.data()), std::streamsize(want));
      if (std::uint64_t(in.gcount()) != want) break;
      stored -= want;
      stream.next_in = input.data();
      stream.avail_in = uInt(want);
    }
    stream.next_out = output.data();
    stream.avail_out = uInt(output.size());
    status = inflate(&stream, Z_NO_FLUSH);
    produced += output.size() - stream.avail_out;
    if (status == Z_BUF_ERROR && stream.avail_in == 0 && stored > 0) status = Z_OK;  // more input to come
    if (produced > expected) break;
  }
  const std::string reason = stream.msg ? stream.msg : "";
  inflateEnd(&stream);
  if (status == Z_STREAM_END && produced == expected) return "";
  if (produced > expected)
    return "inflates to more than the " + std::to_string(expected) + " bytes of voxels the header declares";
  if (status == Z_STREAM_END)
    return "inflates to " + std::to_string(produced) + " bytes, but the header declares " + std::to_string(expected);
  return "is corrupt or cut short after inflating " + std::to_string(produced) + " of " + std::to_string(expected) +
         " bytes" + (reason.empty() ? "" : " (" + reason + ")");
}

// Throws BadInput if a MetaImage file (.mha, or .mhd with its data file) holds fewer data bytes than its
// header says: ITK reads such a file with a warning on stderr and zeros for the missing voxels.
void checkMetaImageBytes(const std::string& path) {
  std::uint64_t headerBytes = 0;
  std::map<std::string, std::string> fields = metaImageFields(path, headerBytes);
  if (!fields.count("ElementDataFile")) throw BadInput(path, "MetaImage header without ElementDataFile");
  const auto channels = fields.find("ElementNumberOfChannels");
  std::uint64_t voxelBytes =
      metaImageElementBytes(path, fields) * (channels == fields.end() ? 1 : std::stoull(channels->second));
  std::istringstream sizes(fields["DimSize"]);
  for (std::uint64_t n; sizes >> n;) voxelBytes *= n;

  const std::string& dataFile = fields["ElementDataFile"];
  if (dataFile.rfind("LIST", 0) == 0 || dataFile.find('%') != std::string::npos) return;  // one file per slice
  const bool local = dataFile == "LOCAL";
  const std::string dataPath = local ? path : (std::filesystem::path(path).parent_path() / dataFile).string();
  const std::uint64_t offset = local ? headerBytes : 0, size = std::filesystem::file_size(dataPath);
  const std::uint64_t actual = size > offset ? size - offset : 0;
  if (!metaImageTrue(fields["CompressedData"])) {
    if (actual < voxelBytes)
      throw BadInput(path, "data is cut short: " + std::to_string(actual) + " of " + std::to_string(voxelBytes) + " bytes");
    return;
  }
  // ITK's MetaIO reads a corrupt or short compressed stream as a whole image (zeros where it failed) and,
  // without CompressedDataSize, inflates a LOCAL file from its first byte, the header's.
  const bool sized = fields.count("CompressedDataSize") > 0;
  if (!sized && local)
    throw BadInput(path, "compressed data without CompressedDataSize in the header (ITK cannot find where it starts)");
  const std::uint64_t stored = sized ? std::stoull(fields["CompressedDataSize"]) : actual;
  if (actual < stored)
    throw BadInput(path, "data is cut short: " + std::to_string(actual) + " of " + std::to_string(stored) + " compressed bytes");
  std::ifstream in(dataPath, std::ios::binary);
  in.seekg(std::streamoff(offset));
  const std::string problem = checkInflates(in, stored, voxelBytes);
  if (!problem.empty()) throw BadInput(path, "compressed data " + problem);
}

// ITK's NIfTI and MetaImage writers report a failed write (a full disk) on stderr only, so what was
// written is read back: a truncated file fails to read, or holds too few voxels. ITK reads a truncated
// NIfTI file without complaint, so its bytes are counted as the reader counts them.
template <class T>
void checkReadsBack(const std::string& path, itk::SizeValueType voxels) {
  const auto fail = [&](const std::string& reason) {
    throw BadInput(path, "cannot write: the file written does not read back (" + reason + "); is the disk full?");
  };
  const std::string extension = fileExtension(path);
  try {
    if (isNifti(path)) checkNiftiFile(path, true);
    if (extension == ".mha" || extension == ".mhd") checkMetaImageBytes(path);
  } catch (const BadInput& error) {
    fail(error.problem());
  } catch (const std::exception& error) {  // a number or file size that cannot be read
    fail(error.what());
  }
  using ImageType = itk::Image<T, 3>;
  auto reader = itk::ImageFileReader<ImageType>::New();
  reader->SetFileName(path);
  try {
    reader->Update();
  } catch (const itk::ExceptionObject& error) {
    fail(itkErrorReason(error));
  }
  if (reader->GetOutput()->GetLargestPossibleRegion().GetNumberOfPixels() != voxels)
    throw BadInput(path, "cannot write: the file written does not hold every voxel; is the disk full?");
}

template <class T>
void writeAs(const std::string& path, const RawHeader& header, const std::vector<float>& values) {
  using ImageType = itk::Image<T, 3>;
  auto image = ImageType::New();
  typename ImageType::RegionType region;
  typename ImageType::SpacingType spacing;
  typename ImageType::PointType origin;
  typename ImageType::DirectionType direction;
  for (unsigned axis = 0; axis < 3; ++axis) {
    region.SetSize(axis, itk::SizeValueType(header.size[axis]));
    spacing[axis] = header.spacing[axis];
    origin[axis] = header.origin[axis];
    for (unsigned column = 0; column < 3; ++column)
      direction(axis, column) = header.direction[3 * axis + column];
  }
  image->SetRegions(region);
  image->SetSpacing(spacing);
  image->SetOrigin(origin);
  image->SetDirection(direction);
  image->Allocate();
  std::transform(values.begin(), values.end(), image->GetBufferPointer(), toStored<T>);

  auto writer = itk::ImageFileWriter<ImageType>::New();
  writer->SetFileName(path);
  writer->SetInput(image);
  writer->SetUseCompression(true);
  writer->Update();
  writer = nullptr;
  image = nullptr;  // the read-back below needs the memory
  checkReadsBack<T>(path, region.GetNumberOfPixels());
}

}  // namespace

RawHeader readImageHeader(const std::string& path) {
  itk::ImageIOBase::Pointer io = openImageIO(path, false);
  check3D(*io, path);
  return headerOf(*io, path);
}

template <class T>
RawVolume<T> readImageFile(const std::string& path) {
  itk::ImageIOBase::Pointer io = openImageIO(path, true);
  check3D(*io, path);
  checkScalar(*io, path);
  RawVolume<T> volume;
  volume.header = headerOf(*io, path);
  using ImageType = itk::Image<T, 3>;
  auto reader = itk::ImageFileReader<ImageType>::New();
  reader->SetFileName(path);
  reader->SetImageIO(io);
  try {
    reader->Update();
  } catch (const itk::ExceptionObject& error) {
    throw BadInput(path, itkErrorReason(error));
  }
  const ImageType& image = *reader->GetOutput();
  copyGeometry(image, volume.header);
  const T* buffer = image.GetBufferPointer();
  volume.values.assign(buffer, buffer + image.GetLargestPossibleRegion().GetNumberOfPixels());
  return volume;
}

template RawVolume<float> readImageFile<float>(const std::string&);
template RawVolume<double> readImageFile<double>(const std::string&);
template RawVolume<std::uint16_t> readImageFile<std::uint16_t>(const std::string&);

void writeImageFile(const std::string& path, const RawHeader& header, const std::vector<float>& values) {
  registerImageFactories();
  try {
    switch (header.storedType) {
      case StoredType::UInt8: return writeAs<std::uint8_t>(path, header, values);
      case StoredType::Int8: return writeAs<std::int8_t>(path, header, values);
      case StoredType::UInt16: return writeAs<std::uint16_t>(path, header, values);
      case StoredType::Int16: return writeAs<std::int16_t>(path, header, values);
      case StoredType::UInt32: return writeAs<std::uint32_t>(path, header, values);
      case StoredType::Int32: return writeAs<std::int32_t>(path, header, values);
      case StoredType::Float32: return writeAs<float>(path, header, values);
      case StoredType::Float64: return writeAs<double>(path, header, values);
    }
  } catch (const itk::ExceptionObject& error) {
    throw BadInput(path, "cannot write: " + itkErrorReason(error));
  }
}

namespace {

// GDCM sorts a series by position along the slice normal; ITK then spaces the slices evenly by their
// mean distance. So two files at one position (a duplicated slice) or a gap (a missing slice) would give
// a volume whose geometry is wrong without a word. Refused here, naming the files.
void checkSlicePositions(const std::string& folder, const std::vector<std::string>& files) {
  if (files.size() < 2) return;
  std::vector<double> along;
  for (const std::string& file : files) {
    auto io = itk::GDCMImageIO::New();
    io->SetFileName(file);
    try {
      io->ReadImageInformation();
    } catch (const itk::ExceptionObject& error) {
      throw BadInput(file, itkErrorReason(error));
    }
    const std::vector<double> normal = io->GetDirection(2);
    double d = 0;
    for (unsigned axis = 0; axis < 3 && axis < normal.size(); ++axis) d += normal[axis] * io->GetOrigin(axis);
    along.push_back(d);
  }
  std::vector<std::size_t> order(files.size());
  for (std::size_t n = 0; n < order.size(); ++n) order[n] = n;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return along[a] < along[b]; });
  const auto name = [&](std::size_t n) { return std::filesystem::path(files[order[n]]).filename().string(); };
  for (std::size_t n = 1; n < order.size(); ++n)
    if (along[order[n]] - along[order[n - 1]] < 1e-3)
      throw BadInput(folder, "slices " + name(n - 1) + " and " + name(n) + " lie at the same position (" +
                                 shortNumber(along[order[n]]) + " mm along the slice normal): a slice is duplicated");
  const double mean = (along[order.back()] - along[order.front()]) / double(files.size() - 1);
  for (std::size_t n = 1; n < order.size(); ++n) {
    const double gap = along[order[n]] - along[order[n - 1]];
    // Up to a tenth of a gap: rounding in the stored positions, and scanners that vary it slightly.
    if (std::abs(gap - mean) > 0.1 * mean)
      throw BadInput(folder, "slices " + name(n - 1) + " and " + name(n) + " are " + shortNumber(gap) +
                                 " mm apart, the series " + shortNumber(mean) +
                                 " mm on average: a slice is missing or the spacing varies");
  }
}

}  // namespace

RawVolume<float> readDicomSlices(const std::string& folder, const std::vector<std::string>& files) {
  registerImageFactories();
  for (const std::string& file : files) checkDicomFileStructure(file);
  checkSlicePositions(folder, files);
  using ImageType = itk::Image<float, 3>;
  auto io = itk::GDCMImageIO::New();
  auto reader = itk::ImageSeriesReader<ImageType>::New();
  reader->SetImageIO(io);
  reader->SetFileNames(files);
  try {
    reader->Update();
  } catch (const itk::ExceptionObject& error) {
    throw BadInput(folder, itkErrorReason(error));
  }
  checkScalar(*io, folder);
  const ImageType& image = *reader->GetOutput();
  RawVolume<float> volume;
  // After Update GDCMImageIO reports the type of the rescaled values (e.g. int16 HU), not the raw pixels.
  volume.header.storedType = storedTypeOf(io->GetComponentType(), folder);
  copyGeometry(image, volume.header);
  const float* buffer = image.GetBufferPointer();
  volume.values.assign(buffer, buffer + image.GetLargestPossibleRegion().GetNumberOfPixels());
  return volume;
}

}  // namespace vesalius::io::itk_seam
