// An output never replaces an input (core/atomic_file.h: protectInput, checkNotAnInput): through the
// writers that use writeAtomically, a reference folder's writer, and any name that reaches an input
// (symlink, hard link, a file inside an input folder, a folder holding an input), --force or not.
#include "test_shapes.h"
#include "vesalius/core/anatomy.h"
#include "vesalius/core/atomic_file.h"
#include "vesalius/core/error.h"
#include "vesalius/core/markers.h"
#include "vesalius/core/mesh.h"
#include "vesalius/io/marker_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/reference_anatomy_io.h"

#include <gtest/gtest.h>

#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace vesalius::io {
namespace {

namespace fs = std::filesystem;

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

using test::tetrahedron;

// A folder of this process under the test output (ctest runs tests at the same time).
std::string privateFolder() {
  fs::create_directories(VESALIUS_TEST_OUTPUT);
  std::string pattern = std::string(VESALIUS_TEST_OUTPUT) + "/protect-XXXXXX";
  EXPECT_NE(mkdtemp(pattern.data()), nullptr);
  return pattern;
}

TEST(InputProtection, NoNameOfAnInputIsReplacedWithForce) {
  const std::string d = privateFolder();
  writeTriMesh(d + "/input.obj", tetrahedron(10));
  fs::create_symlink("input.obj", d + "/symlink.obj");
  fs::create_hard_link(d + "/input.obj", d + "/hardlink.obj");
  writeTriMesh(d + "/other.obj", tetrahedron(10));
  const std::string before = readBytes(d + "/input.obj");
  protectInput(d + "/input.obj");
  for (const std::string& name : {std::string("input.obj"), std::string("symlink.obj"), std::string("hardlink.obj")}) {
    SCOPED_TRACE(name);
    try {
      writeTriMesh(d + "/" + name, tetrahedron(20), MeshWriteOptions{WriteOptions{true}});
      ADD_FAILURE() << "replaced " << name;
    } catch (const UsageError& e) {
      std::cout << e.what() << '\n';
      EXPECT_NE(std::string(e.what()).find(d + "/" + name), std::string::npos) << e.what();
    }
    EXPECT_EQ(readBytes(d + "/" + name), before);
  }
  // A file that is not an input is replaced as before.
  EXPECT_NO_THROW(writeTriMesh(d + "/other.obj", tetrahedron(20), MeshWriteOptions{WriteOptions{true}}));
  EXPECT_NE(readBytes(d + "/other.obj"), before);
}

TEST(InputProtection, AnInputFolderKeepsItsFilesAndNoFolderHoldingAnInputIsReplaced) {
  const std::string d = privateFolder();
  fs::create_directories(d + "/rig/meshes");
  MarkerSet markers;
  markers.markers.push_back(Marker{});
  writeMarkers(d + "/rig/markers.mrk.json", markers);
  writeTriMesh(d + "/rig/meshes/bone.obj", tetrahedron(5));
  protectInput(d + "/rig");
  // Existing files at any depth of the input folder are part of it.
  for (const std::string& existing : {std::string("/rig/markers.mrk.json"), std::string("/rig/meshes/bone.obj")}) {
    SCOPED_TRACE(existing);
    const std::string before = readBytes(d + existing);
    EXPECT_THROW(writeTriMesh(d + existing, tetrahedron(1), MeshWriteOptions{WriteOptions{true}}), UsageError);
    EXPECT_EQ(readBytes(d + existing), before);
  }
  // A new file beside them replaces nothing.
  EXPECT_NO_THROW(writeTriMesh(d + "/rig/meshes/new.obj", tetrahedron(1)));
  // A folder that holds the input (its parent), or the input folder itself, is never replaced whole.
  ReferenceAnatomy reference;
  reference.name = "protection";
  reference.skin = tetrahedron(50);
  for (const std::string& folder : {d, d + "/rig"}) {
    SCOPED_TRACE(folder);
    EXPECT_THROW(writeReferenceAnatomy(folder, reference, WriteOptions{true}), UsageError);
    EXPECT_TRUE(fs::exists(d + "/rig/meshes/bone.obj"));
  }
  EXPECT_NO_THROW(writeReferenceAnatomy(d + "/reference", reference, WriteOptions{true}));
  EXPECT_TRUE(fs::exists(d + "/reference/reference.json"));
}

}  // namespace
}  // namespace vesalius::io
