// A rig folder's meshes are named after tissues from reference.json and label tables (`rig --reference`,
// `rig --labels`): a name holding "../", an absolute path or a folder still gives a file inside meshes/
// (issue 32, item 3), and nothing is written anywhere else.
#include "test_shapes.h"
#include "vesalius/core/anatomy_rig.h"
#include "vesalius/io/anatomy_rig_io.h"

#include <gtest/gtest.h>

#include <stdlib.h>

#include <filesystem>
#include <iostream>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace vesalius::io {
namespace {

namespace fs = std::filesystem;

using test::tetrahedron;

// One tetrahedron, one bone: the smallest rig writeAnatomyRig takes.
AnatomyRig oneTetRig() {
  AnatomyRig rig;
  rig.tets.V = tetrahedron(10).V;
  rig.tets.T.resize(1, 4);
  rig.tets.T << 0, 1, 2, 3;
  rig.tets.vertexAttributes.real["weights"] = Eigen::MatrixXd::Ones(4, 1);
  rig.tets.vertexAttributes.integer["bone"] = Eigen::VectorXi::Zero(4);
  Joint root;
  root.name = "pelvis";
  root.tail = Eigen::Vector3d(0, 0, 5);
  rig.skeleton.joints.push_back(root);
  rig.boneJoint = {0};
  return rig;
}

TEST(AnatomyRigNames, TissueNamesNeverLeaveTheMeshesFolder) {
  fs::create_directories(VESALIUS_TEST_OUTPUT);
  std::string pattern = std::string(VESALIUS_TEST_OUTPUT) + "/rig-names-XXXXXX";
  ASSERT_NE(mkdtemp(pattern.data()), nullptr);
  const fs::path base = pattern, dir = base / "inner" / "rig";
  fs::create_directories(dir.parent_path());
  const std::string absolute = (base / "absolute").string();
  const std::vector<std::pair<std::string, TriMesh>> meshes{
      {"skin.obj", tetrahedron(20)},
      {"../../escaped.obj", tetrahedron(1)},
      {absolute + ".obj", tetrahedron(2)},
      {"bone/../../x.obj", tetrahedron(3)},
      {"..obj", tetrahedron(4)}};
  writeAnatomyRig(dir.string(), oneTetRig(), meshes, {});

  std::set<std::string> inMeshes;
  for (const auto& entry : fs::recursive_directory_iterator(base)) {
    const fs::path relative = fs::relative(entry.path(), dir);
    if (entry.is_directory()) continue;
    SCOPED_TRACE(entry.path().string());
    ASSERT_EQ(relative.begin()->string() == "..", false) << "written outside the rig folder";
    if (relative.parent_path() == "meshes") inMeshes.insert(relative.filename().string());
  }
  std::cout << "meshes/:";
  for (const std::string& name : inMeshes) std::cout << " " << name;
  std::cout << "\n";
  EXPECT_EQ(inMeshes.size(), meshes.size());
  EXPECT_TRUE(inMeshes.count("skin.obj"));
  EXPECT_FALSE(fs::exists(absolute + ".obj"));
  EXPECT_FALSE(fs::exists(base / "escaped.obj"));
  EXPECT_FALSE(fs::exists(base / "inner" / "escaped.obj"));
  if (!HasFailure()) fs::remove_all(base);
}

}  // namespace
}  // namespace vesalius::io
