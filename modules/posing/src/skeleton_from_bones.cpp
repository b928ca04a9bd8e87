#include "vesalius/posing/skeleton_from_bones.h"

#include "vesalius/core/error.h"
#include "vesalius/posing/bone_frame.h"
#include "vesalius/posing/points_near.h"
#include "vesalius/posing/principal_axis.h"

#include <Eigen/Geometry>

#include <map>

namespace vesalius::posing {
namespace {

struct Region {
  MatrixX3d all, boundary;  // voxel centres, mm
};

// Voxel centres of each label in `ids`, all and boundary (a 6-neighbour of another label or off the grid).
std::map<Label, Region> regionsOf(const Grid<Label>& grid, const std::vector<Label>& ids) {
  std::map<Label, std::vector<Eigen::Vector3d>> all, boundary;
  for (Label id : ids) all[id], boundary[id];
  const GridGeometry& g = grid.geometry;
  static const int step[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i) {
        const Label l = grid.at(i, j, k);
        const auto found = all.find(l);
        if (l == 0 || found == all.end()) continue;
        const Eigen::Vector3d p = g.indexToWorld(Eigen::Vector3d(i, j, k));
        found->second.push_back(p);
        for (const auto& s : step)
          if (!g.contains(i + s[0], j + s[1], k + s[2]) || grid.at(i + s[0], j + s[1], k + s[2]) != l) {
            boundary[l].push_back(p);
            break;
          }
      }
  const auto matrix = [](const std::vector<Eigen::Vector3d>& points) {
    MatrixX3d P(Eigen::Index(points.size()), 3);
    for (std::size_t r = 0; r < points.size(); ++r) P.row(Eigen::Index(r)) = points[r].transpose();
    return P;
  };
  std::map<Label, Region> regions;
  for (Label id : ids) regions[id] = {matrix(all[id]), matrix(boundary[id])};
  return regions;
}

Eigen::Vector3d centroid(const MatrixX3d& P) { return P.colwise().mean().transpose(); }

}  // namespace

BoneSkeleton skeletonFromBones(const LabelMap& labels, const SkeletonFromBonesOptions& o, const std::string& source) {
  const auto idOf = [&](const std::string& name) -> Label {
    const LabelEntry* entry = labels.table.find(name);
    return entry ? entry->id : 0;
  };
  std::vector<Label> ids;
  for (const std::string* name : {&o.hipLeft, &o.hipRight, &o.sacrum, &o.femurLeft, &o.femurRight}) {
    if (idOf(*name) == 0) throw BadInput(source, "has no label '" + *name + "' in its table");
    ids.push_back(idOf(*name));
  }
  for (const std::string& name : o.spine)
    if (idOf(name) != 0) ids.push_back(idOf(name));
  std::map<Label, Region> region = regionsOf(labels.labels, ids);
  const auto bone = [&](const std::string& name) -> const Region& {
    const Region& r = region.at(idOf(name));
    if (r.all.rows() == 0) throw BadInput(source, "label '" + name + "' has no voxels");
    return r;
  };

  BoneSkeleton out;
  const auto head = [&](const std::string& femur, const std::string& hip, SphereFit& fit, long& count) {
    const MatrixX3d P = pointsNear(bone(femur).boundary, bone(hip).boundary, o.acetabulumDistance);
    count = long(P.rows());
    if (count < 10)
      throw BadInput(source, "'" + femur + "' has " + std::to_string(count) + " voxels within " +
                                 std::to_string(o.acetabulumDistance) + " mm of '" + hip + "' (a femoral head needs 10)");
    fit = fitSphere(P);
  };
  head(o.femurLeft, o.hipLeft, out.femoralHeadLeft, out.femoralHeadPointsLeft);
  head(o.femurRight, o.hipRight, out.femoralHeadRight, out.femoralHeadPointsRight);

  // Disc centres upward from the sacrum, one per vertebra present.
  std::vector<std::string> chain;
  std::vector<Eigen::Vector3d> disc;
  std::string below = o.sacrum;
  for (const std::string& name : o.spine) {
    if (idOf(name) == 0 || region.at(idOf(name)).all.rows() == 0) break;
    const MatrixX3d a = pointsNear(bone(below).boundary, bone(name).boundary, o.discDistance);
    const MatrixX3d b = pointsNear(bone(name).boundary, bone(below).boundary, o.discDistance);
    if (a.rows() == 0) throw BadInput(source, "'" + name + "' and '" + below + "' have no voxels within " +
                                                  std::to_string(o.discDistance) + " mm of each other");
    disc.push_back((a.colwise().sum() + b.colwise().sum()).transpose() / double(a.rows() + b.rows()));
    chain.push_back(name);
    below = name;
  }

  const Eigen::Vector3d left = out.femoralHeadLeft.centre - out.femoralHeadRight.centre;
  const Eigen::Vector3d origin = (out.femoralHeadLeft.centre + out.femoralHeadRight.centre) / 2;
  const Eigen::Vector3d up = (disc.empty() ? centroid(bone(o.sacrum).all) : disc[0]) - origin;
  std::vector<Eigen::Isometry3d> world{placedFrame(boneFrame(0, left, 2, up), origin)};
  std::vector<Joint> joints{{"pelvis", -1}};
  out.labels.push_back({idOf(o.hipLeft), idOf(o.hipRight), idOf(o.sacrum)});
  for (const auto& [name, fit] : {std::pair{&o.femurLeft, &out.femoralHeadLeft}, {&o.femurRight, &out.femoralHeadRight}}) {
    const MatrixX3d& P = bone(*name).all;
    const Eigen::Vector3d z = principalAxis(P, fit->centre - centroid(P));
    world.push_back(placedFrame(boneFrame(2, z, 0, left), fit->centre));
    Joint joint{*name, 0};
    joint.tail = Eigen::Vector3d(0, 0, ((P.rowwise() - fit->centre.transpose()) * z).minCoeff());
    joints.push_back(joint);
    out.labels.push_back({idOf(*name)});
  }
  for (std::size_t v = 0; v < chain.size(); ++v) {
    const Eigen::Vector3d end = v + 1 < disc.size() ? disc[v + 1] : centroid(bone(chain[v]).all);
    world.push_back(placedFrame(boneFrame(2, end - disc[v], 0, left), disc[v]));
    Joint joint{chain[v], v == 0 ? 0 : int(joints.size()) - 1};
    joint.tail = world.back().inverse() * end;
    joints.push_back(joint);
    out.labels.push_back({idOf(chain[v])});
  }
  for (std::size_t j = 0; j < joints.size(); ++j)
    joints[j].restLocal = joints[j].parent < 0 ? world[j] : world[std::size_t(joints[j].parent)].inverse() * world[j];
  out.skeleton.joints = joints;
  out.skeleton.validate(source);
  return out;
}

}  // namespace vesalius::posing
