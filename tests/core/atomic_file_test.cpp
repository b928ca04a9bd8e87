// writeAtomically: nothing is lost, nothing half-written is left, no planted symlink is followed, an
// interrupted write leaves no temporary; fileExtension; safeFileName.
#include "vesalius/core/atomic_file.h"
#include "vesalius/core/error.h"
#include "vesalius/core/safe_file_name.h"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <map>
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
  // The names in `dir`, sorted.
  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename());
    std::sort(names.begin(), names.end());
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
  // In a private folder beside the target, under the target's own name.
  EXPECT_EQ(fs::path(temporary).parent_path().parent_path(), dir);
  EXPECT_EQ(fs::path(temporary).filename(), "scan.nii.gz");
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

TEST_F(AtomicFile, ErrorsNameTheOutputNotTheTemporary) {
  const std::string target = (dir / "liver.ply").string();
  try {
    writeAtomically(target, {},
                    [](const std::string& tmp) { throw BadInput(tmp, "cannot open " + tmp + " for writing"); });
    FAIL() << "the writer's error was swallowed";
  } catch (const BadInput& error) {
    EXPECT_EQ(std::string(error.what()), target + ": cannot open " + target + " for writing");
    EXPECT_EQ(error.file(), target);
  }
  EXPECT_TRUE(listing().empty());
}

TEST_F(AtomicFile, AWriterThatMakesNoFileFails) {
  const std::string target = (dir / "skin.vtp").string();
  try {
    writeAtomically(target, {}, [](const std::string&) {});
    FAIL() << "nothing was written, yet no error";
  } catch (const BadInput& error) {
    EXPECT_EQ(error.file(), target);
    std::cout << "a writer that made no file: " << error.what() << "\n";
  }
  EXPECT_TRUE(listing().empty());
}

TEST_F(AtomicFile, WriteFileBytesChecksEveryByte) {
  const std::string path = (dir / "out.txt").string();
  writeFileBytes(path, "twelve bytes");
  EXPECT_EQ(get(path), "twelve bytes");
  // /dev/full accepts the open and fails every write with ENOSPC, as a full disk does.
  if (fs::exists("/dev/full")) {
    try {
      writeFileBytes("/dev/full", "x");
      FAIL() << "a write to /dev/full reported success";
    } catch (const BadInput& error) {
      EXPECT_EQ(error.file(), "/dev/full");
      std::cout << "/dev/full: " << error.what() << "\n";
    }
  }
}

// Issue 32, item 4: a symlink planted at a guessable temporary name such as ".<name>.tmp<pid><ext>" must not
// make the write land in its target; the temporary lives in a folder only this process can write in.
TEST_F(AtomicFile, APlantedSymlinkIsNotFollowed) {
  const fs::path victim = dir.parent_path() / (dir.filename().string() + "-victim.txt");
  put(victim.string(), "precious");
  const std::string target = (dir / "o.fcsv").string();
  const fs::path planted = dir / (".o.fcsv.tmp" + std::to_string(::getpid()) + ".fcsv");
  fs::create_symlink(victim, planted);
  std::string temporary;
  writeAtomically(target, {}, [&](const std::string& tmp) {
    temporary = tmp;
    EXPECT_FALSE(fs::exists(fs::symlink_status(tmp)));  // nothing waits at the name the writer gets
    struct stat folder {};
    ASSERT_EQ(::lstat(fs::path(tmp).parent_path().c_str(), &folder), 0);
    EXPECT_TRUE(S_ISDIR(folder.st_mode));
    EXPECT_EQ(folder.st_mode & 0777, 0700u);
    EXPECT_EQ(folder.st_uid, ::geteuid());
    put(tmp, "markers");  // opened by name, following symlinks, as ITK and VTK open files
  });
  EXPECT_NE(fs::path(temporary), planted);
  EXPECT_EQ(get(victim), "precious");
  EXPECT_EQ(get(target), "markers");
  EXPECT_TRUE(fs::is_symlink(planted));  // not ours to remove
  fs::remove(victim);
}

