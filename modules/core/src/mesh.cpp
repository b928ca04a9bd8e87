#include "vesalius/core/mesh.h"

#include "vesalius/core/error.h"

#include <algorithm>
#include <array>
#include <map>

namespace vesalius {

namespace {

void checkFinite(const MatrixX3d& V, const std::string& source) {
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    if (!V.row(i).allFinite())
      throw BadInput(source, "vertex " + std::to_string(i) + " has a non-finite coordinate");
}

template <class Indices>
void checkIndices(const Indices& I, Eigen::Index vertexCount, const char* what, const std::string& source) {
  for (Eigen::Index r = 0; r < I.rows(); ++r)
    for (Eigen::Index c = 0; c < I.cols(); ++c)
      if (I(r, c) < 0 || I(r, c) >= vertexCount)
        throw BadInput(source, std::string(what) + " " + std::to_string(r) + " refers to vertex " +
                                   std::to_string(I(r, c)) + " of " + std::to_string(vertexCount));
}

}  // namespace

void TriMesh::validate(const std::string& source) const {
  checkFinite(V, source);
  checkIndices(F, V.rows(), "triangle", source);
  if (FUV.rows() != 0) {
    if (FUV.rows() != F.rows())
      throw BadInput(source, "texture faces (" + std::to_string(FUV.rows()) + ") do not match triangles (" +
                                 std::to_string(F.rows()) + ")");
    checkIndices(FUV, UV.rows(), "texture triangle", source);
    if (!UV.allFinite()) throw BadInput(source, "non-finite texture coordinate");
  }
  vertexAttributes.checkRows(V.rows(), source);
  faceAttributes.checkRows(F.rows(), source);
}

void TetMesh::validate(const std::string& source) const {
  checkFinite(V, source);
  checkIndices(T, V.rows(), "tetrahedron", source);
  checkIndices(F, V.rows(), "triangle", source);
  vertexAttributes.checkRows(V.rows(), source);
  tetAttributes.checkRows(T.rows(), source);
  faceAttributes.checkRows(F.rows(), source);
}

TriMesh concatenate(const TriMesh& a, const TriMesh& b) {
  TriMesh m;
  m.V.resize(a.V.rows() + b.V.rows(), 3);
  m.V << a.V, b.V;
  m.F.resize(a.F.rows() + b.F.rows(), 3);
  m.F << a.F, (b.F.array() + int(a.V.rows())).matrix();
  return m;
}

Eigen::VectorXd tetVolumes(const MatrixX3d& V, const MatrixX4i& T) {
  Eigen::VectorXd volumes(T.rows());
  for (Eigen::Index t = 0; t < T.rows(); ++t) {
    const Eigen::Vector3d a = V.row(T(t, 0)), b = V.row(T(t, 1)), c = V.row(T(t, 2)), d = V.row(T(t, 3));
    volumes(t) = (b - a).dot((c - a).cross(d - a)) / 6.0;
  }
  return volumes;
}

MatrixX3i tetBoundary(const MatrixX4i& T) {
  // Faces of a positively oriented tet (0,1,2,3), each ordered so its normal points outward.
  static constexpr int kFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  std::map<std::array<int, 3>, std::pair<int, std::array<int, 3>>> faces;  // sorted key -> (count, face)
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    for (const auto& f : kFaces) {
      std::array<int, 3> face{T(t, f[0]), T(t, f[1]), T(t, f[2])};
      std::array<int, 3> key = face;
      std::sort(key.begin(), key.end());
      auto [it, inserted] = faces.try_emplace(key, 0, face);
      ++it->second.first;
    }
  std::vector<std::array<int, 3>> boundary;
  for (const auto& [key, entry] : faces)
    if (entry.first == 1) boundary.push_back(entry.second);
  MatrixX3i F(boundary.size(), 3);
  for (std::size_t i = 0; i < boundary.size(); ++i) F.row(i) << boundary[i][0], boundary[i][1], boundary[i][2];
  return F;
}

TriMesh tetBoundarySurface(const MatrixX3d& V, const MatrixX4i& T) {
  const MatrixX3i F = tetBoundary(T);
  Eigen::VectorXi newIndex = Eigen::VectorXi::Constant(V.rows(), -1);
  TriMesh surface;
  surface.V.resize(V.rows(), 3);
  int used = 0;
  for (Eigen::Index i = 0; i < F.size(); ++i) {
    const int v = F.data()[i];
    if (newIndex[v] >= 0) continue;
    surface.V.row(used) = V.row(v);
    newIndex[v] = used++;
  }
  surface.V.conservativeResize(used, 3);
  surface.F = F.unaryExpr([&](int v) { return newIndex[v]; });
  return surface;
}

}  // namespace vesalius
