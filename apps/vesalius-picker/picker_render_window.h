// The picker's render window: VTK's X/OpenGL window, less one full-window pass per frame.
//
// At the end of every render VTK 9.1 (vtkOpenGLRenderWindow::BlitDisplayFramebuffersToHardware) copies
// its display frame buffer to the window's back buffer: the colour by a blit and the depth by a
// full-window shader pass (TextureDepthBlit). Nothing draws into or reads the window's own depth buffer
// here (VTK reads pixels and depth from its frame buffers, the picker picks by geometry), so this window
// copies the colour only. Under Xvfb, where Mesa's llvmpipe runs every fragment on the CPU, the depth
// pass is a fixed cost of every frame, whatever changed (docs/benchmarks.md). No stereo (VTK's stereo
// copy is not repeated here).
#pragma once

#include <vtkRenderWindow.h>
#include <vtkSmartPointer.h>

namespace vesalius::picker {

// A new X/OpenGL render window that copies only the colour to the screen (the class stays in the .cpp:
// VTK's X header brings Xlib's macros, which clash with Eigen's names).
vtkSmartPointer<vtkRenderWindow> newPickerRenderWindow();

}  // namespace vesalius::picker