// Forks a child whose `write(started)` begins a write that never ends: `started()` tells the parent and
// waits for a signal. The parent runs `during()`, sends `signal` and returns the child's wait status, or
// -1 after recording a failure.
int signalledWhileWriting(int signal, const std::function<void(const std::function<void()>& started)>& write,
                          const std::function<void()>& during) {
  int ready[2];
  if (::pipe(ready) != 0) return ADD_FAILURE() << "pipe", -1;
  const pid_t child = ::fork();
  if (child < 0) return ADD_FAILURE() << "fork", -1;
  if (child == 0) {
    ::close(ready[0]);
    installCleanupOnSignal();
    try {
      write([&] {
        const char byte = 1;
        if (::write(ready[1], &byte, 1) != 1) ::_exit(10);
        for (;;) ::pause();  // only the signal stops it
      });
    } catch (...) {
      ::_exit(11);
    }
    ::_exit(12);
  }
  ::close(ready[1]);
  char byte = 0;
  const bool started = ::read(ready[0], &byte, 1) == 1;
  ::close(ready[0]);
  if (!started) return ADD_FAILURE() << "the child died before it started writing", -1;
  during();
  if (::kill(child, signal) != 0) return ADD_FAILURE() << "kill", -1;
  int status = 0;
  if (::waitpid(child, &status, 0) != child) return ADD_FAILURE() << "waitpid", -1;
  return status;
}

// Issue 32, item 6: a child process writes slowly and is interrupted; no hidden temporary is left.
// `nested`: the writer also fills a subfolder, as a multi-file output (a reference anatomy) does.
void expectNoTemporaryAfterSignal(const fs::path& dir, int signal, bool nested = false) {
  const std::string target = (dir / "th.nii.gz").string();
  std::vector<std::string> during;
  const int status = signalledWhileWriting(
      signal,
      [&](const std::function<void()>& started) {
        writeAtomically(target, {}, [&](const std::string& tmp) {
          writeFileBytes(tmp, std::string(1 << 20, 'v'));
          if (nested) {
            const fs::path tissues = fs::path(tmp).parent_path() / "tissues";
            fs::create_directories(tissues / "bones");
            writeFileBytes((tissues / "liver.obj").string(), "v 0 0 0\n");
            writeFileBytes((tissues / "bones" / "femur.obj").string(), "v 0 0 0\n");
          }
          started();
        });
      },
      [&] {
        for (const auto& entry : fs::directory_iterator(dir)) during.push_back(entry.path().filename());
      });
  ASSERT_EQ(during.size(), 1u) << "the child's temporary folder is not there";
  EXPECT_TRUE(WIFSIGNALED(status)) << "exit status " << status;
  if (WIFSIGNALED(status)) {
    EXPECT_EQ(WTERMSIG(status), signal);
  }
  std::vector<std::string> after;
  for (const auto& entry : fs::directory_iterator(dir)) after.push_back(entry.path().filename());
  EXPECT_TRUE(after.empty()) << "left behind: " << (after.empty() ? "" : after.front());
  std::cout << "signal " << signal << " during a write to " << target << ": temporary " << during.front()
            << " existed, " << after.size() << " entries left after the child died of the signal\n";
}

TEST_F(AtomicFile, SigintDuringAWriteLeavesNoTemporary) { expectNoTemporaryAfterSignal(dir, SIGINT); }

TEST_F(AtomicFile, SigtermDuringAWriteLeavesNoTemporary) { expectNoTemporaryAfterSignal(dir, SIGTERM); }

TEST_F(AtomicFile, SigintDuringAMultiFileWriteLeavesNoTemporary) {
  expectNoTemporaryAfterSignal(dir, SIGINT, true);
}

