// 3D Slicer .seg.nrrd files (slicer_segmentation.h): the Segment fields, layers and their merge. The ITK
// work is behind slicer_segmentation_itk.h; this file sees the system Eigen only.
#include "vesalius/io/slicer_segmentation.h"

#include "raw_geometry.h"
#include "slicer_segmentation_itk.h"

#include "vesalius/core/error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

namespace vesalius::io {

namespace {

using Fields = std::vector<std::pair<std::string, std::string>>;


itk_seam::RawHeader rawHeaderOf(const GridGeometry& geometry) {
  itk_seam::RawHeader header;
  for (int axis = 0; axis < 3; ++axis) {
    header.size[axis] = geometry.size[axis];
    header.origin[axis] = geometry.origin[axis];
    header.spacing[axis] = geometry.spacing[axis];
    for (int column = 0; column < 3; ++column) header.direction[3 * axis + column] = geometry.direction(axis, column);
  }
  return header;
}

// "Segment12_Name" -> (12, "Name"); nullopt for keys of another shape (Segmentation_...).
std::optional<std::pair<int, std::string>> segmentKey(const std::string& key) {
  const std::string prefix = "Segment";
  std::size_t at = prefix.size();
  if (key.rfind(prefix, 0) != 0 || at >= key.size() || !std::isdigit(static_cast<unsigned char>(key[at])))
    return std::nullopt;
  int index = 0;
  while (at < key.size() && std::isdigit(static_cast<unsigned char>(key[at]))) {
    index = index * 10 + (key[at] - '0');
    if (index > 1000000) return std::nullopt;
    ++at;
  }
  if (at >= key.size() || key[at] != '_') return std::nullopt;
  return std::make_pair(index, key.substr(at + 1));
}

std::vector<double> numbers(const std::string& text, const std::string& path, const std::string& key,
                            std::size_t count) {
  std::istringstream in(text);
  std::vector<double> values;
  for (double v; in >> v;) values.push_back(v);
  if (values.size() != count || !(in.eof()))
    throw BadInput(path, key + " is '" + text + "', expected " + std::to_string(count) + " numbers");
  return values;
}

long long wholeNumber(const std::string& text, const std::string& path, const std::string& key, long long low,
                      long long high) {
  const double value = numbers(text, path, key, 1)[0];
  if (!(value >= double(low) && value <= double(high) && value == std::floor(value)))
    throw BadInput(path, key + " is '" + text + "', expected a whole number from " + std::to_string(low) +
                             " to " + std::to_string(high));
  return (long long)value;
}

std::string segmentLabel(const SlicerSegment& segment) {
  return "'" + segment.name + "' (layer " + std::to_string(segment.layer) + ", value " +
         std::to_string(segment.labelValue) + ")";
}

}  // namespace

bool isSlicerSegmentationPath(const std::string& path) { return fileExtension(path) == ".seg.nrrd"; }

SlicerSegmentation readSlicerSegmentation(const std::string& path) {
  itk_seam::RawSegmentationFile file = itk_seam::readSegmentationFile(path);
  const GridGeometry geometry = geometryOf(file.header);
  geometry.validate(path);
  const int layerCount = file.header.components;

  std::map<int, std::map<std::string, std::string>> bySegment;
  for (const auto& [key, value] : file.fields)
    if (auto parsed = segmentKey(key)) bySegment[parsed->first][parsed->second] = value;
  bool anyLayerField = false;
  for (const auto& [index, fields] : bySegment) anyLayerField |= fields.count("Layer") > 0;

  SlicerSegmentation segmentation;
  for (const auto& entry : bySegment) {
    // Not a structured binding: C++17 lambdas cannot capture those (clang refuses; the fuzz build uses it).
    const int index = entry.first;
    const std::map<std::string, std::string>& fields = entry.second;
    const std::string prefix = "Segment" + std::to_string(index) + "_";
    auto field = [&](const char* name) -> const std::string* {
      const auto found = fields.find(name);
      return found == fields.end() ? nullptr : &found->second;
    };
    SlicerSegment segment;
    if (const std::string* id = field("ID")) segment.id = *id;
    if (const std::string* value = field("LabelValue"))
      segment.labelValue = Label(wholeNumber(*value, path, prefix + "LabelValue", 1, 65535));
    if (const std::string* layer = field("Layer"))
      segment.layer = int(wholeNumber(*layer, path, prefix + "Layer", 0, 1 << 20));
    else if (!anyLayerField && layerCount > 1)
      segment.layer = index;  // older Slicer: one layer per segment
    if (segment.layer >= layerCount)
      throw BadInput(path, prefix + "Layer is " + std::to_string(segment.layer) + " but the file holds " +
                               std::to_string(layerCount) + (layerCount == 1 ? " layer" : " layers"));
    const std::string* name = field("Name");
    segment.name = name && !name->empty() ? *name
                   : !segment.id.empty()  ? segment.id
                                          : "Segment_" + std::to_string(segment.labelValue);
    segment.color = defaultLabelColor(segment.labelValue);
    if (const std::string* color = field("Color")) {
      const std::vector<double> rgb = numbers(*color, path, prefix + "Color", 3);
      for (int c = 0; c < 3; ++c) {
        if (!(rgb[c] >= 0 && rgb[c] <= 1))
          throw BadInput(path, prefix + "Color is '" + *color + "', expected three numbers from 0 to 1");
        segment.color[c] = std::uint8_t(std::lround(rgb[c] * 255));
      }
    }
    if (const std::string* extent = field("Extent")) {
      const std::vector<double> e = numbers(*extent, path, prefix + "Extent", 6);
      segment.extent.emplace();
      for (int k = 0; k < 6; ++k) (*segment.extent)[k] = int(std::lround(e[k]));
    }
    for (const SlicerSegment& other : segmentation.segments)
      if (other.layer == segment.layer && other.labelValue == segment.labelValue)
        throw BadInput(path, "segments '" + other.name + "' and '" + segment.name + "' both have value " +
                                 std::to_string(segment.labelValue) + " in layer " + std::to_string(segment.layer));
    segmentation.segments.push_back(std::move(segment));
  }

  const std::size_t voxels = std::size_t(geometry.voxelCount());
  segmentation.layers.assign(std::size_t(layerCount), Grid<Label>(geometry, 0));
  for (std::size_t n = 0; n < voxels; ++n)
    for (int layer = 0; layer < layerCount; ++layer)
      segmentation.layers[layer].values[n] = file.values[n * layerCount + layer];
  return segmentation;
}

std::vector<LabelMap> segmentationLayerMaps(const SlicerSegmentation& segmentation) {
  std::vector<LabelMap> maps(segmentation.layers.size());
  for (std::size_t layer = 0; layer < maps.size(); ++layer) maps[layer].labels = segmentation.layers[layer];
  for (const SlicerSegment& segment : segmentation.segments)
    maps[segment.layer].table.add(LabelEntry{segment.labelValue, segment.name, segment.color});
  return maps;
}

std::vector<SegmentOverlap> segmentOverlaps(const SlicerSegmentation& segmentation) {
  std::vector<SegmentOverlap> overlaps;
  const std::size_t layers = segmentation.layers.size();
  if (layers < 2) return overlaps;
  // segment index of (layer, value); values without a segment are not segments and are skipped
  std::map<std::pair<std::size_t, Label>, std::size_t> index;
  for (std::size_t s = 0; s < segmentation.segments.size(); ++s)
    index[{std::size_t(segmentation.segments[s].layer), segmentation.segments[s].labelValue}] = s;
  std::map<std::pair<std::size_t, std::size_t>, std::int64_t> counts;
  const std::size_t voxels = segmentation.layers[0].values.size();
  std::vector<std::size_t> here;
  for (std::size_t n = 0; n < voxels; ++n) {
    here.clear();
    for (std::size_t layer = 0; layer < layers; ++layer) {
      const Label value = segmentation.layers[layer].values[n];
      if (value == 0) continue;
      const auto found = index.find({layer, value});
      if (found != index.end()) here.push_back(found->second);
    }
    for (std::size_t a = 0; a < here.size(); ++a)
      for (std::size_t b = a + 1; b < here.size(); ++b) ++counts[{here[a], here[b]}];
  }
  for (const auto& [pair, count] : counts) overlaps.push_back(SegmentOverlap{pair.first, pair.second, count});
  return overlaps;
}

LabelMap mergeSegmentationLayers(const SlicerSegmentation& segmentation, const std::string& path) {
  const std::vector<SegmentOverlap> overlaps = segmentOverlaps(segmentation);
  if (!overlaps.empty()) {
    std::string listing;
    for (std::size_t k = 0; k < overlaps.size() && k < 3; ++k) {
      const SegmentOverlap& o = overlaps[k];
      listing += (k ? "; " : "") + segmentLabel(segmentation.segments[o.first]) + " and " +
                 segmentLabel(segmentation.segments[o.second]) + " share " + std::to_string(o.voxels) + " voxels";
    }
    if (overlaps.size() > 3) listing += "; and " + std::to_string(overlaps.size() - 3) + " more pairs";
    throw BadInput(path, "segments overlap, and a label map holds one label per voxel: " + listing +
                             " (remove the overlap in Slicer, or save the segments to separate files)");
  }
  LabelMap merged;
  merged.labels = segmentation.layers.empty() ? Grid<Label>() : Grid<Label>(segmentation.layers[0].geometry, 0);
  std::set<Label> used;
  // Values present in layer 0 and the values of its segments keep their id.
  for (const SlicerSegment& segment : segmentation.segments)
    if (segment.layer == 0) used.insert(segment.labelValue);
  if (!segmentation.layers.empty())
    for (Label value : segmentation.layers[0].values)
      if (value != 0) used.insert(value);
  Label next = 1;
  auto freeId = [&] {
    while (used.count(next)) {
      if (next == 65535) throw BadInput(path, "more segments than label ids 1..65535");
      ++next;
    }
    used.insert(next);
    return next;
  };
  for (std::size_t layer = 0; layer < segmentation.layers.size(); ++layer) {
    std::map<Label, Label> ids;  // value in this layer -> id in the merged map
    for (const SlicerSegment& segment : segmentation.segments) {
      if (std::size_t(segment.layer) != layer) continue;
      Label id = segment.labelValue;
      if (layer > 0) id = used.insert(segment.labelValue).second ? segment.labelValue : freeId();
      ids[segment.labelValue] = id;
      merged.table.add(LabelEntry{id, segment.name, segment.color});
    }
    const std::vector<Label>& values = segmentation.layers[layer].values;
    for (std::size_t n = 0; n < values.size(); ++n) {
      const Label value = values[n];
      if (value == 0) continue;
      auto found = ids.find(value);
      if (found == ids.end()) found = ids.emplace(value, layer == 0 ? value : freeId()).first;
      Label& target = merged.labels.values[n];
      if (target != 0)
        throw BadInput(path, "value " + std::to_string(value) + " of layer " + std::to_string(layer) +
                                 " overlaps another layer's voxels, and a label map holds one label per voxel");
      target = found->second;
    }
  }
  return merged;
}

void writeSlicerSegmentation(const std::string& path, const LabelMap& labelMap, const WriteOptions& options) {
  const Grid<Label>& labels = labelMap.labels;
  if (std::int64_t(labels.values.size()) != labels.geometry.voxelCount())
    throw std::invalid_argument(path + ": " + std::to_string(labels.values.size()) + " values for a grid of " +
                                std::to_string(labels.geometry.voxelCount()) + " voxels");
  // Every listed entry and every id present becomes a segment, with its voxel bounding box.
  std::map<Label, std::array<int, 6>> extents;
  for (const LabelEntry& entry : labelMap.table.entries) extents[entry.id] = {{0, -1, 0, -1, 0, -1}};
  const int nx = labels.geometry.size.x(), ny = labels.geometry.size.y(), nz = labels.geometry.size.z();
  for (int k = 0, n = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i, ++n) {
        const Label id = labels.values[std::size_t(n)];
        if (id == 0) continue;
        auto [at, added] = extents.try_emplace(id, std::array<int, 6>{{i, i, j, j, k, k}});
        std::array<int, 6>& e = at->second;
        if (!added && e[1] < e[0]) e = {{i, i, j, j, k, k}};  // listed entry seen for the first time
        e[0] = std::min(e[0], i), e[1] = std::max(e[1], i);
        e[2] = std::min(e[2], j), e[3] = std::max(e[3], j);
        e[4] = std::min(e[4], k), e[5] = std::max(e[5], k);
      }
  Fields fields;
  int index = 0;
  for (const auto& [id, extent] : extents) {
    const LabelEntry* entry = labelMap.table.find(id);
    const std::string name = entry ? entry->name : "label_" + std::to_string(id);
    const std::array<std::uint8_t, 3> color = entry ? entry->color : defaultLabelColor(id);
    const std::string prefix = "Segment" + std::to_string(index++) + "_";
    char rgb[64];
    std::snprintf(rgb, sizeof rgb, "%.6g %.6g %.6g", color[0] / 255.0, color[1] / 255.0, color[2] / 255.0);
    std::string box;
    for (int v : extent) box += (box.empty() ? "" : " ") + std::to_string(v);
    fields.emplace_back(prefix + "Color", rgb);
    fields.emplace_back(prefix + "ColorAutoGenerated", "0");
    fields.emplace_back(prefix + "Extent", box);
    fields.emplace_back(prefix + "ID", "Segment_" + std::to_string(id));
    fields.emplace_back(prefix + "LabelValue", std::to_string(id));
    fields.emplace_back(prefix + "Layer", "0");
    fields.emplace_back(prefix + "Name", name);
    fields.emplace_back(prefix + "NameAutoGenerated", "0");
    fields.emplace_back(prefix + "Tags", "|");  // no tags; older Slicer needs the closing '|'
  }
  fields.emplace_back("Segmentation_ContainedRepresentationNames", "Binary labelmap|");
  fields.emplace_back("Segmentation_MasterRepresentation", "Binary labelmap");
  fields.emplace_back("Segmentation_ReferenceImageExtentOffset", "0 0 0");
  for (const auto& [key, value] : fields)
    if (value.find_first_of("\r\n") != std::string::npos)
      throw BadInput(path, key + " holds a line break, which a NRRD header cannot carry");
  const itk_seam::RawHeader header = rawHeaderOf(labels.geometry);
  try {
    writeAtomically(path, options, [&](const std::string& temporaryPath) {
      itk_seam::writeSegmentationFile(temporaryPath, header, fields, labels.values);
    });
  } catch (const BadInput& error) {
    throw BadInput(path, error.problem());
  }
}

}  // namespace vesalius::io
