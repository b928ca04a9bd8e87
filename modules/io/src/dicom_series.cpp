// ITK side of DICOM folders: which series a folder holds and which files make each one, through GDCM.
// Exchanges plain data only (see image_io_itk.h for why).
#include "vesalius/io/dicom_series.h"

#include "image_io_itk.h"

#include "vesalius/core/error.h"

#include <itkGDCMImageIO.h>
#include <itkGDCMSeriesFileNames.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>

namespace vesalius::io::itk_seam {

namespace {

std::string tagValue(itk::GDCMImageIO& io, const char* tag) {
  std::string value;
  io.GetValueFromTag(tag, value);
  const std::size_t end = value.find_last_not_of(" \0", std::string::npos, 2);
  return end == std::string::npos ? std::string() : value.substr(0, end + 1);
}

// Series description and modality from the header of the series' first file; left empty if unreadable,
// since they only help a person choose.
void describeSeries(RawDicomSeries& series) {
  auto io = itk::GDCMImageIO::New();
  io->SetFileName(series.files.front());
  try {
    io->ReadImageInformation();
  } catch (const itk::ExceptionObject&) {
    return;
  }
  series.description = tagValue(*io, "0008|103e");
  series.modality = tagValue(*io, "0008|0060");
}

// GDCMSeriesFileNames prints a multi-line ITK warning for a folder without DICOM files; look first. Each
// DICOM file is walked before GDCM parses it (see checkDicomFileStructure).
bool holdsDicomFile(const std::string& folder) {
  std::error_code error;
  bool found = false;
  for (const std::filesystem::directory_entry& entry : std::filesystem::directory_iterator(folder, error))
    if (entry.is_regular_file(error) && isDicomFile(entry.path().string())) {
      checkDicomFileStructure(entry.path().string());
      found = true;
    }
  return found;
}

// The walk of checkDicomFileStructure: data elements in one encoding, every length checked against the
// bytes that remain. Throws BadInput naming the file at the first element that does not fit.
class DicomWalk {
 public:
  DicomWalk(const std::string& bytes, const std::string& path) : bytes_(bytes), path_(path) {}

  // Elements from `at` up to `end`; returns where a delimiter item (FFFE,E00D or E0DD) ends, or `end`.
  std::size_t elements(std::size_t at, std::size_t end, bool explicitVr, bool bigEndian, int depth) {
    if (depth > 64) fail(at, "sequences nest more than 64 deep");
    while (at < end) {
      need(at, 8, end, "an element's tag and length");
      const std::uint16_t group = u16(at, bigEndian), element = u16(at + 2, bigEndian);
      if (group == 0xFFFE) {
        const std::uint32_t length = u32(at + 4, bigEndian);
        at += 8;
        if (element == 0xE00D || element == 0xE0DD) return at;
        if (element != 0xE000) fail(at - 8, "unknown item tag");
        at = item(at, end, length, explicitVr, bigEndian, depth);
        continue;
      }
      bool sequence = false, bytesOfUnknownType = false;
      std::uint32_t length = 0;
      if (explicitVr) {
        const std::string vr = bytes_.substr(at + 4, 2);
        static const char* const kLongVrs[] = {"OB", "OD", "OF", "OL", "OV", "OW", "SQ", "SV", "UC", "UN", "UR", "UT", "UV"};
        const bool longForm = std::any_of(std::begin(kLongVrs), std::end(kLongVrs), [&](const char* v) { return vr == v; });
        sequence = vr == "SQ";
        bytesOfUnknownType = vr == "UN";
        if (longForm) {
          need(at, 12, end, "an element's tag and length");
          length = u32(at + 8, bigEndian);
          at += 12;
        } else {
          length = u16(at + 6, bigEndian);
          at += 8;
        }
      } else {
        length = u32(at + 4, bigEndian);
        at += 8;
        sequence = length == kUndefined;
      }
      if (length == kUndefined) {
        // A sequence, encapsulated pixel data (fragments as items) or, in UN, an implicit-VR sequence.
        const bool nestedImplicit = bytesOfUnknownType;
        at = elements(at, end, nestedImplicit ? false : explicitVr, bigEndian, depth + 1);
        continue;
      }
      need(at, length, end, "element (" + tag(group, element) + ")");
      if (sequence) elements(at, at + length, explicitVr, bigEndian, depth + 1);
      at += length;
    }
    return end;
  }

  [[noreturn]] void fail(std::size_t at, const std::string& problem) const {
    throw BadInput(path_, "not a complete DICOM file: " + problem + " at byte " + std::to_string(at));
  }

  std::uint16_t u16(std::size_t at, bool bigEndian) const {
    const auto* b = reinterpret_cast<const unsigned char*>(bytes_.data() + at);
    return bigEndian ? std::uint16_t(b[0] << 8 | b[1]) : std::uint16_t(b[1] << 8 | b[0]);
  }

  std::uint32_t u32(std::size_t at, bool bigEndian) const {
    const std::uint32_t low = u16(at, bigEndian), high = u16(at + 2, bigEndian);
    return bigEndian ? low << 16 | high : high << 16 | low;
  }

