#include "vesalius/core/keep_faces.h"

namespace vesalius {

TriMesh keepFaces(const TriMesh& mesh, const std::vector<bool>& keep) {
  std::vector<int> faces;
  std::vector<bool> used(std::size_t(mesh.V.rows()), false);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    if (!keep[std::size_t(f)]) continue;
    faces.push_back(int(f));
    for (int k = 0; k < 3; ++k) used[std::size_t(mesh.F(f, k))] = true;
  }
  std::vector<int> vertices;
  Eigen::VectorXi newIndex = Eigen::VectorXi::Constant(mesh.V.rows(), -1);
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    if (used[std::size_t(v)]) newIndex[v] = int(vertices.size()), vertices.push_back(int(v));
  const Eigen::VectorXi faceRows = Eigen::Map<const Eigen::VectorXi>(faces.data(), Eigen::Index(faces.size()));
  const Eigen::VectorXi vertexRows = Eigen::Map<const Eigen::VectorXi>(vertices.data(), Eigen::Index(vertices.size()));
  TriMesh out;
  out.V = mesh.V(vertexRows, Eigen::all);
  out.F = MatrixX3i(mesh.F(faceRows, Eigen::all)).unaryExpr([&](int v) { return newIndex[v]; });
  out.UV = mesh.UV;
  if (mesh.FUV.rows() == mesh.F.rows() && mesh.FUV.rows() > 0) out.FUV = mesh.FUV(faceRows, Eigen::all);
  out.vertexAttributes = mesh.vertexAttributes.selectRows(vertexRows);
  out.faceAttributes = mesh.faceAttributes.selectRows(faceRows);
  return out;
}

}  // namespace vesalius
