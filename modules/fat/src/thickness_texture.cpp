#include "vesalius/fat/thickness_texture.h"

#include "vesalius/core/error.h"
#include "vesalius/core/triangle_tree.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace vesalius::fat {

namespace {

using Index = Eigen::Index;

void checkUv(const TriMesh& mesh, const std::string& source) {
  if (mesh.UV.rows() == 0 || mesh.FUV.rows() != mesh.F.rows())
    throw BadInput(source, "the mesh has no texture coordinates (uv)");
  if (mesh.FUV.rows() > 0 && (mesh.FUV.minCoeff() < 0 || mesh.FUV.maxCoeff() >= mesh.UV.rows()))
    throw BadInput(source, "a uv index is outside the " + std::to_string(mesh.UV.rows()) + " texture coordinates");
  if (!mesh.UV.allFinite()) throw BadInput(source, "a texture coordinate is not finite");
  if (mesh.F.rows() > 0 && (mesh.F.minCoeff() < 0 || mesh.F.maxCoeff() >= mesh.V.rows()))
    throw BadInput(source, "a triangle indexes outside the " + std::to_string(mesh.V.rows()) + " vertices");
}

// Bilinear interpolation at continuous texel coordinates (texel centres at integers), clamped.
template <class T>
double bilinear(const std::vector<T>& u, int W, int H, double sx, double sy) {
  sx = std::clamp(sx, 0.0, double(W - 1));
  sy = std::clamp(sy, 0.0, double(H - 1));
  const int x0 = std::min(int(sx), std::max(W - 2, 0)), y0 = std::min(int(sy), std::max(H - 2, 0));
  const int x1 = std::min(x0 + 1, W - 1), y1 = std::min(y0 + 1, H - 1);
  const double fx = sx - x0, fy = sy - y0;
  auto at = [&](int x, int y) { return double(u[std::size_t(x) + std::size_t(W) * std::size_t(y)]); };
  return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x1, y0)) + fy * ((1 - fx) * at(x0, y1) + fx * at(x1, y1));
}

// Red-black Gauss-Seidel sweeps of u ← mean of the 4-neighbours (inside the image) over texels not
// `known`, until no texel changes by more than `tol`; returns the sweeps done.
int relax(std::vector<double>& u, const std::vector<char>& known, int W, int H, double tol, int maxSweeps) {
  std::vector<double> rowChange(std::size_t(H), 0.0);
  int sweep = 0;
  while (sweep < maxSweeps) {
    ++sweep;
    for (int colour = 0; colour < 2; ++colour)
      tbb::parallel_for(0, H, [&](int y) {
        double change = colour ? rowChange[y] : 0.0;
        for (int x = (y + colour) % 2; x < W; x += 2) {
          const std::size_t t = std::size_t(x) + std::size_t(W) * std::size_t(y);
          if (known[t]) continue;
          double sum = 0;
          int n = 0;
          if (x > 0) sum += u[t - 1], ++n;
          if (x + 1 < W) sum += u[t + 1], ++n;
          if (y > 0) sum += u[t - W], ++n;
          if (y + 1 < H) sum += u[t + W], ++n;
          if (n == 0) continue;  // a 1 × 1 level
          change = std::max(change, std::abs(sum / n - u[t]));
          u[t] = sum / n;
        }
        rowChange[y] = change;
      });
    if (*std::max_element(rowChange.begin(), rowChange.end()) <= tol) break;
  }
  return sweep;
}

