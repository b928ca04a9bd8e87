// MakeHuman rigs: .mhskel skeletons and .mhw skin weights (JSON). See skeleton_io.h.
#include "vesalius/io/skeleton_io.h"
#include "vesalius/io/makehuman_target.h"

#include "vesalius/core/error.h"
#include "vesalius/core/mean_value_coordinates.h"
#include "vesalius/io/marker_formats.h"
#include "vesalius/io/text_file.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace vesalius::io {

namespace {

// Ordered, so that children keep the file's order.
using Json = nlohmann::ordered_json;

// Bone and joint names come from the file and may hold line breaks; messages stay one line.
[[noreturn]] void fail(const std::string& source, const std::string& problem) {
  throw BadInput(source, printable(problem, 300));
}

std::string jsonProblem(const char* what) {
  std::string s(what);
  std::size_t close = s.find("] ");
  return close == std::string::npos ? s : s.substr(close + 2);
}

Json parseJson(std::string_view text, const std::string& source) {
  try {
    return Json::parse(text.begin(), text.end());
  } catch (const Json::exception& e) {
    fail(source, "invalid JSON: " + jsonProblem(e.what()));
  }
}

const Json& objectMember(const Json& doc, const char* key, const std::string& source) {
  auto it = doc.is_object() ? doc.find(key) : doc.end();
  if (it == doc.end() || !it->is_object()) fail(source, std::string("no \"") + key + "\" object");
  return *it;
}

struct Bone {
  std::string name, parent;
  Eigen::Vector3d head, tail;
};

// A bone end names a joint (the mean of its base-mesh vertices) or, rarely, gives the position itself.
Eigen::Vector3d endPosition(const Json& joints, const Json& end, const Eigen::MatrixX3d& vertices,
                            const std::string& source, const std::string& where) {
  if (end.is_array() && end.size() == 3 && end[0].is_number() && end[1].is_number() && end[2].is_number())
    return Eigen::Vector3d(end[0].get<double>(), end[1].get<double>(), end[2].get<double>());
  if (!end.is_string()) fail(source, where + " must name a joint");
  const std::string name = end.get<std::string>();
  auto joint = joints.find(name);
  if (joint == joints.end()) fail(source, where + " names unknown joint '" + name + "'");
  if (!joint->is_array() || joint->empty()) fail(source, "joint '" + name + "' must list vertex indices");
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Json& v : *joint) {
    const long long i = v.is_number_integer() ? v.get<long long>() : -1;
    if (i < 0 || i >= vertices.rows())
      fail(source, "joint '" + name + "': vertex " + v.dump() + " is not in the base mesh (" +
                       std::to_string(vertices.rows()) + " vertices)");
    sum += vertices.row(Eigen::Index(i)).transpose();
  }
  return sum / double(joint->size());
}

std::vector<Bone> readBones(const Json& doc, const Eigen::MatrixX3d& vertices, const std::string& source) {
  const Json& bones = objectMember(doc, "bones", source);
  const Json& joints = objectMember(doc, "joints", source);
  std::vector<Bone> result;
  for (auto it = bones.begin(); it != bones.end(); ++it) {
    const std::string where = "bone '" + it.key() + "'";
    if (!it->is_object()) fail(source, where + " must be an object");
    const Json parent = it->value("parent", Json());
    if (!parent.is_null() && !parent.is_string()) fail(source, where + ": parent must be a bone name or null");
    Bone b{it.key(), parent.is_null() ? "" : parent.get<std::string>(), {}, {}};
    b.head = endPosition(joints, it->value("head", Json()), vertices, source, where + " head");
    b.tail = endPosition(joints, it->value("tail", Json()), vertices, source, where + " tail");
    result.push_back(std::move(b));
  }
  return result;
}

