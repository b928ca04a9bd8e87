// Binary glTF (gltf.h): an anatomy written and read back (names, colours, vertices, triangles), the
// documented axis map and byte layout, VTK's own glTF reader on our file, node transforms of files we did
// not write, and hostile files refused with one line naming the file.
#include "vesalius/core/error.h"
#include "vesalius/io/gltf.h"
#include "vesalius/io/mesh_io.h"

#include "expect_bad_input.h"
#include "test_shapes.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <vtkCompositeDataIterator.h>
#include <vtkGLTFReader.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

namespace vesalius::io {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

std::string output(const std::string& name) {
  const fs::path folder = fs::path(VESALIUS_TEST_OUTPUT) / "gltf";
  fs::create_directories(folder);
  return (folder / name).string();
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

void spit(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

WriteOptions force() {
  WriteOptions o;
  o.force = true;
  return o;
}

std::uint32_t u32(const std::string& bytes, std::size_t at) {
  std::uint32_t v;
  std::memcpy(&v, bytes.data() + at, 4);
  return v;
}

void putU32(std::string& out, std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); }

// A GLB taken apart and put together again, so tests can write files other tools might write.
struct Glb {
  Json doc;
  std::string bin;
};

Glb split(const std::string& bytes) {
  const std::uint32_t jsonLength = u32(bytes, 12);
  Glb glb;
  glb.doc = Json::parse(bytes.substr(20, jsonLength));
  const std::size_t binAt = 20 + jsonLength;
  glb.bin = bytes.substr(binAt + 8, u32(bytes, binAt));
  return glb;
}

std::string pack(const Json& doc, const std::string& bin) {
  std::string json = doc.dump();
  while (json.size() % 4) json.push_back(' ');
  std::string out;
  putU32(out, 0x46546C67);
  putU32(out, 2);
  putU32(out, std::uint32_t(12 + 8 + json.size() + 8 + bin.size()));
  putU32(out, std::uint32_t(json.size()));
  putU32(out, 0x4E4F534A);
  out += json;
  putU32(out, std::uint32_t(bin.size()));
  putU32(out, 0x004E4942);
  return out + bin;
}

// Two tissues inside a skin, away from the origin as a body is in scanner coordinates.
ReferenceAnatomy twoTissueAnatomy() {
  ReferenceAnatomy anatomy;
  anatomy.name = "test";
  anatomy.skin = test::sphere(3, 200.0, Eigen::Vector3d(-12.3, 150.7, -640.2));
  ReferenceTissue bone;
  bone.name = "femur_left";
  bone.kind = TissueKind::Bone;
  bone.mesh = test::sphere(2, 30.0, Eigen::Vector3d(80.1, 140.9, -700.3));
  ReferenceTissue liver;
  liver.name = "liver";
  liver.kind = TissueKind::Organ;
  liver.mesh = test::sphere(2, 60.0, Eigen::Vector3d(-70.4, 120.2, -560.6));
  anatomy.tissues = {bone, liver};
  return anatomy;
}

// A coordinate survives mm -> float32 metres -> mm to float32 rounding of its value in metres.
void expectSameVertices(const MatrixX3d& read, const MatrixX3d& written) {
  ASSERT_EQ(read.rows(), written.rows());
  double worst = 0;
  for (Eigen::Index v = 0; v < read.rows(); ++v)
    for (int k = 0; k < 3; ++k) {
      const double error = std::abs(read(v, k) - written(v, k));
      EXPECT_LE(error, std::abs(written(v, k)) * 6.0e-8 + 1e-9) << "vertex " << v << " axis " << k;
      worst = std::max(worst, error);
    }
  EXPECT_LT(worst, 1e-4);  // mm, for a body within 1 m of the origin
}

TEST(Gltf, AnatomyRoundTripKeepsNamesColoursVerticesAndTriangles) {
  const ReferenceAnatomy anatomy = twoTissueAnatomy();
  const std::string path = output("anatomy.glb");
  writeAnatomyGlb(path, anatomy, force());
  const std::vector<GltfMesh> nodes = readGlb(path);
  ASSERT_EQ(nodes.size(), 3u);
  const std::array<double, 4> expected[] = {linearRgba(tissueKindColour(TissueKind::Bone), 1.0),
                                            linearRgba(tissueKindColour(TissueKind::Organ), 1.0),
                                            linearRgba(kSkinColour, 0.25)};
  const TriMesh* meshes[] = {&anatomy.tissues[0].mesh, &anatomy.tissues[1].mesh, &anatomy.skin};
  const char* names[] = {"femur_left", "liver", "skin"};
  for (std::size_t i = 0; i < 3; ++i) {
    SCOPED_TRACE(names[i]);
    EXPECT_EQ(nodes[i].name, names[i]);
    EXPECT_EQ(nodes[i].rgba, expected[i]);
    expectSameVertices(nodes[i].mesh.V, meshes[i]->V);
    EXPECT_EQ(nodes[i].mesh.F, meshes[i]->F);
  }
  EXPECT_NE(expected[0], expected[1]);
  EXPECT_NEAR(linearRgba({255, 255, 255}, 1)[0], 1.0, 1e-12);
  EXPECT_NEAR(linearRgba({128, 0, 0}, 1)[0], 0.2158605, 1e-6);  // sRGB 128 in linear light
}

TEST(Gltf, AxisMapPutsThePatientUpAlongYFacingZInMetres) {
  EXPECT_TRUE(gltfFromLps({10, 0, 0}).isApprox(Eigen::Vector3d(0.01, 0, 0)));   // left -> +X
  EXPECT_TRUE(gltfFromLps({0, 0, 10}).isApprox(Eigen::Vector3d(0, 0.01, 0)));   // superior -> +Y
  EXPECT_TRUE(gltfFromLps({0, -10, 0}).isApprox(Eigen::Vector3d(0, 0, 0.01)));  // anterior -> +Z
  EXPECT_TRUE(lpsFromGltf(gltfFromLps({1, 2, 3})).isApprox(Eigen::Vector3d(1, 2, 3)));

  // In the file: one triangle; POSITION min/max hold the mapped coordinates.
  TriMesh triangle;
  triangle.V.resize(3, 3);
  triangle.V << 10, 0, 0,  //
      0, 20, 0,            //
      0, 0, 30;
  triangle.F.resize(1, 3);
  triangle.F << 0, 1, 2;
  const std::string path = output("axes.glb");
  writeGlb(path, {{"t", &triangle, {1, 0, 0, 1}}}, force());
  const Glb glb = split(slurp(path));
  const int positionAccessor = glb.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
  const Json& position = glb.doc["accessors"][positionAccessor];
  const std::vector<double> min = position["min"], max = position["max"];
  EXPECT_NEAR(max[0], 0.01, 1e-9);   // L = 10 mm
  EXPECT_NEAR(min[2], -0.02, 1e-9);  // P = 20 mm is behind: -Z
  EXPECT_NEAR(max[1], 0.03, 1e-9);   // S = 30 mm
  EXPECT_NEAR(min[0], 0, 1e-12);
  EXPECT_NEAR(min[1], 0, 1e-12);
  EXPECT_NEAR(max[2], 0, 1e-12);
}

TEST(Gltf, LayoutMaterialsAndNormalsFollowTheSpec) {
  const ReferenceAnatomy anatomy = twoTissueAnatomy();
  const std::string path = output("layout.glb");
  writeAnatomyGlb(path, anatomy, force());
  const std::string bytes = slurp(path);
  ASSERT_EQ(u32(bytes, 0), 0x46546C67u);
  EXPECT_EQ(u32(bytes, 4), 2u);
  EXPECT_EQ(u32(bytes, 8), bytes.size());
  EXPECT_EQ(u32(bytes, 12) % 4, 0u);
  EXPECT_EQ(u32(bytes, 20 + u32(bytes, 12)) % 4, 0u);
  const Glb glb = split(bytes);
  const Json& doc = glb.doc;
  EXPECT_EQ(doc["asset"]["version"], "2.0");
  EXPECT_EQ(doc["asset"]["generator"], "Vesalius");
  EXPECT_EQ(doc["buffers"][0]["byteLength"].get<std::size_t>(), glb.bin.size());
  for (const Json& view : doc["bufferViews"]) EXPECT_EQ(view["byteOffset"].get<std::size_t>() % 4, 0u);
  ASSERT_EQ(doc["materials"].size(), 3u);
  for (std::size_t m = 0; m < 3; ++m) {
    EXPECT_EQ(doc["materials"][m]["pbrMetallicRoughness"]["metallicFactor"], 0.0);
    EXPECT_EQ(doc["materials"][m]["doubleSided"], false);
    EXPECT_EQ(doc["materials"][m]["alphaMode"], m == 2 ? "BLEND" : "OPAQUE");
  }
  EXPECT_EQ(doc["nodes"][2]["name"], "skin");

  // The bone's normals: unit, pointing away from the sphere's centre (in glTF axes).
  const Json& attributes = doc["meshes"][0]["primitives"][0]["attributes"];
  const Json& normals = doc["accessors"][attributes["NORMAL"].get<int>()];
  EXPECT_EQ(normals["componentType"], 5126);
  const std::size_t at = doc["bufferViews"][normals["bufferView"].get<int>()]["byteOffset"];
  const TriMesh& bone = anatomy.tissues[0].mesh;
  const Eigen::Vector3d centre = bone.V.colwise().mean().transpose();
  for (Eigen::Index v = 0; v < bone.V.rows(); ++v) {
    float n[3];
    std::memcpy(n, glb.bin.data() + at + 12 * std::size_t(v), 12);
    const Eigen::Vector3d normal(n[0], n[1], n[2]);
    const Eigen::Vector3d outward = gltfFromLps(bone.V.row(v).transpose() - centre).normalized();
    EXPECT_NEAR(normal.norm(), 1.0, 1e-6);
    EXPECT_GT(normal.dot(outward), 0.98) << "vertex " << v;
  }
}

TEST(Gltf, VtkGltfReaderReadsOurFile) {
  const ReferenceAnatomy anatomy = twoTissueAnatomy();
  const std::string path = output("for-vtk.glb");
  writeAnatomyGlb(path, anatomy, force());
  vtkNew<vtkGLTFReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkMultiBlockDataSet* blocks = reader->GetOutput();
  ASSERT_NE(blocks, nullptr);
  vtkIdType points = 0, cells = 0;
  double bounds[6] = {1e9, -1e9, 1e9, -1e9, 1e9, -1e9};
  vtkSmartPointer<vtkCompositeDataIterator> it;
  it.TakeReference(blocks->NewIterator());
  int leaves = 0;
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem()) {
    auto* poly = vtkPolyData::SafeDownCast(it->GetCurrentDataObject());
    if (poly == nullptr) continue;
    ++leaves;
    points += poly->GetNumberOfPoints();
    cells += poly->GetNumberOfCells();
    double b[6];
    poly->GetBounds(b);
    for (int k = 0; k < 3; ++k) {
      bounds[2 * k] = std::min(bounds[2 * k], b[2 * k]);
      bounds[2 * k + 1] = std::max(bounds[2 * k + 1], b[2 * k + 1]);
    }
  }
  EXPECT_EQ(leaves, 3);
  Eigen::Index wantPoints = anatomy.skin.V.rows(), wantCells = anatomy.skin.F.rows();
  for (const ReferenceTissue& t : anatomy.tissues) wantPoints += t.mesh.V.rows(), wantCells += t.mesh.F.rows();
  EXPECT_EQ(points, wantPoints);
  EXPECT_EQ(cells, wantCells);
  // VTK reads glTF axes in metres: the skin (the largest mesh) sets the bounds, mapped as documented.
  const Eigen::Vector3d lo = gltfFromLps(anatomy.skin.V.colwise().minCoeff().transpose());
  const Eigen::Vector3d hi = gltfFromLps(anatomy.skin.V.colwise().maxCoeff().transpose());
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(bounds[2 * k], std::min(lo(k), hi(k)), 1e-6) << "axis " << k;
    EXPECT_NEAR(bounds[2 * k + 1], std::max(lo(k), hi(k)), 1e-6) << "axis " << k;
  }
}

