// MakeHuman's texture coordinates for its body shapes. The shapes in testdata/body/shapes (mh_*_body.obj)
// are base.obj's "body" group alone: its 13,380 vertices and 13,378 quads in base.obj's order
// (body_vertex_index_map.txt is the identity), moved by shape targets, but written without uv. The group's
// faces come first in base.obj, so its uv carry over face by face; every shape then shares MakeHuman's
// texture layout, as the fat-thickness texture of Dicko et al. 2013, §5, needs.
#pragma once

#include "vesalius/core/mesh.h"

#include <string>

namespace vesalius::io {

// body: a MakeHuman body shape as read by readTriMesh (#F triangles, no uv). base: base.obj as read by
// readTriMesh (quads split the same way), from the file `baseSource`. Returns body with UV (#UV by 2, only
// the coordinates its faces use) and FUV (#F by 3). Throws BadInput(baseSource) when base has no uv or its
// first #F triangles are not body's faces, i.e. body is not one of base.obj's body shapes.
TriMesh withMakeHumanUv(TriMesh body, const TriMesh& base, const std::string& baseSource);

}  // namespace vesalius::io
