#include "picker_inputs.h"

#include "autosave.h"

#include "vesalius/core/error.h"
#include "vesalius/io/marker_io.h"
#include "vesalius/io/mesh_io.h"

#include <fstream>
#include <iostream>

namespace vesalius::picker {
namespace {

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

bool userAgreesToRestore(const std::string& autosavePath) {
  std::cout << "Unsaved markers from an earlier session are in " << autosavePath
            << ". Restore them? [y/N] " << std::flush;
  std::string answer;
  std::getline(std::cin, answer);
  return !answer.empty() && (answer[0] == 'y' || answer[0] == 'Y');
}

}  // namespace

void addNamedLandmarks(MarkerSet& markers, const std::string& path) {
  std::ifstream file(path);
  if (!file) throw BadInput(path, "cannot open the landmark names file");
  std::string line;
  while (std::getline(file, line)) {
    const std::string name = trimmed(line);
    if (name.empty() || name[0] == '#') continue;
    bool present = false;
    for (const Marker& m : markers.markers) present = present || (m.kind == MarkerKind::Landmark && m.label == name);
    if (present) continue;
    Marker named;
    named.label = name;
    named.kind = MarkerKind::Landmark;
    named.status = MarkerStatus::Undefined;
    markers.markers.push_back(named);
  }
}

MarkerSet initialMarkers(const PickerOptions& options, const std::string& autosavePath, bool& restored) {
  restored = false;
  const RestorePolicy policy = parseRestorePolicy(options.restore);
  if (autosaveIsNewer(autosavePath, options.markersPath)) {
    restored = policy == RestorePolicy::Yes ||
               (policy == RestorePolicy::Ask && userAgreesToRestore(autosavePath));
    if (restored) return io::readMarkers(autosavePath);
  }
  if (!options.markersPath.empty()) return io::readMarkers(options.markersPath);
  return {};
}

TriMesh readOverlaySurface(const std::string& path) {
  const auto kind = io::meshFileKind(path);
  if (!kind) throw BadInput(path, "not a mesh file this picker can read as an overlay");
  if (*kind == io::MeshKind::kSurface) return io::readTriMesh(path);
  const TetMesh tets = io::readTetMesh(path);
  TriMesh surface;
  surface.V = tets.V;
  surface.F = tetBoundary(tets.T);
  return surface;
}

}  // namespace vesalius::picker