TEST(Gltf, MeshIoReadsAndWritesGlb) {
  const TriMesh mesh = test::sphere(2, 25.0, Eigen::Vector3d(3, -4, 5));
  const std::string path = output("sphere.glb");
  MeshWriteOptions options;
  options.force = true;
  writeTriMesh(path, mesh, options);
  EXPECT_EQ(meshFileKind(path), MeshKind::kSurface);
  const TriMesh read = readTriMesh(path);
  expectSameVertices(read.V, mesh.V);
  EXPECT_EQ(read.F, mesh.F);
  EXPECT_EQ(readGlb(path).at(0).name, "sphere");

  // A whole model reads as one surface of all its nodes.
  const ReferenceAnatomy anatomy = twoTissueAnatomy();
  writeAnatomyGlb(output("model.glb"), anatomy, force());
  const TriMesh all = readTriMesh(output("model.glb"));
  EXPECT_EQ(all.V.rows(), anatomy.tissues[0].mesh.V.rows() + anatomy.tissues[1].mesh.V.rows() + anatomy.skin.V.rows());
  EXPECT_EQ(all.F.rows(), anatomy.tissues[0].mesh.F.rows() + anatomy.tissues[1].mesh.F.rows() + anatomy.skin.F.rows());

  EXPECT_THROW(writeTriMesh(path, mesh), UsageError);  // exists, no force
}