// writeFilesAtomically: files that belong together (a label map, its tables, its picture) appear all or
// none, an old set stays whole when the new one fails, and what a writer puts beside its temporary goes
// along.
TEST_F(AtomicFile, FilesWrittenTogetherAppearAllOrNone) {
  fs::create_directories(dir / "pictures");
  const std::vector<std::string> outputs{(dir / "labels.nii.gz").string(), (dir / "labels.tsv").string(),
                                         (dir / "pictures" / "labels.png").string()};
  std::vector<std::string> temporaries;
  writeFilesAtomically(outputs, {}, [&](const std::vector<std::string>& files) {
    temporaries = files;
    for (const std::string& output : outputs) EXPECT_FALSE(fs::exists(output));
    put(files[0], "voxels");
    put(files[1], "table");
    put(files[2], "picture");
  });
  EXPECT_EQ(get(outputs[0]), "voxels");
  EXPECT_EQ(get(outputs[1]), "table");
  EXPECT_EQ(get(outputs[2]), "picture");
  // One private folder per output folder: the label map's table is written beside its temporary.
  EXPECT_EQ(fs::path(temporaries[0]).parent_path(), fs::path(temporaries[1]).parent_path());
  EXPECT_EQ(fs::path(temporaries[2]).parent_path().parent_path(), dir / "pictures");
  EXPECT_EQ(listing(), (std::vector<std::string>{"labels.nii.gz", "labels.tsv", "pictures"}));

  // The picture fails after the labels were written: nothing new appears, the old set stays.
  WriteOptions force;
  force.force = true;
  try {
    writeFilesAtomically(outputs, force, [&](const std::vector<std::string>& files) {
      put(files[0], "new voxels");
      put(files[1], "new table");
      throw BadInput(files[2], "cannot write: no space left on device");
    });
    FAIL() << "the picture's failure was swallowed";
  } catch (const BadInput& error) {
    std::cout << "picture failed: " << error.what() << "\n";
    EXPECT_EQ(error.file(), outputs[2]);
  }
  EXPECT_EQ(get(outputs[0]), "voxels");
  EXPECT_EQ(get(outputs[1]), "table");
  EXPECT_EQ(get(outputs[2]), "picture");
  EXPECT_EQ(listing(), (std::vector<std::string>{"labels.nii.gz", "labels.tsv", "pictures"}));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir / "pictures"), fs::directory_iterator()), 1);
}

// The last file cannot be moved into place (something made a folder there meanwhile): the files already
// moved are undone, the old ones back.
TEST_F(AtomicFile, FilesWrittenTogetherAreUndoneWhenOneCannotBeMoved) {
  const std::vector<std::string> outputs{(dir / "labels.nii.gz").string(), (dir / "labels.png").string()};
  put(outputs[0], "old voxels");
  WriteOptions force;
  force.force = true;
  EXPECT_THROW(writeFilesAtomically(outputs, force,
                                    [&](const std::vector<std::string>& files) {
                                      put(files[0], "new voxels");
                                      put(files[1], "new picture");
                                      fs::create_directories(fs::path(outputs[1]) / "held");
                                    }),
               BadInput);
  EXPECT_EQ(get(outputs[0]), "old voxels");
  EXPECT_TRUE(fs::is_directory(outputs[1]));
  fs::remove_all(outputs[1]);
  EXPECT_EQ(listing(), std::vector<std::string>{"labels.nii.gz"});

  // Without an old file, the first one is removed again.
  fs::remove(outputs[0]);
  EXPECT_THROW(writeFilesAtomically(outputs, {},
                                    [&](const std::vector<std::string>& files) {
                                      put(files[0], "new voxels");
                                      put(files[1], "new picture");
                                      fs::create_directories(fs::path(outputs[1]) / "held");
                                    }),
               BadInput);
  EXPECT_EQ(listing(), std::vector<std::string>{"labels.png"});
}