  static constexpr std::uint32_t kUndefined = 0xFFFFFFFF;

 private:
  std::size_t item(std::size_t at, std::size_t end, std::uint32_t length, bool explicitVr, bool bigEndian, int depth) {
    if (length == kUndefined) return elements(at, end, explicitVr, bigEndian, depth + 1);
    need(at, length, end, "an item");
    // A fragment of encapsulated pixel data is bytes, not elements; items of a sequence are elements.
    // Both are only checked to fit: what an item holds is GDCM's to read.
    return at + length;
  }

  void need(std::size_t at, std::uint64_t length, std::size_t end, const std::string& what) const {
    if (length > end - at)
      throw BadInput(path_, "the file is cut short: " + what + " needs " + std::to_string(length) +
                                " bytes at byte " + std::to_string(at) + ", " + std::to_string(end - at) +
                                " remain");
  }

  static std::string tag(std::uint16_t group, std::uint16_t element) {
    char text[16];
    std::snprintf(text, sizeof text, "%04X,%04X", unsigned(group), unsigned(element));
    return text;
  }

  const std::string& bytes_;
  const std::string& path_;
};

}  // namespace

void checkDicomFileStructure(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw BadInput(path, "cannot open");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  DicomWalk walk(bytes, path);
  std::size_t at = 0;
  bool explicitVr = true, bigEndian = false;
  if (bytes.size() >= 132 && bytes.compare(128, 4, "DICM") == 0) {
    // File meta information: group 0002, explicit VR little endian, naming the data set's transfer syntax.
    at = 132;
    std::string syntax;
    while (at + 8 <= bytes.size() && walk.u16(at, false) == 0x0002) {
      const std::uint16_t element = walk.u16(at + 2, false);
      const std::string vr = bytes.substr(at + 4, 2);
      const bool longForm = vr == "OB" || vr == "UN" || vr == "UT" || vr == "SQ";
      if (longForm && at + 12 > bytes.size()) break;
      const std::uint32_t length = longForm ? walk.u32(at + 8, false) : walk.u16(at + 6, false);
      const std::size_t value = at + (longForm ? 12 : 8);
      if (length > bytes.size() - value) walk.elements(at, bytes.size(), true, false, 0);  // reports the cut
      if (element == 0x0010) syntax = bytes.substr(value, length);
      at = value + length;
    }
    while (!syntax.empty() && (syntax.back() == '\0' || syntax.back() == ' ')) syntax.pop_back();
    if (syntax == "1.2.840.10008.1.2.1.99") return;  // deflated: the bytes are not elements until inflated
    explicitVr = syntax != "1.2.840.10008.1.2";
    bigEndian = syntax == "1.2.840.10008.1.2.2";
  } else if (bytes.size() >= 8) {
    // No preamble (older files): explicit VR if two upper-case letters follow the first tag.
    explicitVr = std::isupper(static_cast<unsigned char>(bytes[4])) && std::isupper(static_cast<unsigned char>(bytes[5]));
  }
  walk.elements(at, bytes.size(), explicitVr, bigEndian, 0);
}

bool hasDicomPreamble(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[132] = {};
  return in.read(magic, sizeof magic) && std::memcmp(magic + 128, "DICM", 4) == 0;
}

bool isDicomFile(const std::string& path) {
  // GDCM aborts the process on some cut files even when asked only whether it can read them.
  if (hasDicomPreamble(path)) {
    checkDicomFileStructure(path);
    return true;
  }
  auto io = itk::GDCMImageIO::New();
  return io->CanReadFile(path.c_str());
}

std::vector<RawDicomSeries> findDicomSeries(const std::string& folder) {
  registerImageFactories();
  std::vector<RawDicomSeries> found;
  if (!holdsDicomFile(folder)) return found;
  try {
    auto names = itk::GDCMSeriesFileNames::New();
    // Plain series instance UIDs, so the UID a user copies from a DICOM viewer selects the series.
    names->SetUseSeriesDetails(false);
    names->SetRecursive(false);
    names->SetInputDirectory(folder);
    for (const std::string& uid : names->GetSeriesUIDs()) {
      RawDicomSeries series;
      series.uid = uid;
      series.files = names->GetFileNames(uid);
      if (series.files.empty()) continue;
      describeSeries(series);
      found.push_back(std::move(series));
    }
  } catch (const itk::ExceptionObject& error) {
    throw BadInput(folder, itkErrorReason(error));
  }
  return found;
}

}  // namespace vesalius::io::itk_seam

namespace vesalius::io {

std::vector<DicomSeries> listDicomSeries(const std::string& folder) {
  std::vector<DicomSeries> listed;
  for (const itk_seam::RawDicomSeries& series : itk_seam::findDicomSeries(folder))
    listed.push_back(DicomSeries{series.uid, int(series.files.size()), series.description, series.modality});
  return listed;
}

}  // namespace vesalius::io
