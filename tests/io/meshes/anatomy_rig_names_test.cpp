// A rig folder's meshes are named after tissues from reference.json and label tables (`rig --reference`,
// `rig --labels`): a name holding "../", an absolute path or a folder still gives a file inside meshes/
// (issue 32, item 3), and nothing is written anywhere else.
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

TriMesh tetrahedronSurface(double size) {
  TriMesh m;
  m.V.resize(4, 3);
  m.V << 0, 0, 0, size, 0, 0, 0, size, 0, 0, 0, size;
  m.F.resize(4, 3);
  m.F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  return m;
}

// One tetrahedron, one bone: the smallest rig writeAnatomyRig takes.
AnatomyRig oneTetRig() {
  AnatomyRig rig;
  rig.tets.V = tetrahedronSurface(10).V;
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
      {"skin.obj", tetrahedronSurface(20)},
      {"../../escaped.obj", tetrahedronSurface(1)},
      {absolute + ".obj", tetrahedronSurface(2)},
      {"bone/../../x.obj", tetrahedronSurface(3)},
      {"..obj", tetrahedronSurface(4)}};
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
