#include "vesalius/io/makehuman_uv.h"

#include "vesalius/core/error.h"

#include <vector>

namespace vesalius::io {

TriMesh withMakeHumanUv(TriMesh body, const TriMesh& base, const std::string& baseSource) {
  const Eigen::Index faces = body.F.rows();
  if (base.UV.rows() == 0 || base.FUV.rows() != base.F.rows())
    throw BadInput(baseSource, "no texture coordinates to give the body shape");
  if (base.F.rows() < faces || base.F.topRows(faces) != body.F)
    throw BadInput(baseSource, "its first " + std::to_string(faces) +
                                   " triangles are not the body shape's faces (not a MakeHuman body of this base mesh)");
  std::vector<int> compact(std::size_t(base.UV.rows()), -1);
  body.FUV.resize(faces, 3);
  int used = 0;
  for (Eigen::Index f = 0; f < faces; ++f)
    for (int k = 0; k < 3; ++k) {
      int& index = compact[std::size_t(base.FUV(f, k))];
      if (index < 0) index = used++;
      body.FUV(f, k) = index;
    }
  body.UV.resize(used, 2);
  for (std::size_t u = 0; u < compact.size(); ++u)
    if (compact[u] >= 0) body.UV.row(compact[u]) = base.UV.row(Eigen::Index(u));
  return body;
}

}  // namespace vesalius::io
