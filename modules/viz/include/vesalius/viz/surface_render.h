// A 3-D picture of surfaces, rendered offscreen with VTK/OpenGL.
//
// Debian's VTK renders through X11 only, so this needs a display (an X server or Xvfb:
// `xvfb-run -a -s "-screen 0 1280x1024x24"`); slice overlays (slice_overlay.h) need none.
// The camera looks at the patient from the front (anterior), superior up, so the patient's left is on the
// image right as in the coronal slice; the view fits the bounds of all surfaces.
#pragma once

#include "vesalius/core/atomic_file.h"
#include "vesalius/core/mesh.h"
#include "vesalius/viz/rgb_image.h"

#include <string>
#include <vector>

namespace vesalius::viz {

struct SurfaceLayer {
  const TriMesh* mesh = nullptr;  // LPS mm, not owned
  Rgb color{{200, 200, 200}};
  double opacity = 1.0;  // in (0, 1]; translucent outer layers show what lies inside
};

struct SurfaceRenderOptions {
  int width = 800, height = 800;  // pixels
  Rgb background{{24, 24, 28}};
  WriteOptions write;
};

// True when an X display is available (DISPLAY is set), i.e. when writeSurfacesPng can work.
bool canRenderSurfaces();

// Renders the layers. Throws UsageError without a display or with no non-empty layer, BadInput if a mesh
// fails TriMesh::validate.
RgbImage renderSurfaces(const std::vector<SurfaceLayer>& layers, const SurfaceRenderOptions& options = {});

// renderSurfaces written as PNG (writePng).
void writeSurfacesPng(const std::vector<SurfaceLayer>& layers, const std::string& pngPath,
                      const SurfaceRenderOptions& options = {});

}  // namespace vesalius::viz