TEST_F(AtomicFile, FilesWrittenTogetherTakeWhatTheWriterPutsBeside) {
  const std::string header = (dir / "scan.nhdr").string();
  writeFilesAtomically({header}, {}, [&](const std::vector<std::string>& files) {
    put(files[0], "data file: scan.raw.gz");
    put((fs::path(files[0]).parent_path() / "scan.raw.gz").string(), "voxels");
  });
  EXPECT_EQ(get(dir / "scan.raw.gz"), "voxels");
  EXPECT_EQ(listing(), (std::vector<std::string>{"scan.nhdr", "scan.raw.gz"}));
  // An existing file there is checked as an output: kept without force, and nothing else appears.
  fs::remove(header);
  EXPECT_THROW(writeFilesAtomically({header}, {},
                                    [&](const std::vector<std::string>& files) {
                                      put(files[0], "data file: scan.raw.gz");
                                      put((fs::path(files[0]).parent_path() / "scan.raw.gz").string(), "new");
                                    }),
               UsageError);
  EXPECT_EQ(get(dir / "scan.raw.gz"), "voxels");
  EXPECT_EQ(listing(), std::vector<std::string>{"scan.raw.gz"});
}

TEST_F(AtomicFile, AFileGivenTwiceIsRefused) {
  const std::string labels = (dir / "labels.nii.gz").string();
  bool called = false;
  EXPECT_THROW(writeFilesAtomically({labels, (dir / "." / "labels.nii.gz").string()}, {},
                                    [&](const std::vector<std::string>&) { called = true; }),
               UsageError);
  EXPECT_FALSE(called);
  EXPECT_TRUE(listing().empty());
}

// writeFolderAtomically: the folder appears whole at the end, a failure or a signal halfway leaves the
// old folder (or none) as it was, and nothing beside it.
class AtomicFolder : public AtomicFile {
 protected:
  // Path -> bytes of every file under `root`, to compare a folder before and after.
  static std::map<std::string, std::string> contents(const fs::path& root) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(root))
      if (entry.is_regular_file()) files[fs::relative(entry.path(), root).string()] = get(entry.path());
    return files;
  }
  // Writes `files` files, some in a subfolder, into `staging`; throws after `failAfter` of them.
  static void writeSome(const std::string& staging, int files, int failAfter = -1) {
    fs::create_directories(fs::path(staging) / "meshes" / "bones");
    for (int i = 0; i < files; ++i) {
      if (i == failAfter) throw BadInput(staging + "/meshes/m" + std::to_string(i) + ".obj", "cannot write: test");
      writeFileBytes(staging + (i % 2 ? "/meshes/bones/m" : "/meshes/m") + std::to_string(i) + ".obj",
                     std::string(100 + i, 'v'));
    }
  }
};

TEST_F(AtomicFolder, AppearsWholeAndReplacesOnlyWithForce) {
  const std::string target = (dir / "rig").string();
  for (const int files : {1, 3, 8}) {
    SCOPED_TRACE(files);
    writeFolderAtomically(target, {files > 1}, [&](const std::string& staging) {
      EXPECT_NE(staging, target);
      EXPECT_TRUE(fs::is_directory(staging));
      EXPECT_TRUE(fs::is_empty(staging));
      EXPECT_EQ(fs::path(staging).parent_path().parent_path(), dir);  // beside the target, so one file system
      writeSome(staging, files);
    });
    EXPECT_EQ(contents(target).size(), std::size_t(files));  // the new folder only, none of the old files
    EXPECT_EQ(listing(), std::vector<std::string>{"rig"});
  }
  const auto before = contents(target);
  EXPECT_THROW(writeFolderAtomically(target, {}, [](const std::string&) { FAIL() << "written without --force"; }),
               UsageError);
  EXPECT_EQ(contents(target), before);
  put((dir / "file").string(), "a file");
  EXPECT_THROW(writeFolderAtomically((dir / "file").string(), {true}, [](const std::string&) {}), UsageError);
  EXPECT_EQ(get(dir / "file"), "a file");
  EXPECT_THROW(writeFolderAtomically((dir / "missing" / "rig").string(), {}, [](const std::string&) {}), UsageError);
  EXPECT_FALSE(fs::exists(dir / "missing"));
}