// Depth-first from the roots, children in file order, so parents come before children.
std::vector<int> depthFirstOrder(const std::vector<Bone>& bones, const std::string& source) {
  std::map<std::string, int> index;
  for (std::size_t i = 0; i < bones.size(); ++i) index[bones[i].name] = int(i);
  std::vector<std::vector<int>> children(bones.size());
  std::vector<int> stack;
  for (std::size_t i = 0; i < bones.size(); ++i) {
    if (bones[i].parent.empty()) continue;
    auto p = index.find(bones[i].parent);
    if (p == index.end()) fail(source, "bone '" + bones[i].name + "' has unknown parent '" + bones[i].parent + "'");
    children[std::size_t(p->second)].push_back(int(i));
  }
  for (std::size_t i = bones.size(); i-- > 0;)
    if (bones[i].parent.empty()) stack.push_back(int(i));
  std::vector<int> order;
  while (!stack.empty()) {
    const int b = stack.back();
    stack.pop_back();
    order.push_back(b);
    for (auto c = children[std::size_t(b)].rbegin(); c != children[std::size_t(b)].rend(); ++c) stack.push_back(*c);
  }
  if (order.size() != bones.size()) fail(source, "the bones' parents form a cycle");
  return order;
}

}  // namespace

Skeleton parseMakeHumanSkeleton(std::string_view text, const std::string& source,
                                const Eigen::MatrixX3d& baseVertices) {
  const Json doc = parseJson(text, source);
  const std::vector<Bone> bones = readBones(doc, baseVertices, source);
  const std::vector<int> order = depthFirstOrder(bones, source);
  std::map<std::string, int> jointOf;  // bone name -> index in the skeleton
  Skeleton skeleton;
  for (int b : order) {
    const Bone& bone = bones[std::size_t(b)];
    Joint j;
    j.name = bone.name;
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    if (!bone.parent.empty()) {
      j.parent = jointOf.at(bone.parent);
      origin = bones[std::size_t(order[std::size_t(j.parent)])].head;
    }
    j.restLocal.translation() = bone.head - origin;
    j.tail = bone.tail - bone.head;
    jointOf[bone.name] = int(skeleton.joints.size());
    skeleton.joints.push_back(std::move(j));
  }
  skeleton.validate(source);
  return skeleton;
}

Skeleton readMakeHumanSkeleton(const std::string& mhskelPath, const Eigen::MatrixX3d& baseVertices) {
  return parseMakeHumanSkeleton(readTextFile(mhskelPath), mhskelPath, baseVertices);
}

namespace {

void addBoneWeights(const Json& list, int joint, int vertexCount, const std::string& where, const std::string& source,
                    std::vector<Eigen::Triplet<double>>& triplets) {
  if (!list.is_array()) fail(source, where + " must be a list of [vertex, weight]");
  for (const Json& pair : list) {
    if (!pair.is_array() || pair.size() != 2 || !pair[0].is_number_integer() || !pair[1].is_number())
      fail(source, where + ": " + pair.dump() + " is not [vertex, weight]");
    const long long v = pair[0].get<long long>();
    const double w = pair[1].get<double>();
    if (v < 0 || v >= vertexCount)
      fail(source, where + ": vertex " + std::to_string(v) + " is not in the mesh (" + std::to_string(vertexCount) +
                       " vertices)");
    if (!std::isfinite(w) || w < 0) fail(source, where + ": weight " + pair[1].dump() + " is not >= 0");
    if (w > 0) triplets.emplace_back(int(v), joint, w);
  }
}

}  // namespace

SkinWeights parseMakeHumanWeights(std::string_view text, const std::string& source, const Skeleton& skeleton,
                                  int vertexCount) {
  if (vertexCount < 0) throw UsageError("parseMakeHumanWeights: negative vertex count");
  const Json doc = parseJson(text, source);
  const Json& weights = objectMember(doc, "weights", source);
  std::vector<Eigen::Triplet<double>> triplets;
  for (auto it = weights.begin(); it != weights.end(); ++it) {
    const int joint = skeleton.find(it.key());
    if (joint < 0) fail(source, "weights for bone '" + it.key() + "', which the skeleton does not have");
    addBoneWeights(*it, joint, vertexCount, "bone '" + it.key() + "'", source, triplets);
  }
  SkinWeights w(vertexCount, Eigen::Index(skeleton.joints.size()));
  w.setFromTriplets(triplets.begin(), triplets.end());  // sums repeated (vertex, bone) pairs
  for (Eigen::Index r = 0; r < w.outerSize(); ++r) {
    double sum = 0;
    for (SkinWeights::InnerIterator it(w, r); it; ++it) sum += it.value();
    if (sum > 0)
      for (SkinWeights::InnerIterator it(w, r); it; ++it) it.valueRef() /= sum;
  }
  return w;
}

