// Reference folders (io/reference_anatomy_io.h): a round trip, and reference.json files that name meshes
// outside their folder or carry a member of the wrong type, refused in one line naming reference.json.
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/reference_anatomy_io.h"

#include "expect_bad_input.h"
#include "test_shapes.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace vesalius::io {
namespace {

namespace fs = std::filesystem;

std::string folder(const std::string& name) {
  const fs::path dir = fs::path(VESALIUS_TEST_OUTPUT) / "reference" / name;
  fs::remove_all(dir);
  fs::create_directories(dir.parent_path());
  return dir.string();
}

ReferenceAnatomy twoSpheres() {
  ReferenceAnatomy a;
  a.name = "spheres";
  a.skin = test::sphere(2, 100.0);
  a.tissues.push_back({"bone/../../x", TissueKind::Bone, "", false, test::sphere(1, 10.0)});
  return a;
}

// Replaces `from` by `to` in the folder's reference.json.
void edit(const std::string& dir, const std::string& from, const std::string& to) {
  const std::string path = dir + "/reference.json";
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  std::ofstream(path) << text;
}

TEST(ReferenceAnatomyIo, ATissueNameNeverBecomesAPath) {
  const std::string dir = folder("round_trip");
  writeReferenceAnatomy(dir, twoSpheres(), {});
  EXPECT_EQ(tissueFile("bone/../../x"), "tissues/bone_______x.obj");
  EXPECT_TRUE(fs::exists(dir + "/" + tissueFile("bone/../../x")));
  const ReferenceAnatomy back = readReferenceAnatomy(dir);
  ASSERT_EQ(back.tissues.size(), 1u);
  EXPECT_EQ(back.tissues[0].name, "bone/../../x");
  EXPECT_EQ(back.tissues[0].mesh.F.rows(), twoSpheres().tissues[0].mesh.F.rows());
}

TEST(ReferenceAnatomyIo, MeshesOutsideTheFolderAndBadVersionsAreRefused) {
  const std::string outside = folder("outside");
  writeReferenceAnatomy(outside, twoSpheres(), {});
  writeTriMesh(fs::path(outside).parent_path().string() + "/elsewhere.obj", test::sphere(1, 5.0), {true});
  edit(outside, "\"tissues/bone_______x.obj\"", "\"../elsewhere.obj\"");
  test::expectOneLineBadInput(outside + "/reference.json", "mesh file '../elsewhere.obj' lies outside the reference folder",
                              [&] { readReferenceAnatomy(outside); });
  const std::string absolute = folder("absolute");
  writeReferenceAnatomy(absolute, twoSpheres(), {});
  edit(absolute, "\"skin.obj\"", "\"/etc/hostname\"");
  test::expectOneLineBadInput(absolute + "/reference.json", "lies outside the reference folder",
                              [&] { readReferenceAnatomy(absolute); });
  const std::string version = folder("version");
  writeReferenceAnatomy(version, twoSpheres(), {});
  edit(version, "\"version\": 1", "\"version\": \"1\"");
  test::expectOneLineBadInput(version + "/reference.json", "unsupported reference anatomy version",
                              [&] { readReferenceAnatomy(version); });
}

// Members of the wrong type (the fuzz_reference_json harness found the first one), each refused in one
// line naming reference.json and the member, not with a JSON library exception.
TEST(ReferenceAnatomyIo, MembersOfTheWrongTypeAreRefused) {
  const struct {
    const char *from, *to, *fragment;
  } cases[] = {
      {"\"kind\": \"bone\"", "\"kind\": \"bone\", \"group\": [0.0, -60.0, 0.0]", "\"group\" must be a string"},
      {"\"kind\": \"bone\"", "\"kind\": \"bone\", \"symmetric\": 1", "\"symmetric\" must be true or false"},
      {"\"name\": \"spheres\"", "\"name\": 7", "\"name\" must be a string"},
      {"\"format\": \"vesalius-reference-anatomy\"", "\"format\": 3", "not a reference anatomy"},
      {"\"tissues\": [", "\"tissues\": 5, \"unused\": [", "\"tissues\" must be an array"},
      {"\"points\": []", "\"points\": \"p\"", "\"points\" must be an array"},
      {"\"points\": []", "\"points\": [{\"name\": \"p\", \"tissue\": 5, \"position\": [0, 0, 0]}]",
       "\"tissue\" must be a string"},
      {"\"skin_cut_vertices\": []", "\"skin_cut_vertices\": [4294967296]", "must be an array of vertex indices"},
      {"\"skin_cut_vertices\": []", "\"skin_cut_vertices\": [-1]", "must be an array of vertex indices"},
  };
  int n = 0;
  for (const auto& c : cases) {
    const std::string dir = folder("wrong_type_" + std::to_string(n++));
    writeReferenceAnatomy(dir, twoSpheres(), {});
    edit(dir, c.from, c.to);
    test::expectOneLineBadInput(dir + "/reference.json", c.fragment, [&] { readReferenceAnatomy(dir); });
  }
}

}  // namespace
}  // namespace vesalius::io
