// Issue 32, item 1: a full disk. Each writer of io, given a file system with no room (or too little room)
// for its output, must throw a BadInput naming the output and leave nothing behind: neither the output
// nor a temporary. The file system is a 2 MB tmpfs the test mounts (full_disk.h); without the right to
// mount one the test is skipped.
#include "vesalius/core/error.h"
#include "vesalius/core/grid.h"
#include "vesalius/core/label_map.h"
#include "vesalius/core/markers.h"
#include "vesalius/core/mesh.h"
#include "vesalius/core/skeleton.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/label_table_io.h"
#include "vesalius/io/marker_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/motion_io.h"
#include "vesalius/io/report.h"

#include "full_disk.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>
#include <random>
#include <string>
#include <vector>

namespace vesalius::io {
namespace {

namespace fs = std::filesystem;

// One writer: what it writes, the output's file name, and the call.
// The files writing `path` makes: itself, a label map's table beside it, TetGen's .node, .ele and .face.
std::vector<std::string> filesOf(const std::string& path) {
  std::vector<std::string> files = labelTableSidecarPaths(path);
  if (fileExtension(path) == ".ele") {
    const std::string stem = path.substr(0, path.size() - 4);
    for (const char* extension : {".node", ".ele", ".face"}) files.push_back(stem + extension);
  } else {
    files.push_back(path);
  }
  return files;
}

struct Case {
  std::string what, name;
  std::function<void(const std::string& path)> write;
};

class FullDisk : public vesalius::test::FullDiskTest {
 protected:
  // Each case must throw BadInput naming its output (or another file it makes: a label map's table, TetGen's
  // .node) and leave only the filler.
  void expectEachFails(const std::vector<Case>& cases, const char* situation) {
    for (const Case& c : cases) {
      const std::string path = (dir / c.name).string();
      try {
        c.write(path);
        ADD_FAILURE() << c.what << " on a " << situation << " disk reported success";
      } catch (const BadInput& error) {
        const std::string message = error.what();
        std::cout << situation << ", " << c.what << ": " << message << "\n";
        bool namesAFile = false;
        for (const std::string& file : filesOf(path)) namesAFile |= message.rfind(file + ": ", 0) == 0;
        EXPECT_TRUE(namesAFile)
            << c.what << ": the message does not start with the output's name: " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << c.what << ": more than one line";
      } catch (const std::exception& error) {
        ADD_FAILURE() << c.what << ": not a BadInput: " << error.what();
      }
      EXPECT_EQ(listing(), std::vector<std::string>{"filler"}) << c.what << " left a file behind";
      for (const std::string& name : listing())
        if (name != "filler") fs::remove_all(dir / name);  // so the next case is judged on its own
    }
  }
};

// Random values, so compression cannot make them fit.
Image noiseImage(int n) {
  GridGeometry geometry;
  geometry.size = Eigen::Vector3i(n, n, n);
  Image image(geometry);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> value(-1000, 1000);
  for (float& v : image.values) v = value(random);
  return image;
}

LabelMap noiseLabels(int n) {
  GridGeometry geometry;
  geometry.size = Eigen::Vector3i(n, n, n);
  LabelMap map;
  map.labels = Grid<Label>(geometry);
  std::mt19937 random(8);
  std::uniform_int_distribution<int> label(0, 255);
  for (Label& v : map.labels.values) v = Label(label(random));
  map.table.add({1, "skin", {{200, 150, 120}}});
  return map;
}

// A wavy n by n sheet of triangles.
TriMesh sheet(int n) {
  TriMesh mesh;
  mesh.V.resize(n * n, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) mesh.V.row(i * n + j) << 0.37 * i, 0.41 * j, std::sin(0.1 * i) * std::cos(0.13 * j);
  mesh.F.resize(2 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      const int a = i * n + j, b = a + 1, c = a + n, d = c + 1;
      mesh.F.row(f++) << a, b, d;
      mesh.F.row(f++) << a, d, c;
    }
  return mesh;
}

// A wavy sheet's vertices lifted into a slab of n by n by 2 vertices, each square column split into three
// tetrahedra (the rows only need valid indices for the writers).
TetMesh slab(int n) {
  const TriMesh top = sheet(n);
  TetMesh tets;
  tets.V.resize(2 * top.V.rows(), 3);
  tets.V << top.V, top.V.rowwise() + Eigen::RowVector3d(0, 0, 1.7);
  tets.T.resize(3 * top.F.rows(), 4);
  const int lift = int(top.V.rows());
  for (Eigen::Index f = 0; f < top.F.rows(); ++f) {
    const int a = top.F(f, 0), b = top.F(f, 1), c = top.F(f, 2);
    tets.T.row(3 * f) << a, b, c, c + lift;
    tets.T.row(3 * f + 1) << a, b, c + lift, b + lift;
    tets.T.row(3 * f + 2) << a, a + lift, b + lift, c + lift;
  }
  return tets;
}

// A one-joint motion of `frames` frames of six channels.
Motion longMotion(int frames) {
  Motion motion;
  Joint root;
  root.name = "pelvis";
  root.tail = Eigen::Vector3d(0, 0, 10);
  motion.skeleton.joints.push_back(root);
  motion.channels = {{Channel::Xposition, Channel::Yposition, Channel::Zposition, Channel::Zrotation,
                      Channel::Xrotation, Channel::Yrotation}};
  motion.values.resize(frames, 6);
  for (int f = 0; f < frames; ++f)
    for (int c = 0; c < 6; ++c) motion.values(f, c) = 0.123456789 * f + 10.5 * c;
  return motion;
}

MarkerSet manyMarkers(int count) {
  MarkerSet set;
  set.name = "icp";
  for (int i = 0; i < count; ++i) {
    Marker m;
    m.label = "icp-" + std::to_string(i);
    m.kind = MarkerKind::IcpMarker;
    m.position = Eigen::Vector3d(0.123456789 * i, -1.5 * i, 3.25 + i);
    m.description = "a marker on the liver boundary, written to fill the disk";
    set.markers.push_back(m);
  }
  return set;
}

LabelTable longTable(int count) {
  LabelTable table;
  for (int id = 1; id <= count; ++id) table.add(LabelEntry{Label(id), "structure_number_" + std::to_string(id), {}});
  return table;
}

Report longReport(int count) {
  Report report("fill");
  for (int i = 0; i < count; ++i) report.metric("measure_" + std::to_string(i), 0.123456789 * i);
  return report;
}

std::vector<Case> writers() {
  // Each output is far larger than the room left on the nearly full disk.
  static const Image image = noiseImage(64);           // 1 MB of float32 noise
  static const LabelMap labels = noiseLabels(48);      // 110 kB of uint8 noise
  static const TriMesh mesh = sheet(120);              // 14,400 vertices, 28,322 triangles
  static const MarkerSet markers = manyMarkers(2000);  // about 1 MB as markups JSON
  static const TriMesh smallMesh = sheet(40);          // 1,600 vertices, 3,042 triangles (760 kB as ASCII STL)
  static const TetMesh tets = slab(40);                // 3,200 vertices, 9,126 tetrahedra
  static const Motion motion = longMotion(20000);      // about 1.5 MB of BVH frames
  static const LabelTable table = longTable(20000);    // about 600 kB
  static const Report report = longReport(20000);      // about 700 kB of JSON
  const auto asciiMesh = [] {
    MeshWriteOptions options;
    options.binary = false;
    return options;
  };
  return {
      {"binary STL mesh (writeTriMesh)", "skin.stl", [](const std::string& p) { writeTriMesh(p, mesh); }},
      {"ASCII STL mesh (writeTriMesh)", "skin-ascii.stl", [=](const std::string& p) { writeTriMesh(p, smallMesh, asciiMesh()); }},
      {"legacy VTK surface (writeTriMesh)", "skin.vtk", [](const std::string& p) { writeTriMesh(p, mesh); }},
      {"ASCII legacy VTK surface (writeTriMesh)", "skin-ascii.vtk", [=](const std::string& p) { writeTriMesh(p, mesh, asciiMesh()); }},
      {"glTF binary (writeTriMesh)", "skin.glb", [](const std::string& p) { writeTriMesh(p, mesh); }},
      {"VTU tet mesh (writeTetMesh)", "tets.vtu", [](const std::string& p) { writeTetMesh(p, tets); }},
      {"legacy VTK tet mesh (writeTetMesh)", "tets.vtk", [](const std::string& p) { writeTetMesh(p, tets); }},
      {"Gmsh tet mesh (writeTetMesh)", "tets.msh", [](const std::string& p) { writeTetMesh(p, tets); }},
      {"MEDIT tet mesh (writeTetMesh)", "tets.mesh", [](const std::string& p) { writeTetMesh(p, tets); }},
      {"BVH motion (writeBvh)", "motion.bvh", [](const std::string& p) { writeBvh(p, motion); }},
      {"CSV markers (writeMarkers)", "icp.csv", [](const std::string& p) { writeMarkers(p, markers); }},
      {"NIfTI scan (writeScan)", "th.nii.gz", [](const std::string& p) { writeScan(p, image); }},
      {"MetaImage scan (writeScan)", "scan.mha", [](const std::string& p) { writeScan(p, image); }},
      {"NRRD scan (writeScan)", "scan.nrrd", [](const std::string& p) { writeScan(p, image); }},
      {"uncompressed NIfTI scan (writeScan)", "scan.nii", [](const std::string& p) { writeScan(p, image); }},
      {"NIfTI label map (writeLabelMap)", "labels.nii.gz", [](const std::string& p) { writeLabelMap(p, labels); }},
      {"Slicer segmentation (writeLabelMap)", "labels.seg.nrrd", [](const std::string& p) { writeLabelMap(p, labels); }},
      {"PLY mesh (writeTriMesh)", "skin.ply", [](const std::string& p) { writeTriMesh(p, mesh); }},
      {"ASCII PLY mesh (writeTriMesh)", "skin-ascii.ply",
       [](const std::string& p) {
         MeshWriteOptions options;
         options.binary = false;
         writeTriMesh(p, mesh, options);
       }},
      {"OBJ mesh (writeTriMesh)", "skin.obj", [](const std::string& p) { writeTriMesh(p, mesh); }},
      {"VTP mesh (writeTriMesh)", "skin.vtp", [](const std::string& p) { writeTriMesh(p, mesh); }},
      {"markups (writeMarkers)", "icp.mrk.json", [](const std::string& p) { writeMarkers(p, markers); }},
      {"fcsv markers (writeMarkers)", "icp.fcsv", [](const std::string& p) { writeMarkers(p, markers); }},
      {"ITK-SNAP annotations (writeMarkers)", "icp.annot",
       [](const std::string& p) { writeMarkers(p, markers, {}, &image.geometry); }},
      {"TetGen tet mesh (writeTetMesh)", "tets.ele", [](const std::string& p) { writeTetMesh(p, tets); }},
      {"label table (writeLabelTable)", "labels.tsv", [](const std::string& p) { writeLabelTable(p, table); }},
      {"report (Report::write)", "report.json", [](const std::string& p) { report.write(p, {}); }},
  };
}

TEST_F(FullDisk, EveryWriterFailsCleanlyOnAFullDisk) {
  fill(0);
  expectEachFails(writers(), "full");
}

// Room for the headers but not the data: a writer that ignored its failed writes would leave a truncated
// file that looks whole.
TEST_F(FullDisk, EveryWriterFailsCleanlyOnANearlyFullDisk) {
  fill(64 * 1024);
  expectEachFails(writers(), "nearly full");
}

// The same writers succeed once there is room, so the failures above are the disk's.
TEST_F(FullDisk, TheSameWritersSucceedWithRoom) {
  for (const Case& c : writers()) {
    const std::string path = (dir / c.name).string();
    EXPECT_NO_THROW(c.write(path)) << c.what;
    EXPECT_TRUE(fs::exists(path)) << c.what;
    for (const std::string& file : filesOf(path)) fs::remove(file);
  }
  EXPECT_TRUE(listing().empty());
}

}  // namespace
}  // namespace vesalius::io