TEST(Gltf, NodeTransformsOfOtherWritersAreApplied) {
  const TriMesh mesh = test::sphere(1, 10.0);
  const std::string ours = output("plain.glb");
  writeGlb(ours, {{"ball", &mesh, {1, 1, 1, 1}}}, force());
  Glb glb = split(slurp(ours));
  // A parent moving 0.05 m along glTF +X (our L) holding a child mirrored in X: winding must flip back.
  glb.doc["nodes"] = Json::array({{{"name", "parent"}, {"translation", {0.05, 0, 0}}, {"children", {1}}},
                                  {{"name", "child"}, {"mesh", 0}, {"scale", {-1, 1, 1}}}});
  glb.doc["scenes"] = Json::array({{{"nodes", {0}}}});
  const std::string path = output("transformed.glb");
  spit(path, pack(glb.doc, glb.bin));
  const std::vector<GltfMesh> nodes = readGlb(path);
  ASSERT_EQ(nodes.size(), 1u);
  EXPECT_EQ(nodes[0].name, "child");
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    const Eigen::Vector3d want(50.0 - mesh.V(v, 0), mesh.V(v, 1), mesh.V(v, 2));
    EXPECT_LT((nodes[0].mesh.V.row(v).transpose() - want).norm(), 1e-4) << "vertex " << v;
  }
  // Outward normals survive the mirror: the enclosed volume stays positive.
  double volume = 0;
  const TriMesh& m = nodes[0].mesh;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    const Eigen::Vector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
    volume += a.dot(b.cross(c)) / 6;
  }
  EXPECT_GT(volume, 0);
}