TEST_F(AtomicFolder, AFailureHalfwayLeavesTheOldFolderOrNone) {
  for (const bool replacing : {false, true}) {
    const std::string target = (dir / (replacing ? "old" : "new")).string();
    std::map<std::string, std::string> before;
    if (replacing) {
      writeFolderAtomically(target, {}, [](const std::string& staging) { writeSome(staging, 5); });
      before = contents(target);
    }
    for (const int failAfter : {1, 4}) {
      SCOPED_TRACE(target + " failing after " + std::to_string(failAfter));
      try {
        writeFolderAtomically(target, {true}, [&](const std::string& staging) { writeSome(staging, 6, failAfter); });
        ADD_FAILURE() << "no error";
      } catch (const BadInput& error) {
        // Named inside the output folder, never in the staging folder.
        EXPECT_EQ(error.file(), target + "/meshes/m" + std::to_string(failAfter) + ".obj");
      }
      EXPECT_EQ(fs::exists(target), replacing);
      if (replacing) { EXPECT_EQ(contents(target), before); }
      std::vector<std::string> expected{fs::path(target).filename().string()};
      if (!replacing) expected.clear();
      EXPECT_EQ(listing(), expected);  // no staging folder left
    }
  }
}

// A folder write that a signal stops: the process dies of it, the staging folder is gone, and the folder
// it was replacing is whole.
TEST_F(AtomicFolder, ASignalHalfwayLeavesTheOldFolder) {
  const std::string target = (dir / "poses").string();
  writeFolderAtomically(target, {}, [](const std::string& staging) { writeSome(staging, 3); });
  const auto before = contents(target);
  for (const int signal : {SIGINT, SIGTERM}) {
    std::size_t during = 0;
    const int status = signalledWhileWriting(
        signal,
        [&](const std::function<void()>& started) {
          writeFolderAtomically(target, {true}, [&](const std::string& staging) {
            writeSome(staging, 7);
            started();
          });
        },
        [&] { during = listing().size(); });
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal) << "exit status " << status;
    EXPECT_EQ(during, 2u);  // the folder and its staging folder
    EXPECT_EQ(listing(), std::vector<std::string>{"poses"});
    EXPECT_EQ(contents(target), before);
    std::cout << "signal " << signal << " during a folder write: " << during << " entries beside, "
              << listing().size() << " after; the old folder's " << before.size() << " files unchanged\n";
  }
}

TEST_F(AtomicFolder, NeverReplacesAFolderHoldingAnInput) {
  const std::string target = (dir / "reference").string();
  writeFolderAtomically(target, {}, [](const std::string& staging) { writeSome(staging, 2); });
  const auto before = contents(target);
  protectInput(target + "/meshes/m0.obj");
  for (const std::string& out : {target, dir.string()}) {
    SCOPED_TRACE(out);
    EXPECT_THROW(writeFolderAtomically(out, {true}, [](const std::string&) { FAIL() << "written"; }), UsageError);
  }
  EXPECT_EQ(contents(target), before);
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

// Names from files become file names that stay where they are put.
TEST(SafeFileName, NoSeparatorDotOrControlCharacterSurvives) {
  EXPECT_EQ(safeFileName("liver"), "liver");
  EXPECT_EQ(safeFileName("hip_left-2"), "hip_left-2");
  EXPECT_EQ(safeFileName("../x"), "___x");
  EXPECT_EQ(safeFileName("/tmp/y"), "_tmp_y");
  EXPECT_EQ(safeFileName(".."), "__");
  EXPECT_EQ(safeFileName(std::string("a\0b\n", 4)), "a_b_");
  EXPECT_EQ(safeFileName("f\xc3\xa9mur"), "f__mur");
  EXPECT_EQ(safeFileName(""), "unnamed");
}

}  // namespace
}  // namespace vesalius
