#include "vesalius/io/anatomy_rig_io.h"

#include "vesalius/core/error.h"
#include "vesalius/core/safe_file_name.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/motion_io.h"
#include "vesalius/io/text_file.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace vesalius::io {

Motion posedSkeletonMotion(const Skeleton& rest, const std::vector<Eigen::Isometry3d>& posedWorld) {
  // BVH offsets carry no rotation: the file's skeleton has the joints' rest positions with unrotated frames,
  // each posed by its joint's rest-to-posed map, which is all skinning needs (skeleton_pose.h).
  const std::vector<Eigen::Isometry3d> restWorld = rest.restWorld();
  Motion motion;
  motion.skeleton = rest;
  std::vector<Eigen::Isometry3d> world(rest.joints.size());
  const std::vector<Channel> rotations{Channel::Zrotation, Channel::Yrotation, Channel::Xrotation};
  std::vector<double> values;
  for (std::size_t j = 0; j < rest.joints.size(); ++j) {
    Joint& joint = motion.skeleton.joints[j];
    const Eigen::Vector3d at = restWorld[j].translation();
    world[j] = posedWorld[j] * restWorld[j].inverse() * Eigen::Translation3d(at);
    joint.restLocal = Eigen::Translation3d(joint.parent < 0 ? at : at - restWorld[joint.parent].translation());
    joint.tail = restWorld[j].linear() * joint.tail;
    const Eigen::Isometry3d parent = joint.parent < 0 ? Eigen::Isometry3d::Identity() : world[joint.parent];
    const Eigen::Isometry3d local = parent.inverse() * world[j];
    std::vector<Channel> channels = rotations;
    if (joint.parent < 0) {
      channels.insert(channels.begin(), {Channel::Xposition, Channel::Yposition, Channel::Zposition});
      const Eigen::Vector3d shift = local.translation() - joint.restLocal.translation();
      values.insert(values.end(), {shift.x(), shift.y(), shift.z()});
    }
    // Z Y X channels compose as Rz·Ry·Rx (core/skeleton.h): Euler angles about axes 2, 1, 0.
    const Eigen::Vector3d zyx = local.linear().eulerAngles(2, 1, 0) * (180.0 / M_PI);
    values.insert(values.end(), {zyx[0], zyx[1], zyx[2]});
    motion.channels.push_back(channels);
  }
  motion.values = Eigen::Map<Eigen::RowVectorXd>(values.data(), Eigen::Index(values.size()));
  return motion;
}

namespace {

bool hasRotatedFrames(const Skeleton& skeleton) {
  for (const Eigen::Isometry3d& w : skeleton.restWorld())
    if (!w.linear().isIdentity(1e-12)) return true;
  return false;
}

// frames.txt: "name r00 r01 r02 r10 ... r22" per joint, its rest world rotation row by row.
void writeFrames(const std::string& path, const Skeleton& skeleton, const WriteOptions& options) {
  const std::vector<Eigen::Isometry3d> world = skeleton.restWorld();
  writeAtomically(path, options, [&](const std::string& temporary) {
    std::ofstream out(temporary);
    out.precision(17);
    for (std::size_t j = 0; j < world.size(); ++j) {
      out << skeleton.joints[j].name;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) out << ' ' << world[j].linear()(r, c);
      out << '\n';
    }
    out.close();  // the last buffered bytes reach the file here, so check after it
    if (!out) throw BadInput(temporary, "cannot write");
  });
}

// Turns the rest frames of `skeleton` (read from BVH, unrotated) to those of frames.txt, keeping every
// joint's position and tail.
void readFrames(const std::string& path, Skeleton& skeleton) {
  std::vector<Eigen::Isometry3d> world = skeleton.restWorld();
  std::istringstream lines(readTextFile(path));
  for (std::string line; std::getline(lines, line);) {
    std::istringstream in(line);
    std::string name;
    Eigen::Matrix3d R;
    if (!(in >> name)) continue;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) in >> R(r, c);
    const int j = skeleton.find(name);
    if (!in || j < 0 || !(R.transpose() * R).isIdentity(1e-9) || R.determinant() < 0)
      throw BadInput(path, "line '" + line + "' is not a joint of skeleton.bvh and a rotation");
    skeleton.joints[j].tail = R.transpose() * world[j].linear() * skeleton.joints[j].tail;
    world[j].linear() = R;
  }
  for (Joint& joint : skeleton.joints) {
    const int j = int(&joint - skeleton.joints.data());
    joint.restLocal = joint.parent < 0 ? world[j] : world[joint.parent].inverse() * world[j];
  }
}

}  // namespace