// ---- hostile files ----

std::string validBytes() {
  static const std::string bytes = [] {
    const TriMesh mesh = test::sphere(1, 10.0);
    return formatGlb({{"ball", &mesh, {1, 1, 1, 1}}}, "ball.glb");
  }();
  return bytes;
}

void expectRefused(const std::string& name, const std::string& bytes, const std::string& fragment) {
  const std::string path = output(name);
  spit(path, bytes);
  test::expectOneLineBadInput(path, fragment, [&] { readGlb(path); });
  test::expectOneLineBadInput(path, fragment, [&] { readTriMesh(path); });
}

std::string edited(const std::function<void(Glb&)>& edit) {
  Glb glb = split(validBytes());
  edit(glb);
  return pack(glb.doc, glb.bin);
}

TEST(GltfBadInput, EachProblemIsOneLineNamingTheFile) {
  std::string badMagic = validBytes();
  badMagic[0] = 'x';
  expectRefused("bad-magic.glb", badMagic, "magic");
  expectRefused("empty.glb", "", "too short");

  std::string longer = validBytes();
  const std::uint32_t claimed = std::uint32_t(longer.size() + 100);
  std::memcpy(&longer[8], &claimed, 4);
  expectRefused("header-too-long.glb", longer, "truncated");
  expectRefused("cut.glb", validBytes().substr(0, validBytes().size() - 40), "truncated");

  expectRefused("accessor-beyond.glb", edited([](Glb& g) { g.doc["accessors"][0]["count"] = 1000000; }),
                "beyond bufferView");
  expectRefused("accessor-offset.glb", edited([](Glb& g) { g.doc["accessors"][2]["byteOffset"] = 4294967292u; }),
                "beyond bufferView");
  expectRefused("view-beyond.glb", edited([](Glb& g) { g.doc["bufferViews"][0]["byteOffset"] = 1u << 30; }),
                "beyond its buffer");
  expectRefused("buffer-longer.glb", edited([](Glb& g) { g.doc["buffers"][0]["byteLength"] = g.bin.size() + 4; }),
                "larger than the BIN chunk");
  expectRefused("index-out-of-range.glb", edited([](Glb& g) {
                  const std::size_t at = g.doc["bufferViews"][2]["byteOffset"];
                  const std::uint32_t big = 1u << 20;
                  std::memcpy(&g.bin[at], &big, 4);
                }),
                "beyond its");
  expectRefused("lines.glb", edited([](Glb& g) { g.doc["meshes"][0]["primitives"][0]["mode"] = 1; }), "mode 1");
  expectRefused("uri.glb", edited([](Glb& g) { g.doc["buffers"][0]["uri"] = "data.bin"; }), "external");
  expectRefused("negative.glb", edited([](Glb& g) { g.doc["accessors"][0]["count"] = -3; }), "non-negative");
  expectRefused("string-count.glb", edited([](Glb& g) { g.doc["accessors"][0]["count"] = "many"; }), "non-negative");
  expectRefused("double-position.glb", edited([](Glb& g) { g.doc["accessors"][0]["componentType"] = 5130; }),
                "componentType");
  expectRefused("no-accessor.glb", edited([](Glb& g) { g.doc["meshes"][0]["primitives"][0]["indices"] = 99; }),
                "out of range");
  expectRefused("cycle.glb", edited([](Glb& g) { g.doc["nodes"][0]["children"] = {0}; }), "twice");
  expectRefused("draco.glb", edited([](Glb& g) { g.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"}; }),
                "KHR_draco_mesh_compression");
  expectRefused("not-json.glb", edited([](Glb& g) { g.doc = Json::array(); }), "not a JSON object");
  expectRefused("nodes-object.glb", edited([](Glb& g) { g.doc["nodes"] = Json::object(); }), "not an array");
  expectRefused("nan.glb", edited([](Glb& g) {
                  const float nan = std::nanf("");
                  std::memcpy(&g.bin[0], &nan, 4);
                }),
                "ball");
}

// Every prefix of a valid file and every single-byte change of its JSON is refused with a BadInput or
// read; nothing else (a crash, another exception) is allowed.
TEST(GltfBadInput, PrefixesAndByteChangesNeverCrash) {
  const std::string bytes = validBytes();
  for (std::size_t n = 0; n < bytes.size(); n += 7) {
    try {
      parseGlb(std::string_view(bytes).substr(0, n), "prefix.glb");
      ADD_FAILURE() << "prefix of " << n << " bytes read";
    } catch (const BadInput& e) {
      EXPECT_EQ(std::string(e.what()).rfind("prefix.glb: ", 0), 0u);
    }
  }
  const std::size_t jsonEnd = 20 + u32(bytes, 12);
  for (std::size_t at = 0; at < jsonEnd; ++at)
    for (const char c : {'0', '9', '-', '"', '{', '\xff'}) {
      std::string changed = bytes;
      changed[at] = c;
      try {
        parseGlb(changed, "changed.glb");
      } catch (const BadInput&) {
      }
    }
}

}  // namespace
}  // namespace vesalius::io
