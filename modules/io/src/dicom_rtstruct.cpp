// RT Structure Sets through DCMTK's dcmrt (dicom_rtstruct.h): a label map's voxel boundaries traced into
// closed polygons per slice, and polygons filled back onto a grid by the even-odd rule.
#include "vesalius/io/dicom_rtstruct.h"

#include "dicom_common.h"
#include "label_names.h"

#include "vesalius/core/error.h"
#include "vesalius/io/image_io.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <dcmtk/dcmdata/dcvrda.h>
#include <dcmtk/dcmdata/dcvrtm.h>
#include <dcmtk/dcmrt/drtstrct.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <stdexcept>

namespace vesalius::io {

namespace {

using namespace dicom;

// The Referenced SOP Class UID of an RT Referenced Study item: Detached Study Management (retired), which
// C.8.8.5 names for it and planning systems expect.
constexpr const char* kDetachedStudyManagement = "1.2.840.10008.3.1.2.3.1";

// How far (mm) a contour's points may lie off their common plane: planning systems write coordinates
// rounded to 0.01 mm or coarser, which moves a point up to 0.009 mm.
constexpr double kPlanarTolerance = 0.02;

// ------------------------------------------------------------------------------------- tracing a slice

// A closed polygon in a slice's (i, j) index plane, at voxel corners: corner (a, b) is index (a − ½, b − ½).
using Polygon = std::vector<Eigen::Vector2i>;

// Boundary polygons of a mask (nx × ny, i fastest): every edge between a voxel inside and one outside (or
// the border), directed with the inside on its left, linked into loops. A loop starts at the first corner
// in row order that has an edge left, which is never one where two regions touch diagonally (the edge
// below it would come first); at such a corner the loop turns left, staying with its own region, so
// regions touching at a corner get a polygon each. Only corners where the direction changes are kept.
std::vector<Polygon> traceBoundaries(const std::vector<std::uint8_t>& mask, int nx, int ny) {
  static const Eigen::Vector2i kStep[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};  // +i, +j, −i, −j
  const int cx = nx + 1, cy = ny + 1;
  std::vector<std::uint8_t> out(std::size_t(cx) * cy, 0);  // per corner, a bit per outgoing direction
  auto inside = [&](int i, int j) { return i >= 0 && j >= 0 && i < nx && j < ny && mask[std::size_t(j) * nx + i]; };
  auto corner = [&](int a, int b) -> std::uint8_t& { return out[std::size_t(b) * cx + a]; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (!inside(i, j)) continue;
      if (!inside(i, j - 1)) corner(i, j) |= 1;              // bottom, +i
      if (!inside(i + 1, j)) corner(i + 1, j) |= 2;          // right, +j
      if (!inside(i, j + 1)) corner(i + 1, j + 1) |= 4;      // top, −i
      if (!inside(i - 1, j)) corner(i, j + 1) |= 8;          // left, −j
    }
  std::vector<Polygon> polygons;
  for (int b = 0; b < cy; ++b)
    for (int a = 0; a < cx; ++a) {
      while (corner(a, b)) {
        Polygon polygon;
        Eigen::Vector2i at(a, b);
        int direction = -1;
        do {
          std::uint8_t& bits = corner(at.x(), at.y());
          int next = -1;
          if (direction < 0) next = __builtin_ctz(bits);
          else
            for (int turn : {1, 0, 3})
              if (bits & (1 << ((direction + turn) % 4))) {
                next = (direction + turn) % 4;
                break;
              }
          if (next < 0) throw std::logic_error("traceBoundaries: an open boundary");
          bits &= std::uint8_t(~(1 << next));
          if (next != direction) polygon.push_back(at);
          direction = next;
          at += kStep[direction];
        } while (at != Eigen::Vector2i(a, b));
        polygons.push_back(std::move(polygon));
      }
    }
  return polygons;
}

// The labels present on slice k with their bounding boxes (i0, j0, i1, j1), by id.
std::map<Label, Eigen::Vector4i> labelsOnSlice(const Grid<Label>& labels, int k) {
  const GridGeometry& g = labels.geometry;
  std::map<Label, Eigen::Vector4i> boxes;
  const Label* slice = labels.values.data() + std::size_t(k) * g.size.x() * g.size.y();
  for (int j = 0; j < g.size.y(); ++j)
    for (int i = 0; i < g.size.x(); ++i) {
      const Label id = slice[std::size_t(j) * g.size.x() + i];
      if (id == 0) continue;
      auto [box, added] = boxes.try_emplace(id, i, j, i, j);
      if (!added)
        box->second = {std::min(box->second[0], i), std::min(box->second[1], j), std::max(box->second[2], i),
                       std::max(box->second[3], j)};
    }
  return boxes;
}

// ------------------------------------------------------------------------------------------ writing

struct RoiContours {
  Label id = 0;
  std::vector<std::pair<int, Polygon>> polygons;  // slice k, corners in the grid's (i, j)
};

std::vector<RoiContours> contoursOf(const Grid<Label>& labels) {
  const GridGeometry& g = labels.geometry;
  std::map<Label, RoiContours> rois;
  std::vector<std::uint8_t> mask;
  for (int k = 0; k < g.size.z(); ++k) {
    const Label* slice = labels.values.data() + std::size_t(k) * g.size.x() * g.size.y();
    for (const auto& [id, box] : labelsOnSlice(labels, k)) {
      const int nx = box[2] - box[0] + 1, ny = box[3] - box[1] + 1;
      mask.assign(std::size_t(nx) * ny, 0);
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
          mask[std::size_t(j) * nx + i] = slice[std::size_t(j + box[1]) * g.size.x() + i + box[0]] == id;
      RoiContours& roi = rois[id];
      roi.id = id;
      for (Polygon& polygon : traceBoundaries(mask, nx, ny)) {
        for (Eigen::Vector2i& c : polygon) c += box.head<2>();
        roi.polygons.emplace_back(k, std::move(polygon));
      }
    }
  }
  std::vector<RoiContours> out;
  for (auto& [id, roi] : rois) out.push_back(std::move(roi));
  return out;
}

void setSourceAttributes(DRTStructureSetIOD& rt, const DicomSourceSeries& s, const std::string& path) {
  auto set = [&](const OFCondition& c, const char* what) { check(c, path, std::string("cannot set ") + what); };
  set(rt.setPatientName(s.patientName.c_str(), false), "Patient's Name");
  set(rt.setPatientID(s.patientId.c_str(), false), "Patient ID");
  set(rt.setPatientBirthDate(s.patientBirthDate.c_str(), false), "Patient's Birth Date");
  set(rt.setPatientSex(s.patientSex.c_str(), false), "Patient's Sex");
  set(rt.setStudyDate(s.studyDate.c_str(), false), "Study Date");
  set(rt.setStudyTime(s.studyTime.c_str(), false), "Study Time");
  set(rt.setStudyID(s.studyId.c_str(), false), "Study ID");
  set(rt.setAccessionNumber(s.accessionNumber.c_str(), false), "Accession Number");
  set(rt.setReferringPhysicianName(s.referringPhysicianName.c_str(), false), "Referring Physician's Name");
  set(rt.setStudyDescription(s.studyDescription.c_str(), false), "Study Description");
}

// Referenced Frame of Reference Sequence (C.8.8.5): the frame of reference and, with a source series, its
// study, series and every image with a SOP instance.
void addReferencedFrameOfReference(DRTStructureSetIOD& rt, const std::string& frameOfReference,
                                   const std::string& study, const DicomSourceSeries* source, const std::string& path) {
  const std::string what = "cannot write the Referenced Frame of Reference Sequence";
  DRTReferencedFrameOfReferenceSequence::Item* item = nullptr;
  check(rt.getReferencedFrameOfReferenceSequence().addItem(item), path, what);
  check(item->setFrameOfReferenceUID(frameOfReference.c_str()), path, what);
  if (!source || source->seriesInstanceUid.empty()) return;
  DRTRTReferencedStudySequence::Item* studyItem = nullptr;
  check(item->getRTReferencedStudySequence().addItem(studyItem), path, what);
  check(studyItem->setReferencedSOPClassUID(kDetachedStudyManagement), path, what);
  check(studyItem->setReferencedSOPInstanceUID(study.c_str()), path, what);
  DRTRTReferencedSeriesSequence::Item* series = nullptr;
  check(studyItem->getRTReferencedSeriesSequence().addItem(series), path, what);
  check(series->setSeriesInstanceUID(source->seriesInstanceUid.c_str()), path, what);
  for (const DicomSourceImage& image : source->images) {
    if (image.sopClassUid.empty() || image.sopInstanceUid.empty()) continue;
    DRTContourImageSequence::Item* reference = nullptr;
    check(series->getContourImageSequence().addItem(reference), path, what);
    check(reference->setReferencedSOPClassUID(image.sopClassUid.c_str()), path, what);
    check(reference->setReferencedSOPInstanceUID(image.sopInstanceUid.c_str()), path, what);
  }
}

void addContour(DRTContourSequence& contours, const GridGeometry& g, int k, const Polygon& polygon,
                const DicomSourceSeries* source, const std::string& path) {
  const std::string what = "cannot write a contour";
  DRTContourSequence::Item* item = nullptr;
  check(contours.addItem(item), path, what);
  if (const DicomSourceImage* image = sourceImageAt(source, g, k)) {
    DRTContourImageSequence::Item* reference = nullptr;
    check(item->getContourImageSequence().addItem(reference), path, what);
    check(reference->setReferencedSOPClassUID(image->sopClassUid.c_str()), path, what);
    check(reference->setReferencedSOPInstanceUID(image->sopInstanceUid.c_str()), path, what);
  }
  std::string data;
  for (const Eigen::Vector2i& c : polygon) {
    const Eigen::Vector3d p = g.indexToWorld(Eigen::Vector3d(c.x() - 0.5, c.y() - 0.5, k));
    for (int d = 0; d < 3; ++d) data += (data.empty() ? "" : "\\") + decimal(p[d]);
  }
  check(item->setContourGeometricType("CLOSED_PLANAR"), path, what);
  check(item->setNumberOfContourPoints(std::to_string(polygon.size()).c_str()), path, what);
  check(item->setContourData(data.c_str(), false), path, what);
}

void addRoi(DRTStructureSetIOD& rt, const LabelTable& table, const RoiContours& roi, int number,
            const std::string& frameOfReference, const GridGeometry& g, const DicomSourceSeries* source,
            const std::string& path) {
  const LabelEntry* entry = table.find(roi.id);
  const std::string name = entry ? entry->name : "label_" + std::to_string(roi.id);
  const std::array<std::uint8_t, 3> rgb = entry ? entry->color : defaultLabelColor(roi.id);
  const std::string what = "cannot write ROI '" + name + "'";
  const std::string numberText = std::to_string(number);
  DRTStructureSetROISequence::Item* structure = nullptr;
  check(rt.getStructureSetROISequence().addItem(structure), path, what);
  check(structure->setROINumber(numberText.c_str()), path, what);
  check(structure->setReferencedFrameOfReferenceUID(frameOfReference.c_str()), path, what);
  check(structure->setROIName(name.substr(0, 64).c_str(), false), path, what);
  check(structure->setROIDescription(labelDescription(roi.id).c_str()), path, what);
  DRTROIContourSequence::Item* contour = nullptr;
  check(rt.getROIContourSequence().addItem(contour), path, what);
  check(contour->setReferencedROINumber(numberText.c_str()), path, what);
  check(contour->setROIDisplayColor(
            (std::to_string(rgb[0]) + "\\" + std::to_string(rgb[1]) + "\\" + std::to_string(rgb[2])).c_str()),
        path, what);
  for (const auto& [k, polygon] : roi.polygons) addContour(contour->getContourSequence(), g, k, polygon, source, path);
  DRTRTROIObservationsSequence::Item* observation = nullptr;
  check(rt.getRTROIObservationsSequence().addItem(observation), path, what);
  check(observation->setObservationNumber(numberText.c_str()), path, what);
  check(observation->setReferencedROINumber(numberText.c_str()), path, what);
}

void writeRtStructFile(const std::string& path, const std::string& reportedPath, const LabelMap& labelMap,
                       const DicomSourceSeries* source) {
  quietDcmtk();
  const GridGeometry& g = labelMap.labels.geometry;
  const std::vector<RoiContours> rois = contoursOf(labelMap.labels);
  if (rois.empty())
    throw BadInput(reportedPath, "the label map holds no labels; an RT Structure Set needs at least one ROI");
  DRTStructureSetIOD rt;
  auto set = [&](const OFCondition& c, const char* what) { check(c, reportedPath, std::string("cannot set ") + what); };
  if (source) setSourceAttributes(rt, *source, reportedPath);
  const std::string study = source && !source->studyInstanceUid.empty() ? source->studyInstanceUid : newUid();
  const std::string frameOfReference =
      source && !source->frameOfReferenceUid.empty() ? source->frameOfReferenceUid : newUid();
  OFString date, time;
  DcmDate::getCurrentDate(date);
  DcmTime::getCurrentTime(time);
  set(rt.setStudyInstanceUID(study.c_str()), "Study Instance UID");
  set(rt.setSeriesInstanceUID(newUid().c_str()), "Series Instance UID");
  set(rt.setSeriesNumber("1000"), "Series Number");
  set(rt.setSeriesDescription("Vesalius label map"), "Series Description");
  set(rt.setModality("RTSTRUCT"), "Modality");
  set(rt.setManufacturer("Vesalius"), "Manufacturer");
  set(rt.setManufacturerModelName("Vesalius"), "Manufacturer's Model Name");
  set(rt.setSoftwareVersions(VESALIUS_VERSION), "Software Versions");
  set(rt.setSOPClassUID(UID_RTStructureSetStorage), "SOP Class UID");
  set(rt.setSOPInstanceUID(newUid().c_str()), "SOP Instance UID");
  set(rt.setInstanceCreationDate(date), "Instance Creation Date");
  set(rt.setInstanceCreationTime(time), "Instance Creation Time");
  set(rt.setInstanceNumber("1"), "Instance Number");
  set(rt.setStructureSetLabel("Vesalius"), "Structure Set Label");
  set(rt.setStructureSetName("Label map"), "Structure Set Name");
  set(rt.setStructureSetDate(date), "Structure Set Date");
  set(rt.setStructureSetTime(time), "Structure Set Time");
  addReferencedFrameOfReference(rt, frameOfReference, study, source, reportedPath);
  for (std::size_t n = 0; n < rois.size(); ++n)
    addRoi(rt, labelMap.table, rois[n], int(n + 1), frameOfReference, g, source, reportedPath);
  DcmFileFormat file;
  check(rt.write(*file.getDataset()), reportedPath, "cannot make the RT Structure Set");
  // Implicit VR, whose elements have 32-bit lengths: in Explicit VR a decimal string (DS) holds at most
  // 65534 bytes (PS3.5 7.1.2), less than the Contour Data of a contour with some 1500 points.
  saveWhole(file, EXS_LittleEndianImplicit, path, reportedPath, "RT Structure Set");
}

// ------------------------------------------------------------------------------------------ reading

struct Roi {
  LabelEntry entry;
  std::int32_t number = 0;
  std::map<int, std::vector<std::vector<Eigen::Vector2d>>> polygons;  // by slice, in the grid's (i, j)
};

// One contour's points on the grid: its slice and (i, j) polygon. BadInput for the problems the header lists.
std::pair<int, std::vector<Eigen::Vector2d>> contourOnGrid(DRTContourSequence::Item& contour, const GridGeometry& g,
                                                           const std::string& where, const std::string& path) {
  OFVector<Float64> data;
  contour.getContourData(data);
  if (data.size() % 3 != 0)
    throw BadInput(path, where + " has " + std::to_string(data.size()) + " Contour Data values, not a multiple of 3");
  const std::size_t count = data.size() / 3;
  Sint32 declared = 0;
  if (contour.getNumberOfContourPoints(declared).good() && declared != Sint32(count))
    throw BadInput(path, where + " declares " + std::to_string(declared) + " points but holds " +
                             std::to_string(count));
  if (count < 3)
    throw BadInput(path, where + " has " + std::to_string(count) + " points; a closed contour needs at least 3");
  std::vector<Eigen::Vector3d> points(count);
  Eigen::Vector3d centre = Eigen::Vector3d::Zero(), normal = Eigen::Vector3d::Zero();
  for (std::size_t n = 0; n < count; ++n) points[n] = {data[3 * n], data[3 * n + 1], data[3 * n + 2]};
  for (std::size_t n = 0; n < count; ++n) {
    centre += points[n] / double(count);
    normal += points[n].cross(points[(n + 1) % count]);  // Newell's method: twice the area vector
  }
  if (normal.norm() > 1e-9) {
    normal.normalize();
    double off = 0;
    for (const Eigen::Vector3d& p : points) off = std::max(off, std::abs(normal.dot(p - centre)));
    if (off > kPlanarTolerance)
      throw BadInput(path, where + " is not planar: a point lies " + decimal(off) + " mm off its plane");
  }
  std::vector<Eigen::Vector2d> polygon(count);
  double low = 1e300, high = -1e300;
  for (std::size_t n = 0; n < count; ++n) {
    const Eigen::Vector3d index = g.worldToIndex(points[n]);
    polygon[n] = index.head<2>();
    low = std::min(low, index.z()), high = std::max(high, index.z());
  }
  const int k = int(std::lround((low + high) / 2));
  if (high - k > 0.25 || k - low > 0.25)
    throw BadInput(path, where + " lies on no slice of the grid (at slice index " + decimal(low) +
                             (high - low > 1e-6 ? " to " + decimal(high) : "") + ")");
  if (k < 0 || k >= g.size.z())
    throw BadInput(path, where + " lies off every slice of the grid (at slice index " + std::to_string(k) +
                             "; the grid has 0 to " + std::to_string(g.size.z() - 1) + ")");
  return {k, polygon};
}

// Runs of voxels (first linear index, length) inside an odd number of a slice's polygons: voxel centres
// (integer i, j) against edge crossings of each row, the half-open rule counting a vertex once.
void fillSlice(const std::vector<std::vector<Eigen::Vector2d>>& polygons, const GridGeometry& g, int k,
               std::vector<std::pair<std::int64_t, int>>& runs) {
  double low = 1e300, high = -1e300;
  for (const auto& polygon : polygons)
    for (const Eigen::Vector2d& p : polygon) low = std::min(low, p.y()), high = std::max(high, p.y());
  const int j0 = std::max(0, int(std::ceil(low))), j1 = std::min(g.size.y() - 1, int(std::floor(high)));
  if (j1 < j0) return;
  std::vector<std::vector<double>> crossings(std::size_t(j1 - j0 + 1));
  for (const auto& polygon : polygons)
    for (std::size_t n = 0; n < polygon.size(); ++n) {
      const Eigen::Vector2d &a = polygon[n], &b = polygon[(n + 1) % polygon.size()];
      const double y0 = std::min(a.y(), b.y()), y1 = std::max(a.y(), b.y());
      for (int j = std::max(j0, int(std::ceil(y0))); j <= j1 && j < y1; ++j)
        crossings[j - j0].push_back(a.x() + (j - a.y()) * (b.x() - a.x()) / (b.y() - a.y()));
    }
  for (int j = j0; j <= j1; ++j) {
    std::vector<double>& x = crossings[j - j0];
    std::sort(x.begin(), x.end());
    for (std::size_t n = 0; n + 1 < x.size(); n += 2) {
      const int i0 = std::max(0, int(std::floor(x[n])) + 1), i1 = std::min(g.size.x() - 1, int(std::ceil(x[n + 1])) - 1);
      if (i1 >= i0) runs.emplace_back(g.linearIndex(i0, j, k), i1 - i0 + 1);
    }
  }
}

std::vector<Roi> roisOf(DRTStructureSetIOD& rt, const std::string& path) {
  DRTStructureSetROISequence& structures = rt.getStructureSetROISequence();
  if (structures.getNumberOfItems() == 0) throw BadInput(path, "the RT Structure Set holds no ROIs");
  std::vector<Roi> rois(structures.getNumberOfItems());
  std::vector<bool> taken(65536, false);
  bool described = true, numbered = true;
  std::vector<std::int32_t> numbers;
  for (std::size_t n = 0; n < rois.size(); ++n) {
    DRTStructureSetROISequence::Item& item = structures.getItem(n);
    Sint32 number = 0;
    if (item.getROINumber(number).bad())
      throw BadInput(path, "Structure Set ROI " + std::to_string(n + 1) + " has no ROI Number");
    if (std::find(numbers.begin(), numbers.end(), number) != numbers.end())
      throw BadInput(path, "two ROIs have ROI Number " + std::to_string(number));
    numbers.push_back(number);
    OFString name, description;
    item.getROIName(name);
    item.getROIDescription(description);
    Roi& roi = rois[n];
    roi.number = number;
    roi.entry.name = name.empty() ? "ROI_" + std::to_string(number) : name.c_str();
    const Label id = labelOfDescription(description.c_str());
    if (id != 0 && !taken[id]) taken[id] = true, roi.entry.id = id;
    else described = false;
    numbered &= number >= 1 && number <= 65535;
  }
  for (std::size_t n = 0; n < rois.size(); ++n) {
    if (!described) rois[n].entry.id = Label(numbered ? rois[n].number : std::int32_t(n + 1));
    rois[n].entry.color = defaultLabelColor(rois[n].entry.id);
  }
  return rois;
}

// Loads the structure set at `path` into `rt`; BadInput for a file that is none.
void readStructureSet(DRTStructureSetIOD& rt, const std::string& path) {
  DcmFileFormat file;
  loadDicom(file, path, true);
  const std::string sopClass = sopClassOf(file);
  if (sopClass != UID_RTStructureSetStorage)
    throw BadInput(path, "not a DICOM RT Structure Set (SOP Class UID " + (sopClass.empty() ? "missing" : sopClass) + ")");
  check(rt.read(*file.getDataset()), path, "cannot read the RT Structure Set");
}

// The frames of reference the contours are in: those the ROIs refer to, else (ROIs naming none) those of
// the Referenced Frame of Reference Sequence. Empty when the structure set names none.
std::set<std::string> framesOfReference(DRTStructureSetIOD& rt) {
  std::set<std::string> frames;
  OFString uid;
  DRTStructureSetROISequence& structures = rt.getStructureSetROISequence();
  for (std::size_t n = 0; n < structures.getNumberOfItems(); ++n)
    if (structures.getItem(n).getReferencedFrameOfReferenceUID(uid).good() && !uid.empty()) frames.insert(uid.c_str());
  DRTReferencedFrameOfReferenceSequence& listed = rt.getReferencedFrameOfReferenceSequence();
  for (std::size_t n = 0; frames.empty() && n < listed.getNumberOfItems(); ++n)
    if (listed.getItem(n).getFrameOfReferenceUID(uid).good() && !uid.empty()) frames.insert(uid.c_str());
  return frames;
}

// The ROIs' contours filled onto `grid` (see the header).
LabelMap rasterize(DRTStructureSetIOD& rt, const GridGeometry& grid, const std::string& path) {
  std::vector<Roi> rois = roisOf(rt, path);
  DRTROIContourSequence& contours = rt.getROIContourSequence();
  for (std::size_t n = 0; n < contours.getNumberOfItems(); ++n) {
    DRTROIContourSequence::Item& item = contours.getItem(n);
    Sint32 number = 0;
    item.getReferencedROINumber(number);
    const auto roi = std::find_if(rois.begin(), rois.end(), [&](const Roi& r) { return r.number == number; });
    if (roi == rois.end())
      throw BadInput(path, "ROI Contour " + std::to_string(n + 1) + " refers to ROI " + std::to_string(number) +
                               ", which the Structure Set ROI Sequence does not list");
    Sint32 rgb[3];
    bool coloured = true;
    for (int c = 0; c < 3; ++c) coloured &= item.getROIDisplayColor(rgb[c], c).good() && rgb[c] >= 0 && rgb[c] <= 255;
    roi->entry.color = coloured ? std::array<std::uint8_t, 3>{{std::uint8_t(rgb[0]), std::uint8_t(rgb[1]),
                                                              std::uint8_t(rgb[2])}}
                                : defaultLabelColor(roi->entry.id);
    DRTContourSequence& sequence = item.getContourSequence();
    for (std::size_t c = 0; c < sequence.getNumberOfItems(); ++c) {
      DRTContourSequence::Item& contour = sequence.getItem(c);
      const std::string where = "contour " + std::to_string(c + 1) + " of ROI '" + roi->entry.name + "'";
      OFString type;
      contour.getContourGeometricType(type);
      if (type == "POINT") continue;
      if (type != "CLOSED_PLANAR")
        throw BadInput(path, where + " is " + (type.empty() ? "of no type" : std::string(type.c_str())) +
                                 "; only CLOSED_PLANAR contours enclose voxels");
      auto [k, polygon] = contourOnGrid(contour, grid, where, path);
      roi->polygons[k].push_back(std::move(polygon));
    }
  }
  // Each ROI's voxels as runs; painted from the largest ROI to the smallest, so the smallest wins overlaps.
  std::vector<std::vector<std::pair<std::int64_t, int>>> runs(rois.size());
  std::vector<std::int64_t> voxels(rois.size(), 0);
  for (std::size_t n = 0; n < rois.size(); ++n) {
    for (const auto& [k, polygons] : rois[n].polygons) fillSlice(polygons, grid, k, runs[n]);
    for (const auto& run : runs[n]) voxels[n] += run.second;
  }
  std::vector<std::size_t> order(rois.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return voxels[a] != voxels[b] ? voxels[a] > voxels[b] : a > b; });
  LabelMap map;
  map.labels = Grid<Label>(grid, 0);
  for (std::size_t n : order)
    for (const auto& [start, length] : runs[n])
      std::fill_n(map.labels.values.begin() + start, length, rois[n].entry.id);
  for (const Roi& roi : rois) map.table.add(roi.entry);
  return map;
}

}  // namespace

