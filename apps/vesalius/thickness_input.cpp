// Fat thickness and the fat forest from the command line (thickness_input.h).
#include "thickness_input.h"

#include "label_map_input.h"

#include "vesalius/core/atomic_file.h"
#include "vesalius/core/error.h"
#include "vesalius/fat/thickness_at_vertices.h"
#include "vesalius/fat/thickness_texture.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/text_file.h"
#include "vesalius/segmentation/label_ops.h"

#include <cmath>
#include <filesystem>
#include <vector>

namespace vesalius::cli {

namespace {

fat::ThicknessTexture readTexture(const std::string& path) {
  const Image image = io::readScan(path);
  if (image.geometry.size.z() != 1)
    throw BadInput(path, "a thickness texture is one slice (W x H x 1); this image has " +
                             std::to_string(image.geometry.size.z()));
  fat::ThicknessTexture t;
  t.width = image.geometry.size.x(), t.height = image.geometry.size.y();
  t.values = image.values;
  return t;
}

fat::Mask maskOfLabel(const LabelMap& map, Label id, const std::string& role, const std::string& path) {
  fat::Mask mask = segmentation::maskOf(map.labels, id);
  if (segmentation::countVoxels(mask) == 0)
    throw BadInput(path, "no voxel has the " + role + " label " + std::to_string(id) +
                             (map.table.find(id) ? " (" + map.table.find(id)->name + ")" : std::string()));
  return mask;
}

}  // namespace

Eigen::VectorXd readThickness(const std::string& spec, const TriMesh& skin, const std::string& skinPath,
                              std::string& kind) {
  try {
    std::size_t used = 0;
    const double value = std::stod(spec, &used);
    if (used == spec.size()) {
      if (!(value >= 0)) throw UsageError("--thickness " + spec + ": a thickness is a number >= 0 (mm) or a file");
      kind = "uniform";
      return Eigen::VectorXd::Constant(skin.V.rows(), value);
    }
  } catch (const std::logic_error&) {
    // not a number: a file
  }
  if (!std::filesystem::exists(spec)) throw BadInput(spec, "no such file (nor a thickness in mm)");
  const std::string ext = fileExtension(spec);
  if (ext == ".nii" || ext == ".nii.gz" || ext == ".nrrd" || ext == ".nhdr" || ext == ".mha" || ext == ".mhd") {
    kind = "texture";
    return fat::sampleTextureAtVertices(readTexture(spec), skin, skinPath);
  }
  Eigen::VectorXd t;
  if (io::meshFileKind(spec) == io::MeshKind::kSurface) {
    kind = "mesh attribute";
    const TriMesh m = io::readTriMesh(spec);
    const auto it = m.vertexAttributes.real.find("fat_thickness");
    if (it == m.vertexAttributes.real.end() || it->second.cols() != 1)
      throw BadInput(spec, "no point attribute fat_thickness (write one with 'vesalius fat forest --out-mesh')");
    t = it->second.col(0);
  } else {
    kind = "text";
    std::vector<double> values;
    const std::string text = io::readTextFile(spec);
    io::LineReader reader(text, spec);
    for (std::string_view line; reader.next(line);)
      for (std::string_view token : io::splitWhitespace(line))
        values.push_back(io::parseDouble(token, reader, "thickness"));
    t = Eigen::Map<const Eigen::VectorXd>(values.data(), Eigen::Index(values.size()));
  }
  if (t.size() != skin.V.rows())
    throw BadInput(spec, std::to_string(t.size()) + " thickness values for the " + std::to_string(skin.V.rows()) +
                             " vertices of " + skinPath);
  return t;
}

void addForestSourceOptions(CLI::App& cmd, ForestSource& o, bool required) {
  auto* labels = addLabelsOption(cmd, o.labels, o.grid,
                                 "Label map with skin and fat classes (e.g. from 'vesalius segment', CT or MRI)");
  if (required) labels->required();
  cmd.add_option("--table", o.table, "Label table (.tsv or Slicer .ctbl); default: the one beside the label map");
  cmd.add_option("--skin-label", o.skinLabel, "Skin label id or name")->capture_default_str();
  cmd.add_option("--fat-label", o.fatLabel, "Fat label id or name")->capture_default_str();
  cmd.add_option("--fat-mask", o.fatMask,
                 "Fat from a mask on the same grid instead (any nonzero voxel; e.g. TotalSegmentator's "
                 "subcutaneous_fat.nii.gz)");
  cmd.add_option("--max-distance", o.maxDistance, "Leave fat farther than this from the skin unreached (mm)");
  cmd.add_option("--gather-radius", o.gatherRadius,
                 "A skin voxel takes the largest tree thickness within this radius (mm); -1: one voxel "
                 "diagonal; 0: the paper's per-tree value")
      ->capture_default_str();
  cmd.add_option("--vertex-radius", o.vertexRadius,
                 "Skin voxels within this distance of a vertex give its thickness (mm); 0: one voxel diagonal")
      ->capture_default_str();
}

LoadedForest loadForest(const ForestSource& o, io::Report& report, Progress& progress) {
  LoadedForest l;
  report.input("labels", o.labels);
  if (!o.fatMask.empty()) report.input("fat_mask", o.fatMask);
  l.map = readLabelsOption(o.labels, o.table, o.grid, report);
  const Label skinId = resolveLabel(l.map, o.skinLabel, o.labels);
  l.skin = maskOfLabel(l.map, skinId, "skin", o.labels);
  if (o.fatMask.empty()) {
    l.fat = maskOfLabel(l.map, resolveLabel(l.map, o.fatLabel, o.labels), "fat", o.labels);
  } else {
    const LabelMap m = io::readLabelMap(o.fatMask);  // any nonzero voxel is fat
    l.fat = fat::Mask(m.labels.geometry, 0);
    for (std::size_t v = 0; v < l.fat.values.size(); ++v) l.fat.values[v] = m.labels.values[v] != 0;
  }
  report.parameter("skin_label", skinId);
  report.parameter("fat", o.fatMask.empty() ? nlohmann::json(o.fatLabel) : nlohmann::json(o.fatMask));
  report.parameter("max_distance_mm", std::isfinite(o.maxDistance) ? nlohmann::json(o.maxDistance) : nullptr);
  report.parameter("gather_radius_mm", o.gatherRadius);

  fat::FatForestOptions options;
  options.maxDistanceMm = o.maxDistance;
  options.gatherRadiusMm = o.gatherRadius;
  progress.begin("fat forest", "shortest paths from the skin through the fat");
  l.forest = std::make_unique<fat::FatForest>(l.skin, l.fat, options, o.fatMask.empty() ? o.labels : o.fatMask);
  progress.end();
  report.stage("fat forest", l.forest->statistics().seconds);
  return l;
}

Eigen::VectorXd vertexThickness(const std::string& spec, const TriMesh& skin, const std::string& skinPath,
                                const LoadedForest& l, const ForestSource& source, io::Report& report) {
  if (!spec.empty()) {
    std::string kind;
    Eigen::VectorXd t = readThickness(spec, skin, skinPath, kind);
    report.parameter("thickness", spec);
    report.parameter("thickness_from", kind);
    return t;
  }
  fat::VertexThicknessOptions options;
  options.radiusMm = source.vertexRadius;
  const fat::VertexThickness t = fat::thicknessAtVertices(*l.forest, skin.V, skin.F, options);
  report.parameter("thickness_from", "forest");
  report.metric("vertices", {{"measured", t.measured}, {"filled", t.filled}, {"unreached", t.unreached}});
  return t.thickness;
}

}  // namespace vesalius::cli