// Harmonic fill of the texels not `known` (thickness_texture.h, step 3). Needs one known texel at least.
int harmonicFill(std::vector<double>& u, const std::vector<char>& known, int W, int H, double tol, int maxSweeps) {
  if (std::all_of(known.begin(), known.end(), [](char k) { return k != 0; }) || (W == 1 && H == 1)) return 0;
  const int Wc = (W + 1) / 2, Hc = (H + 1) / 2;
  std::vector<double> coarse(std::size_t(Wc) * Hc, 0.0), count(coarse.size(), 0.0);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const std::size_t t = std::size_t(x) + std::size_t(W) * y, c = std::size_t(x / 2) + std::size_t(Wc) * (y / 2);
      if (known[t]) coarse[c] += u[t], count[c] += 1;
    }
  std::vector<char> coarseKnown(coarse.size());
  for (std::size_t c = 0; c < coarse.size(); ++c) {
    coarseKnown[c] = count[c] > 0;
    if (count[c] > 0) coarse[c] /= count[c];
  }
  harmonicFill(coarse, coarseKnown, Wc, Hc, tol, maxSweeps);
  // Fine texel x has its centre at coarse coordinate (x − 0.5) / 2.
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const std::size_t t = std::size_t(x) + std::size_t(W) * y;
      if (!known[t]) u[t] = bilinear(coarse, Wc, Hc, (x - 0.5) / 2, (y - 0.5) / 2);
    }
  return relax(u, known, W, H, tol, maxSweeps);
}

struct Corner {
  Eigen::Vector3d p;  // texel coordinates (x, y, 0)
  double value;
};

// Passes 1 and 2 of rasterizeThickness over one triangle. sum/count: inside texels; best/rimValue: the
// nearest triangle of each rim texel.
void rasterizeTriangle(const std::array<Corner, 3>& c, int W, int H, double rim, std::vector<double>& sum,
                       std::vector<int>& count, std::vector<double>* best, std::vector<double>* rimValue) {
  const Eigen::Vector2d a = c[0].p.head<2>(), b = c[1].p.head<2>(), d = c[2].p.head<2>();
  const double area = (b.x() - a.x()) * (d.y() - a.y()) - (b.y() - a.y()) * (d.x() - a.x());
  if (!(std::abs(area) > 1e-12)) return;  // no extent in uv
  const double reach = best ? rim : 0.0;
  const int x0 = std::max(0, int(std::ceil(std::min({a.x(), b.x(), d.x()}) - reach)));
  const int x1 = std::min(W - 1, int(std::floor(std::max({a.x(), b.x(), d.x()}) + reach)));
  const int y0 = std::max(0, int(std::ceil(std::min({a.y(), b.y(), d.y()}) - reach)));
  const int y1 = std::min(H - 1, int(std::floor(std::max({a.y(), b.y(), d.y()}) + reach)));
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const std::size_t t = std::size_t(x) + std::size_t(W) * y;
      if (!best) {
        // Barycentric weights from signed areas; a centre on a shared edge counts for both triangles.
        const Eigen::Vector2d p(x, y);
        auto cross = [](const Eigen::Vector2d& e, const Eigen::Vector2d& f) { return e.x() * f.y() - e.y() * f.x(); };
        const double w0 = cross(b - p, d - p) / area, w1 = cross(d - p, a - p) / area, w2 = 1 - w0 - w1;
        if (w0 < -1e-12 || w1 < -1e-12 || w2 < -1e-12) continue;
        sum[t] += w0 * c[0].value + w1 * c[1].value + w2 * c[2].value;
        ++count[t];
        continue;
      }
      if (count[t]) continue;
      Eigen::Vector3d w;
      const Eigen::Vector3d q = closestPointOnTriangle(Eigen::Vector3d(x, y, 0), c[0].p, c[1].p, c[2].p, w);
      const double dist = (q - Eigen::Vector3d(x, y, 0)).norm();
      if (dist > rim || dist >= (*best)[t]) continue;
      (*best)[t] = dist;
      (*rimValue)[t] = w[0] * c[0].value + w[1] * c[1].value + w[2] * c[2].value;
    }
}

}  // namespace