SkinWeights readMakeHumanWeights(const std::string& mhwPath, const Skeleton& skeleton, int vertexCount) {
  return parseMakeHumanWeights(readTextFile(mhwPath), mhwPath, skeleton, vertexCount);
}

bool isMakeHumanBody(const TriMesh& base, const TriMesh& body) {
  return body.V.rows() > 0 && body.V.rows() <= base.V.rows() && body.F.rows() > 0 && body.F.rows() <= base.F.rows() &&
         body.F == base.F.topRows(body.F.rows()) && body.F.maxCoeff() < body.V.rows() &&
         (body.V.rows() == base.V.rows() || base.F.bottomRows(base.F.rows() - body.F.rows()).minCoeff() >= body.V.rows());
}

Skeleton readMakeHumanSkeletonOfBody(const std::string& mhskelPath, const TriMesh& base, const TriMesh& body) {
  const std::string text = readTextFile(mhskelPath);
  if (!isMakeHumanBody(base, body) || body.V.rows() == base.V.rows())
    return parseMakeHumanSkeleton(text, mhskelPath, isMakeHumanBody(base, body) ? body.V : base.V);
  // Only the helper vertices that joints name are carried (about 1,000 of base.obj's 5,778 helpers).
  std::vector<Eigen::Index> carried;
  const Json doc = parseJson(text, mhskelPath);
  for (const auto& [name, vertices] : objectMember(doc, "joints", mhskelPath).items())
    if (vertices.is_array())
      for (const Json& v : vertices)
        if (v.is_number_integer() && v.get<long long>() >= body.V.rows() && v.get<long long>() < base.V.rows())
          carried.push_back(Eigen::Index(v.get<long long>()));
  std::sort(carried.begin(), carried.end());
  carried.erase(std::unique(carried.begin(), carried.end()), carried.end());
  TriMesh cage;
  cage.V = base.V.topRows(body.V.rows());
  cage.F = body.F;
  MatrixX3d points(Eigen::Index(carried.size()), 3);
  for (std::size_t i = 0; i < carried.size(); ++i) points.row(Eigen::Index(i)) = base.V.row(carried[i]);
  const Eigen::MatrixXd moved = meanValueInterpolate(cage, body.V - cage.V, points);
  Eigen::MatrixX3d vertices = base.V;
  vertices.topRows(body.V.rows()) = body.V;
  for (std::size_t i = 0; i < carried.size(); ++i) vertices.row(carried[i]) += moved.row(Eigen::Index(i));
  return parseMakeHumanSkeleton(text, mhskelPath, vertices);
}

MakeHumanTarget parseMakeHumanTarget(std::string_view text, const std::string& source) {
  std::vector<int> vertex;
  std::vector<Eigen::Vector3d> offset;
  std::size_t start = 0;
  for (long line = 1; start < text.size(); ++line) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string row(text.substr(start, end - start));
    start = end + 1;
    if (const std::size_t hash = row.find('#'); hash != std::string::npos) row.resize(hash);
    if (row.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::istringstream in(row);
    long long index = -1;
    Eigen::Vector3d d;
    std::string rest;
    if (!(in >> index >> d.x() >> d.y() >> d.z()) || (in >> rest) || index < 0 || index > 100'000'000 || !d.allFinite())
      fail(source, "line " + std::to_string(line) + ": expected a vertex index and three finite offsets");
    vertex.push_back(int(index));
    offset.push_back(d);
  }
  MakeHumanTarget t;
  t.vertex = Eigen::Map<const Eigen::VectorXi>(vertex.data(), Eigen::Index(vertex.size()));
  t.offset.resize(Eigen::Index(offset.size()), 3);
  for (std::size_t i = 0; i < offset.size(); ++i) t.offset.row(Eigen::Index(i)) = offset[i].transpose();
  return t;
}

MakeHumanTarget readMakeHumanTarget(const std::string& path) { return parseMakeHumanTarget(readTextFile(path), path); }

TriMesh applyMakeHumanTarget(TriMesh body, const MakeHumanTarget& target, double weight) {
  for (Eigen::Index k = 0; k < target.vertex.size(); ++k)
    if (target.vertex[k] < body.V.rows()) body.V.row(target.vertex[k]) += weight * target.offset.row(k);
  return body;
}

}  // namespace vesalius::io

