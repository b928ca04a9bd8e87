#include "anatomy_rig.h"

#include "vesalius/core/error.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/motion_io.h"
#include "vesalius/io/text_file.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace vesalius::cli {

Motion posedSkeletonMotion(const Skeleton& rest, const std::vector<Eigen::Isometry3d>& posedWorld) {
  Motion motion;
  motion.skeleton = rest;
  const std::vector<Channel> rotations{Channel::Zrotation, Channel::Yrotation, Channel::Xrotation};
  std::vector<double> values;
  for (std::size_t j = 0; j < rest.joints.size(); ++j) {
    const Joint& joint = rest.joints[j];
    if (!joint.restLocal.linear().isIdentity(1e-12))
      throw UsageError("skeleton '" + joint.name + "': a rotated rest frame cannot be written as BVH");
    const Eigen::Isometry3d parent = joint.parent < 0 ? Eigen::Isometry3d::Identity() : posedWorld[joint.parent];
    const Eigen::Isometry3d local = parent.inverse() * posedWorld[j];
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

MatrixX3d AnatomyRig::centres() const {
  const auto found = tets.vertexAttributes.real.find("cor_centre");
  if (found == tets.vertexAttributes.real.end() || found->second.cols() != 3)
    throw BadInput("rig.vtu", "has no centres of rotation for CoR skinning (it was made with --no-cor-centres; "
                              "run `vesalius rig` without it)");
  return found->second;
}

void writeAnatomyRig(const std::string& dir, const AnatomyRig& rig,
                     const std::vector<std::pair<std::string, TriMesh>>& meshes, const WriteOptions& options) {
  fs::create_directories(fs::path(dir) / "meshes");
  io::writeTetMesh(dir + "/rig.vtu", rig.tets, io::MeshWriteOptions{options});
  writeAtomically(dir + "/bones.txt", options, [&](const std::string& path) {
    std::ofstream out(path);
    for (int j : rig.boneJoint) out << rig.skeleton.joints[j].name << '\n';
    if (!out) throw BadInput(path, "cannot write");
  });
  std::vector<Eigen::Isometry3d> rest = rig.skeleton.restWorld();
  io::writeBvh(dir + "/skeleton.bvh", posedSkeletonMotion(rig.skeleton, rest), options);
  for (const auto& [name, mesh] : meshes) io::writeTriMesh(dir + "/meshes/" + name, mesh, io::MeshWriteOptions{options});
}

AnatomyRig readAnatomyRig(const std::string& dir) {
  AnatomyRig rig;
  const std::string tetsPath = dir + "/rig.vtu", bonesPath = dir + "/bones.txt";
  for (const std::string& p : {tetsPath, bonesPath, dir + "/skeleton.bvh"})
    if (!fs::exists(p)) throw BadInput(p, "missing (make the anatomy directory with `vesalius rig`)");
  rig.tets = io::readTetMesh(tetsPath);
  rig.skeleton = io::readBvh(dir + "/skeleton.bvh").skeleton;
  std::istringstream names(io::readTextFile(bonesPath));
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
  return rig;
}

}  // namespace vesalius::cli
