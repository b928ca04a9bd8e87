// Fat thickness in the skin's texture space, and back (Dicko et al. 2013, §3: the user gives "a user-defined
// distribution of sub-skin fat ... modeled using a thickness function in texture space"; §5: "Based on
// the texture coordinates of the skin voxels and the associated thickness, we interpolate the value at
// each pixel of the thickness texture", and erosion reads "the local depth using the texture
// coordinates"). Source and target skins share one (u, v) space, so a texture made on one skin is read
// at any registered skin.
//
// Texels: texel (x, y) of a W × H texture is the square u ∈ [x/W, (x+1)/W], v ∈ [y/H, (y+1)/H] and holds
// the value at its centre; y = 0 is v = 0, the bottom row of the picture as OBJ textures are drawn.
//
// rasterizeThickness: per-vertex values (e.g. thicknessAtVertices) over the uv triangles (TriMesh::UV,
// FUV; corner c of face f carries the value of vertex F(f, c)).
//  1. Inside: a texel whose centre lies in a uv triangle takes the barycentric interpolation of the
//     triangle's corner values (in several triangles, where charts overlap: their mean).
//  2. Rim: an uncovered texel whose centre lies within rimTexels of a triangle takes the value at the
//     nearest point of the nearest triangle, so every texel a bilinear lookup reads at a point of a chart
//     (the four centres around it, within √2 texels) carries that chart's values. Deviation: the paper
//     interpolates from skin voxels directly; here the voxels go to vertices first (thicknessAtVertices).
//  3. Fill: all other texels solve Laplace's equation with the inside and rim texels fixed (a harmonic
//     fill: smooth, each value the mean of its 4-neighbours, all within the range of the fixed ones).
//     Solved as a cascade from coarse to fine: each coarser level averages the fixed texels of 2 × 2
//     blocks and is filled first; its bilinear interpolation starts the finer level, which red-black
//     Gauss-Seidel sweeps relax until no texel changes by more than fillTolerance times the range of the
//     fixed values (or maxSweeps). Within a level the sweeps are parallel over rows (TBB) and the result
//     does not depend on the number of threads.
// sampleTexture: bilinear between texel centres, clamped at the texture's edges.
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace vesalius::fat {

struct ThicknessTextureOptions {
  int width = 1024, height = 1024;  // texels, 1 to 16384
  double rimTexels = 1.5;           // reach of the rim around the charts, in texels (>= 0)
  double fillTolerance = 1e-5;      // stop relaxing a level when no texel changes by more (× value range)
  int maxSweeps = 2000;             // per level
};

struct ThicknessTexture {
  int width = 0, height = 0;
  std::vector<float> values;  // width · height; texel (x, y) at x + width · y
  enum Coverage : std::uint8_t { kFilled = 0, kRim = 1, kInside = 2 };
  std::vector<std::uint8_t> coverage;  // same layout
  std::int64_t inside = 0, rim = 0, filled = 0;
  std::int64_t overlapping = 0;  // inside texels covered by two or more triangles
  int sweeps = 0;                // relaxation sweeps at the finest level
  float at(int x, int y) const { return values[std::size_t(x) + std::size_t(width) * std::size_t(y)]; }
};

// mesh: F, UV and FUV (#F by 3); values: #V, finite. Throws BadInput naming `source` if the mesh has no
// uv (UV empty or FUV not #F by 3), FUV indexes outside UV, a value or uv is not finite, the values are
// not #V, or no texel centre lies within the rim of any triangle (uv outside [0, 1]); UsageError for a
// size outside 1..16384 or negative options.
ThicknessTexture rasterizeThickness(const TriMesh& mesh, const Eigen::VectorXd& values,
                                    const ThicknessTextureOptions& options = {}, const std::string& source = "");

// The texture at each row of UV (#UV by 2): #UV values, bilinear. Throws UsageError for an empty texture.
Eigen::VectorXd sampleTexture(const ThicknessTexture& texture, const MatrixX2d& UV);

// The texture at the vertices of a mesh with uv: #V values, each the mean over the vertex's uv corners
// (a vertex on a seam has several); 0 for a vertex in no triangle. Throws BadInput naming `source` as
// rasterizeThickness does for missing or broken uv.
Eigen::VectorXd sampleTextureAtVertices(const ThicknessTexture& texture, const TriMesh& mesh,
                                        const std::string& source = "");

}  // namespace vesalius::fat