void writeAnatomyRig(const std::string& dir, const AnatomyRig& rig,
                     const std::vector<std::pair<std::string, TriMesh>>& meshes, const WriteOptions& options) {
  // Whole or not at all (core/atomic_file.h): a failure halfway leaves no mixed rig folder, which `pose`
  // would read as a rig of parts that do not belong together.
  writeFolderAtomically(dir, options, [&](const std::string& staging) {
    fs::create_directory(fs::path(staging) / "meshes");
    writeTetMesh(staging + "/rig.vtu", rig.tets);
    writeAtomically(staging + "/bones.txt", {}, [&](const std::string& path) {
      std::ofstream out(path);
      for (int j : rig.boneJoint) out << rig.skeleton.joints[j].name << '\n';
      out.close();
      if (!out) throw BadInput(path, "cannot write");
    });
    std::vector<Eigen::Isometry3d> rest = rig.skeleton.restWorld();
    writeBvh(staging + "/skeleton.bvh", posedSkeletonMotion(rig.skeleton, rest), {});
    if (hasRotatedFrames(rig.skeleton)) writeFrames(staging + "/frames.txt", rig.skeleton, {});
    // Mesh names come from label tables and reference.json: their stems are made safe (their extensions are
    // the writer's format).
    if (!rig.meshJoint.empty() && rig.meshJoint.size() != meshes.size())
      throw UsageError("writeAnatomyRig: " + std::to_string(rig.meshJoint.size()) + " mesh joints for " +
                       std::to_string(meshes.size()) + " meshes");
    std::ostringstream boneMeshes;
    for (std::size_t m = 0; m < meshes.size(); ++m) {
      const fs::path file(meshes[m].first);
      const std::string name = safeFileName(file.stem().string()) + file.extension().string();
      if (fs::exists(staging + "/meshes/" + name)) throw BadInput(dir, "two meshes share the file name meshes/" + name);
      writeTriMesh(staging + "/meshes/" + name, meshes[m].second);
      if (const int j = rig.jointOfMesh(m); j >= 0) boneMeshes << name << '\t' << rig.skeleton.joints[std::size_t(j)].name << '\n';
    }
    if (!boneMeshes.str().empty())
      writeAtomically(staging + "/bone_meshes.txt", {}, [&](const std::string& path) {
        std::ofstream out(path);
        out << boneMeshes.str();
        out.close();
        if (!out) throw BadInput(path, "cannot write");
      });
  });
}

AnatomyRig readAnatomyRig(const std::string& dir) {
  AnatomyRig rig;
  const std::string tetsPath = dir + "/rig.vtu", bonesPath = dir + "/bones.txt";
  for (const std::string& p : {tetsPath, bonesPath, dir + "/skeleton.bvh"})
    if (!fs::exists(p)) throw BadInput(p, "missing (make the anatomy directory with `vesalius rig`)");
  rig.tets = readTetMesh(tetsPath);
  rig.skeleton = readBvh(dir + "/skeleton.bvh").skeleton;
  if (fs::exists(dir + "/frames.txt")) readFrames(dir + "/frames.txt", rig.skeleton);
  std::istringstream names(readTextFile(bonesPath));
  for (std::string name; std::getline(names, name);) {
    if (name.empty()) continue;
    const int j = rig.skeleton.find(name);
    if (j < 0) throw BadInput(bonesPath, "bone '" + name + "' is not a joint of skeleton.bvh");
    rig.boneJoint.push_back(j);
  }
  const auto& real = rig.tets.vertexAttributes.real;
  const auto& integer = rig.tets.vertexAttributes.integer;
  if (!real.count("weights") || !integer.count("bone"))
    throw BadInput(tetsPath, "lacks the point data 'weights' or 'bone' of a rig");
  if (rig.weights().cols() != Eigen::Index(rig.boneJoint.size()))
    throw BadInput(tetsPath, "has " + std::to_string(rig.weights().cols()) + " weight columns for " +
                                 std::to_string(rig.boneJoint.size()) + " bones in bones.txt");
  if (fs::is_directory(dir + "/meshes"))
    for (const auto& entry : fs::directory_iterator(dir + "/meshes")) rig.meshes.push_back(entry.path().string());
  std::sort(rig.meshes.begin(), rig.meshes.end());
  const std::string boneMeshesPath = dir + "/bone_meshes.txt";
  if (fs::exists(boneMeshesPath)) {
    rig.meshJoint.assign(rig.meshes.size(), -1);
    std::istringstream lines(readTextFile(boneMeshesPath));
    for (std::string line; std::getline(lines, line);) {
      if (line.empty()) continue;
      const std::size_t tab = line.find('\t');
      const std::string file = line.substr(0, tab), joint = tab == std::string::npos ? "" : line.substr(tab + 1);
      const auto mesh = std::find_if(rig.meshes.begin(), rig.meshes.end(),
                                     [&](const std::string& m) { return fs::path(m).filename() == file; });
      const int j = rig.skeleton.find(joint);
      if (mesh == rig.meshes.end() || j < 0)
        throw BadInput(boneMeshesPath, "line '" + line + "' is not a file of meshes/, a tab and a joint of skeleton.bvh");
      rig.meshJoint[std::size_t(mesh - rig.meshes.begin())] = j;
    }
  }
  return rig;
}

}  // namespace vesalius::io