ThicknessTexture rasterizeThickness(const TriMesh& mesh, const Eigen::VectorXd& values,
                                    const ThicknessTextureOptions& o, const std::string& source) {
  checkUv(mesh, source);
  if (values.size() != mesh.V.rows())
    throw BadInput(source, "thickness has " + std::to_string(values.size()) + " values for " +
                               std::to_string(mesh.V.rows()) + " vertices");
  if (!values.allFinite()) throw BadInput(source, "a thickness value is not finite");
  if (o.width < 1 || o.height < 1 || o.width > 16384 || o.height > 16384)
    throw UsageError("thickness texture: size must be 1 to 16384 texels a side");
  if (!(o.rimTexels >= 0) || !(o.fillTolerance >= 0) || o.maxSweeps < 0)
    throw UsageError("thickness texture: rim, tolerance and sweeps must be >= 0");
  const int W = o.width, H = o.height;
  const std::size_t n = std::size_t(W) * H;
  std::vector<double> sum(n, 0.0), best(n, std::numeric_limits<double>::infinity()), rimValue(n, 0.0);
  std::vector<int> count(n, 0);
  auto corners = [&](Index f) {
    std::array<Corner, 3> c;
    for (int k = 0; k < 3; ++k)
      c[k] = {Eigen::Vector3d(mesh.UV(mesh.FUV(f, k), 0) * W - 0.5, mesh.UV(mesh.FUV(f, k), 1) * H - 0.5, 0),
              values[mesh.F(f, k)]};
    return c;
  };
  for (Index f = 0; f < mesh.F.rows(); ++f)
    rasterizeTriangle(corners(f), W, H, o.rimTexels, sum, count, nullptr, nullptr);  // inside
  for (Index f = 0; f < mesh.F.rows(); ++f)
    rasterizeTriangle(corners(f), W, H, o.rimTexels, sum, count, &best, &rimValue);  // rim

  ThicknessTexture out;
  out.width = W, out.height = H;
  out.coverage.assign(n, ThicknessTexture::kFilled);
  std::vector<double> u(n, 0.0);
  std::vector<char> known(n, 0);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t t = 0; t < n; ++t) {
    if (count[t]) {
      u[t] = sum[t] / count[t], out.coverage[t] = ThicknessTexture::kInside, ++out.inside;
      out.overlapping += count[t] > 1;
    } else if (std::isfinite(best[t])) {
      u[t] = rimValue[t], out.coverage[t] = ThicknessTexture::kRim, ++out.rim;
    } else {
      ++out.filled;
      continue;
    }
    known[t] = 1, lo = std::min(lo, u[t]), hi = std::max(hi, u[t]);
  }
  if (out.inside + out.rim == 0) throw BadInput(source, "no uv triangle covers a texel (uv outside [0, 1]?)");
  out.sweeps = harmonicFill(u, known, W, H, o.fillTolerance * (hi - lo), o.maxSweeps);
  out.values.assign(u.begin(), u.end());
  return out;
}

Eigen::VectorXd sampleTexture(const ThicknessTexture& texture, const MatrixX2d& UV) {
  if (texture.width < 1 || texture.height < 1 ||
      texture.values.size() != std::size_t(texture.width) * std::size_t(texture.height))
    throw UsageError("sample texture: the texture is empty");
  Eigen::VectorXd out(UV.rows());
  for (Index i = 0; i < UV.rows(); ++i)
    out[i] = bilinear(texture.values, texture.width, texture.height, UV(i, 0) * texture.width - 0.5,
                      UV(i, 1) * texture.height - 0.5);
  return out;
}

Eigen::VectorXd sampleTextureAtVertices(const ThicknessTexture& texture, const TriMesh& mesh,
                                        const std::string& source) {
  checkUv(mesh, source);
  const Eigen::VectorXd atUv = sampleTexture(texture, mesh.UV);
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(mesh.V.rows()), count = sum;
  // Each distinct (vertex, uv) corner counts once, however many triangles share it.
  std::vector<std::pair<int, int>> corners;
  for (Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) corners.emplace_back(mesh.F(f, k), mesh.FUV(f, k));
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  for (const auto& [v, t] : corners) sum[v] += atUv[t], count[v] += 1;
  for (Index v = 0; v < sum.size(); ++v)
    if (count[v] > 0) sum[v] /= count[v];
  return sum;
}

}  // namespace vesalius::fat
