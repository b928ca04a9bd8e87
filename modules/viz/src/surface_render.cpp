// Offscreen 3-D render of surfaces (surface_render.h): one actor per layer, depth peeling for the
// translucent ones, the frame read back with vtkWindowToImageFilter from the back buffer (docs/design.md,
// "Where Debian 12's stack bites").
#include "vesalius/viz/surface_render.h"

#include "vesalius/core/error.h"
#include "vesalius/io/polydata.h"
#include "vesalius/viz/display_connection.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cstdlib>

namespace vesalius::viz {
namespace {

vtkSmartPointer<vtkActor> layerActor(const SurfaceLayer& layer) {
  vtkNew<vtkPolyDataNormals> normals;  // smooth shading
  normals->SetInputData(io::toPolyData(*layer.mesh));
  normals->SplittingOff();
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(normals->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(layer.color[0] / 255.0, layer.color[1] / 255.0, layer.color[2] / 255.0);
  actor->GetProperty()->SetOpacity(layer.opacity);
  actor->GetProperty()->SetSpecular(0.2);
  return actor;
}

// Anterior view: the camera in front of the patient (-y in LPS), superior (+z) up.
void placeCamera(vtkRenderer* renderer) {
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(0, 0, 0);
  camera->SetPosition(0, -1, 0);
  camera->SetViewUp(0, 0, 1);
  renderer->ResetCamera();
}

void checkLayers(const std::vector<SurfaceLayer>& layers) {
  bool any = false;
  for (const SurfaceLayer& layer : layers) {
    if (!layer.mesh || !(layer.opacity > 0.0 && layer.opacity <= 1.0))
      throw UsageError("each surface layer needs a mesh and an opacity in (0, 1]");
    layer.mesh->validate("surface layer");
    any = any || layer.mesh->F.rows() > 0;
  }
  if (!any) throw UsageError("nothing to render: every surface is empty");
}

// The grabbed frame (RGB, row 0 at the bottom) as an RgbImage (row 0 at the top).
RgbImage fromVtk(vtkImageData* frame) {
  int dims[3];
  frame->GetDimensions(dims);
  RgbImage image(dims[0], dims[1], {{0, 0, 0}});
  const auto* in = static_cast<const std::uint8_t*>(frame->GetScalarPointer());
  const std::size_t rowBytes = std::size_t(dims[0]) * 3;
  for (int y = 0; y < dims[1]; ++y)
    std::copy(in + rowBytes * std::size_t(dims[1] - 1 - y), in + rowBytes * std::size_t(dims[1] - y),
              image.pixels.begin() + std::ptrdiff_t(rowBytes * std::size_t(y)));
  return image;
}

}  // namespace

bool canRenderSurfaces() {
  const char* display = std::getenv("DISPLAY");
  return display && *display;
}

RgbImage renderSurfaces(const std::vector<SurfaceLayer>& layers, const SurfaceRenderOptions& options) {
  if (!canRenderSurfaces())
    throw UsageError("a 3-D render needs an X display; run under xvfb-run -a -s \"-screen 0 1280x1024x24\"");
  checkLayers(layers);
  vtkNew<vtkRenderer> renderer;
  const Rgb& bg = options.background;
  renderer->SetBackground(bg[0] / 255.0, bg[1] / 255.0, bg[2] / 255.0);
  renderer->SetUseDepthPeeling(true);
  for (const SurfaceLayer& layer : layers) renderer->AddActor(layerActor(layer));
  placeCamera(renderer);
  const DisplayConnection connection("a 3-D render");  // outlives the window, which does not close it
  vtkNew<vtkRenderWindow> window;
  window->SetDisplayId(connection.display);
  window->SetOffScreenRendering(1);
  window->SetAlphaBitPlanes(1);
  window->SetMultiSamples(0);
  window->SetSize(options.width, options.height);
  window->AddRenderer(renderer);
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  return fromVtk(grab->GetOutput());
}

void writeSurfacesPng(const std::vector<SurfaceLayer>& layers, const std::string& pngPath,
                      const SurfaceRenderOptions& options) {
  writePng(pngPath, renderSurfaces(layers, options), options.write);
}

}  // namespace vesalius::viz
