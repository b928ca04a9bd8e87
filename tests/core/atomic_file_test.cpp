// writeAtomically: nothing is lost, nothing half-written is left; fileExtension.
#include "vesalius/core/atomic_file.h"
#include "vesalius/core/error.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace vesalius {
namespace {

namespace fs = std::filesystem;

class AtomicFile : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir = fs::path(VESALIUS_TEST_OUTPUT) / "atomic" / info->name();
    fs::remove_all(dir);
    fs::create_directories(dir);
  }

  static void put(const std::string& path, const std::string& text) { std::ofstream(path) << text; }
  static std::string get(const fs::path& path) {
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename());
    return names;
  }

  fs::path dir;
};

TEST_F(AtomicFile, WritesThroughATemporaryBesideTheTarget) {
  const std::string target = (dir / "scan.nii.gz").string();
  std::string temporary;
  writeAtomically(target, {}, [&](const std::string& tmp) {
    temporary = tmp;
    EXPECT_FALSE(fs::exists(target));
    put(tmp, "voxels");
  });
  EXPECT_EQ(get(target), "voxels");
  EXPECT_NE(temporary, target);
  EXPECT_EQ(fs::path(temporary).parent_path(), dir);
  EXPECT_EQ(fileExtension(temporary), ".nii.gz");
  EXPECT_FALSE(fs::exists(temporary));
  EXPECT_EQ(listing(), std::vector<std::string>{"scan.nii.gz"});
}

TEST_F(AtomicFile, KeepsAnExistingOutputUnlessForced) {
  const std::string target = (dir / "liver.stl").string();
  put(target, "old");
  bool called = false;
  EXPECT_THROW(writeAtomically(target, {}, [&](const std::string& tmp) {
                 called = true;
                 put(tmp, "new");
               }),
               UsageError);
  EXPECT_FALSE(called);
  EXPECT_EQ(get(target), "old");
  WriteOptions force;
  force.force = true;
  writeAtomically(target, force, [&](const std::string& tmp) { put(tmp, "new"); });
  EXPECT_EQ(get(target), "new");
  EXPECT_EQ(listing(), std::vector<std::string>{"liver.stl"});
}

TEST_F(AtomicFile, AFailedWriteLeavesNothing) {
  const std::string target = (dir / "fitted.vtu").string();
  EXPECT_THROW(writeAtomically(target, {}, [&](const std::string& tmp) {
                 put(tmp, "half of a mesh");
                 throw NumericalFailure("solver diverged");
               }),
               NumericalFailure);
  EXPECT_TRUE(listing().empty());
  EXPECT_THROW(writeAtomically(target, {}, [](const std::string&) { throw std::runtime_error("x"); }),
               std::runtime_error);
  EXPECT_TRUE(listing().empty());
}

TEST_F(AtomicFile, AFailedForcedWriteKeepsTheOldOutput) {
  const std::string target = (dir / "points.mrk.json").string();
  put(target, "old");
  WriteOptions force;
  force.force = true;
  EXPECT_THROW(writeAtomically(target, force, [&](const std::string& tmp) {
                 put(tmp, "partial");
                 throw BadInput("points.mrk.json", "cannot encode");
               }),
               BadInput);
  EXPECT_EQ(get(target), "old");
  EXPECT_EQ(listing(), std::vector<std::string>{"points.mrk.json"});
}

TEST_F(AtomicFile, NeverReplacesAFolderOrDevice) {
  fs::create_directories(dir / "labels.nii.gz");
  bool called = false;
  EXPECT_THROW(writeAtomically((dir / "labels.nii.gz").string(), {true}, [&](const std::string&) { called = true; }),
               UsageError);
  EXPECT_THROW(writeAtomically("/dev/null", {true}, [&](const std::string&) { called = true; }), UsageError);
  EXPECT_FALSE(called);
  EXPECT_TRUE(fs::is_directory(dir / "labels.nii.gz"));
}

TEST(AtomicFileExtension, KnowsDoubleExtensionsAndLowersCase) {
  EXPECT_EQ(fileExtension("a/b.nii.gz"), ".nii.gz");
  EXPECT_EQ(fileExtension("markers.mrk.json"), ".mrk.json");
  EXPECT_EQ(fileExtension("labels.seg.nrrd"), ".seg.nrrd");
  EXPECT_EQ(fileExtension("LIVER.STL"), ".stl");
  EXPECT_EQ(fileExtension("Scan.NII.GZ"), ".nii.gz");
  EXPECT_EQ(fileExtension("report.json"), ".json");
  EXPECT_EQ(fileExtension("archive.tar.gz"), ".gz");
  EXPECT_EQ(fileExtension("dir.d/README"), "");
  EXPECT_EQ(fileExtension("noext"), "");
}

}  // namespace
}  // namespace vesalius