bool isDicomRtStructPath(const std::string& path) {
  const std::string suffix = ".rtstruct.dcm";
  if (path.size() < suffix.size()) return false;
  std::string tail = path.substr(path.size() - suffix.size());
  std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return tail == suffix;
}

bool isDicomRtStructFile(const std::string& path) { return isDicomFileOfClass(path, UID_RTStructureSetStorage); }

void writeDicomRtStruct(const std::string& path, const LabelMap& labelMap, const DicomSourceSeries* source,
                        const WriteOptions& options) {
  if (std::int64_t(labelMap.labels.values.size()) != labelMap.labels.geometry.voxelCount())
    throw std::invalid_argument(path + ": label values do not fill the grid");
  writeAtomically(path, options, [&](const std::string& temporaryPath) {
    writeRtStructFile(temporaryPath, path, labelMap, source);
  });
}

LabelMap readDicomRtStruct(const std::string& path, const GridGeometry& grid) {
  DRTStructureSetIOD rt;
  readStructureSet(rt, path);
  return rasterize(rt, grid, path);
}

LabelMap readDicomRtStructOntoScan(const std::string& path, const std::string& scanPath,
                                   const std::string& tablePath) {
  DRTStructureSetIOD rt;
  readStructureSet(rt, path);
  const std::optional<DicomSourceSeries> scan = readDicomSource(scanPath);
  if (scan && !scan->frameOfReferenceUid.empty())
    for (const std::string& frame : framesOfReference(rt))
      if (frame != scan->frameOfReferenceUid)
        throw BadInput(path, "its contours are in Frame of Reference " + frame + " and the scan " + scanPath +
                                 " is in " + scan->frameOfReferenceUid +
                                 ": another patient space, where they would land in the wrong place");
  LabelMap map = rasterize(rt, describeScan(scanPath).geometry, path);
  applyExplicitTable(map, tablePath);
  return map;
}

}  // namespace vesalius::io
