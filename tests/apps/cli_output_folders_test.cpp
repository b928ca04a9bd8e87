// Commands that write a folder of files write it whole or not at all (issue 32, item 6; core/atomic_file.h
// writeFolderAtomically): a failure after the first file leaves no folder, or with --force the old one
// byte-identical, and nothing beside it; an output folder that is or holds an input is refused first.
#include "run_command.h"

#include "vesalius/core/label_map.h"
#include "vesalius/io/image_io.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

namespace vesalius::test {
namespace {

namespace fs = std::filesystem;

const std::string kBody = std::string(VESALIUS_TESTDATA) + "/body/";

std::string freshDir(const std::string& name) {
  const fs::path d = fs::path(outputDir()) / "output-folders" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d.string();
}

std::string readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const fs::path& path, const std::string& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << bytes;
}

// Every entry under `root` (hidden ones too), files with their bytes.
std::map<std::string, std::string> contents(const fs::path& root) {
  std::map<std::string, std::string> entries;
  for (const auto& entry : fs::recursive_directory_iterator(root))
    entries[fs::relative(entry.path(), root).string()] = entry.is_regular_file() ? readBytes(entry.path()) : "<folder>";
  return entries;
}

// `dir` holds what it held (`before`, from contents()): nothing left behind, nothing changed. Returns its
// contents.
std::map<std::string, std::string> expectAsBefore(const fs::path& dir, const std::map<std::string, std::string>& before) {
  const std::map<std::string, std::string> after = contents(dir);
  EXPECT_EQ(after.size(), before.size());
  for (const auto& [path, bytes] : after) {
    const auto was = before.find(path);
    if (was == before.end())
      ADD_FAILURE() << "left behind: " << path;
    else
      EXPECT_TRUE(was->second == bytes) << path << " changed";
  }
  return after;
}

// A folder someone had before the failing run: what --force must keep when the run fails.
void writeOldFolder(const std::string& dir) {
  writeBytes(dir + "/bones.txt", "pelvis\nfemur_l\n");
  writeBytes(dir + "/meshes/skin.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
}

// The command fails (exit `code`, one line on stderr naming `file` and `problem`), and `dir` (the folder
// holding the output folder and the inputs) is afterwards exactly as before: no output folder or the
// old one unchanged, no staging folder.
void expectFailsLeavingAllAsItWas(const std::vector<std::string>& args, int code, const std::string& dir,
                                  const std::string& file, const std::string& problem) {
  const std::map<std::string, std::string> before = contents(dir);
  const CommandResult r = runVesalius(args);
  EXPECT_EQ(r.exitCode, code) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  expectContains(r.err, file);
  expectContains(r.err, problem);
  const std::map<std::string, std::string> after = expectAsBefore(dir, before);
  std::cout << r.err << "  " << before.size() << " entries before, " << after.size() << " after\n";
}

// The command fails the same way writing a new folder `out` and replacing an old one with --force: no
// `out` after the first, the old folder byte-identical after the second.
void expectAllOrNothing(std::vector<std::string> args, const std::string& dir, const std::string& out,
                        const std::string& file, const std::string& problem) {
  expectFailsLeavingAllAsItWas(args, 3, dir, file, problem);
  EXPECT_FALSE(fs::exists(out));
  writeOldFolder(out);
  args.push_back("--force");
  expectFailsLeavingAllAsItWas(args, 3, dir, file, problem);
  EXPECT_EQ(readBytes(out + "/bones.txt"), "pelvis\nfemur_l\n");
  EXPECT_EQ(readBytes(out + "/meshes/skin.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
}

// `count` cubes of labels 1..count along x on a grid of `size` voxels; the last label's name is longer than
// a file name may be, so that its mesh, written last, fails after the others were written.
void writeLabels(const std::string& path, int size, int count) {
  LabelMap map;
  map.labels.geometry.size = Eigen::Vector3i(size, size, size);
  map.labels.values.assign(std::size_t(size) * size * size, 0);
  const int width = (size - 2) / count;
  for (int label = 1; label <= count; ++label) {
    for (int k = 2; k < size - 2; ++k)
      for (int j = 2; j < size - 2; ++j)
        for (int i = 1 + (label - 1) * width; i < label * width; ++i)
          map.labels.values[std::size_t(i + size * (j + size * k))] = Label(label);
    const std::string name = label < count ? "part_" + std::to_string(label) : std::string(300, 'x');
    map.table.add(LabelEntry{Label(label), name, defaultLabelColor(Label(label))});
  }
  io::writeLabelMap(path, map);
}

// `surface` with several labels: the last mesh cannot be written (its name is too long for the file
// system), after the others were.
TEST(CliOutputFolders, SurfaceWithSeveralLabelsWritesAllOrNothing) {
  for (const auto& [size, count] : {std::pair{14, 2}, std::pair{24, 4}}) {
    SCOPED_TRACE(std::to_string(count) + " labels");
    const std::string dir = freshDir("surface-" + std::to_string(count)), out = dir + "/meshes";
    writeLabels(dir + "/labels.nii.gz", size, count);
    std::vector<std::string> args{"surface", "--labels", dir + "/labels.nii.gz", "--out", out, "--progress", "none"};
    for (int label = 1; label <= count; ++label) args.insert(args.end(), {"--label", std::to_string(label)});
    const std::string last = out + "/" + std::string(300, 'x') + ".vtp";
    expectAllOrNothing(args, dir, out, last, "File name too long");
  }
}

// A report inside the output folder the command makes: its folder does not exist before the run and is
// not refused for that; a report into a folder that exists nowhere is.
TEST(CliOutputFolders, AReportInsideTheOutputFolderIsWritten) {
  const std::string dir = freshDir("report-inside"), out = dir + "/meshes";
  writeLabels(dir + "/labels.nii.gz", 24, 3);
  const std::vector<std::string> args{"surface", "--labels", dir + "/labels.nii.gz", "--out", out, "--label", "1",
                                      "--label", "2", "--progress", "none", "--report"};
  std::vector<std::string> inside = args;
  inside.push_back(out + "/report.json");
  const CommandResult r = runVesalius(inside);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(fs::exists(out + "/report.json"));
  EXPECT_TRUE(fs::exists(out + "/part_1.vtp"));
  std::vector<std::string> nowhere = args;
  nowhere.push_back(dir + "/missing/report.json");
  const CommandResult refused = runVesalius(nowhere);
  EXPECT_EQ(refused.exitCode, 2);
  EXPECT_NE(refused.err.find("which does not exist"), std::string::npos) << refused.err;
}

// `rig` with two --tissue meshes of one file name: refused when the second is written, after rig.vtu,
// bones.txt, skeleton.bvh and the skin were.
TEST(CliOutputFolders, RigWritesAllOrNothing) {
  const std::string dir = freshDir("rig"), out = dir + "/rig";
  const std::string tissue = kBody + "shapes/mh_neutral_body.obj";
  writeBytes(dir + "/a/tissue.obj", readBytes(tissue));
  writeBytes(dir + "/b/tissue.obj", readBytes(tissue));
  std::vector<std::string> args{"rig", "--skin", tissue, "--skeleton", kBody + "default.mhskel", "--voxel-size", "8",
                                "--target-tets", "8000", "--no-cor-centres", "--tissue", dir + "/a/tissue.obj",
                                "--tissue", dir + "/b/tissue.obj", "--out", out, "--progress", "none"};
  expectAllOrNothing(args, dir, out, out, "two meshes share the file name meshes/tissue.obj");
}

// An output folder that is an input, or holds one, is refused before any work, --force or not.
TEST(CliOutputFolders, AnOutputFolderThatIsOrHoldsAnInputIsRefused) {
  const std::string dir = freshDir("inputs");
  writeOldFolder(dir + "/reference");
  fs::create_directories(dir + "/labelled");
  writeLabels(dir + "/labelled/labels.nii.gz", 14, 2);
  writeBytes(dir + "/body/skin.obj", readBytes(kBody + "shapes/mh_neutral_body.obj"));
  const std::vector<std::vector<std::string>> cases{
      {"rig", "--reference", dir + "/reference", "--out", dir + "/reference", "--force"},
      {"rig", "--skin", dir + "/body/skin.obj", "--skeleton", kBody + "default.mhskel", "--out", dir + "/body", "--force"},
      {"surface", "--labels", dir + "/labelled/labels.nii.gz", "--out", dir + "/labelled", "--force"},
      {"reference", "torso", "--scan", dir + "/labelled/labels.nii.gz", "--labels", dir + "/labelled/labels.nii.gz",
       "--out", dir + "/labelled", "--force"},
      {"pose", "--anatomy", dir + "/reference", "--angles", "femur_l=10,0,0", "--out", dir, "--force"}};
  for (const std::vector<std::string>& args : cases) {
    SCOPED_TRACE(args[0] + " --out " + args[args.size() - 2]);
    std::vector<std::string> run = args;
    run.insert(run.end(), {"--progress", "none"});
    const std::string out = args[args.size() - 2];
    expectFailsLeavingAllAsItWas(run, 2, dir, out, "input");
  }
}

// Ctrl-C while `rig --force` writes its folder (issue 32, item 6): the program dies of the signal, and the
// old folder is whole, with nothing beside it. The signal is sent as soon as the hidden staging folder
// appears beside the output, so it lands while the files are written.
TEST(CliOutputFolders, SigintWhileWritingLeavesTheOldFolder) {
  const std::string dir = freshDir("sigint"), out = dir + "/rig";
  const std::string tissue = kBody + "shapes/mh_neutral_body.obj";
  writeOldFolder(out);
  const std::map<std::string, std::string> before = contents(dir);
  const std::vector<std::string> args{VESALIUS_EXE, "rig", "--skin", tissue, "--skeleton", kBody + "default.mhskel",
                                      "--voxel-size", "8", "--target-tets", "8000", "--no-cor-centres", "--out", out,
                                      "--force", "--progress", "none"};
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(VESALIUS_EXE, argv.data());
    ::_exit(127);
  }
  int status = 0;
  bool signalled = false;
  while (::waitpid(child, &status, WNOHANG) == 0) {
    if (!signalled && std::distance(fs::directory_iterator(dir), fs::directory_iterator()) > 1) {
      ASSERT_EQ(::kill(child, SIGINT), 0);
      signalled = true;
    }
    ::usleep(200);
  }
  if (!signalled) GTEST_SKIP() << "rig ended (status " << status << ") before its staging folder was seen";
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << "wait status " << status;
  const std::map<std::string, std::string> after = expectAsBefore(dir, before);
  std::cout << "SIGINT while rig wrote " << out << ": " << after.size() << " entries after, " << before.size()
            << " before\n";
}

// An output, or a report, in a folder the user cannot write to is refused before any work, in one line
// naming it (not its temporary). The folder is read-only by its mode, or for root (whom modes do not stop)
// a read-only tmpfs the test mounts; without the right to mount one the test is skipped as root.
TEST(CliOutputFolders, AnOutputInAReadOnlyFolderIsRefusedBeforeTheWork) {
  const std::string dir = freshDir("read-only"), readOnly = dir + "/read-only";
  writeLabels(dir + "/labels.nii.gz", 14, 2);
  fs::create_directories(readOnly);
  bool mounted = false;
  if (::geteuid() == 0) {
    mounted = std::system(("mount -t tmpfs -o ro,size=1m tmpfs '" + readOnly + "' 2>/dev/null").c_str()) == 0;
    if (!mounted) GTEST_SKIP() << "as root, cannot mount a read-only tmpfs at " << readOnly;
  } else {
    fs::permissions(readOnly, fs::perms::owner_read | fs::perms::owner_exec);
  }
  const std::vector<std::vector<std::string>> cases{
      {"labels", "crop", "--labels", dir + "/labels.nii.gz", "--out", readOnly + "/crop.nii.gz"},
      {"labels", "crop", "--labels", dir + "/labels.nii.gz", "--out", dir + "/crop.nii.gz", "--report",
       readOnly + "/report.json"}};
  for (const std::vector<std::string>& args : cases) {
    const std::string output = args.back(), option = args[args.size() - 2];
    SCOPED_TRACE(option + " " + output);
    expectFailsLeavingAllAsItWas(args, 2, dir, output + ": " + option + " is in the folder " + readOnly,
                                 "which is not writable");
  }
  if (mounted) std::system(("umount '" + readOnly + "'").c_str());
  else fs::permissions(readOnly, fs::perms::owner_all);
}

}  // namespace
}  // namespace vesalius::test
