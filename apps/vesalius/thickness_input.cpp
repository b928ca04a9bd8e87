// Fat thickness from the command line (thickness_input.h).
#include "thickness_input.h"

#include "vesalius/core/atomic_file.h"
#include "vesalius/core/error.h"
#include "vesalius/fat/thickness_texture.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/text_file.h"

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

}  // namespace vesalius::cli
