// OpenSim 4 models (.osim) read with VTK's XML parser. See skeleton_io.h for what is read and how.
#include "vesalius/io/skeleton_io.h"

#include "vesalius/core/error.h"
#include "vesalius/io/marker_formats.h"
#include "vesalius/io/text_file.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkNew.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>

namespace vesalius::io {

namespace {

using Element = vtkXMLDataElement;

struct Reader {
  const std::string& source;
  std::map<std::string, int> bodyIndex;  // body name -> index in the BodySet; "ground" -> -1

  [[noreturn]] void fail(const std::string& problem) const { throw BadInput(source, printable(problem, 300)); }

  int body(const std::string& name, const std::string& where) const {
    if (name == "ground") return -1;
    auto it = bodyIndex.find(name);
    if (it == bodyIndex.end()) fail(where + ": unknown body '" + name + "'");
    return it->second;
  }
};

Element* child(Element* e, const char* name) { return e ? e->FindNestedElementWithName(name) : nullptr; }

std::vector<Element*> children(Element* e) {
  std::vector<Element*> out;
  for (int i = 0; e && i < e->GetNumberOfNestedElements(); ++i) out.push_back(e->GetNestedElement(i));
  return out;
}

std::string nameOf(Element* e) {
  const char* n = e->GetAttribute("name");
  return n ? n : "";
}

std::string textOf(Element* e) {
  const char* t = e ? e->GetCharacterData() : nullptr;
  return t ? std::string(trim(t)) : std::string();
}

// "/bodyset/femur_r", "../femur_r" or "femur_r" -> "femur_r".
std::string lastComponent(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::vector<double> numbersOf(Element* e, const Reader& r, const std::string& where) {
  std::vector<double> values;
  const std::string text = textOf(e);
  const char* p = text.c_str();
  while (*p) {
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end == p || !std::isfinite(v)) r.fail(where + ": '" + text + "' is not a list of finite numbers");
    values.push_back(v);
    p = end;
    while (std::isspace(static_cast<unsigned char>(*p))) ++p;
  }
  return values;
}

Eigen::Vector3d vectorOf(Element* parent, const char* name, const Eigen::Vector3d& fallback, const Reader& r,
                         const std::string& where) {
  Element* e = child(parent, name);
  if (!e) return fallback;
  const std::vector<double> v = numbersOf(e, r, where + " " + name);
  if (v.size() != 3) r.fail(where + ": " + name + " must hold 3 numbers");
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

// The cubic spline through (xs, ys) at x; s below is a sixth of the second derivative at each knot, from
// the usual tridiagonal system. End conditions: natural (zero curvature) or, for SimmSpline, Forsythe-Malcolm-Moler's (third
// derivatives matched to cubics through the end points, exact for cubic data). Linear beyond the knots.
double cubicSpline(const std::vector<double>& xs, const std::vector<double>& ys, double x, bool natural) {
  const std::size_t n = xs.size();
  std::vector<double> h(n - 1), delta(n - 1), sub(n, 0.0), diag(n, 1.0), sup(n, 0.0), rhs(n, 0.0);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    h[i] = xs[i + 1] - xs[i];
    delta[i] = (ys[i + 1] - ys[i]) / h[i];
  }
  for (std::size_t i = 1; i + 1 < n; ++i) {
    sub[i] = h[i - 1];
    diag[i] = 2 * (h[i - 1] + h[i]);
    sup[i] = h[i];
    rhs[i] = delta[i] - delta[i - 1];
  }
  if (!natural) {  // rows -h s0 + h s1 = ... and h s[n-2] - h s[n-1] = ..., zero for 3 knots
    diag[0] = -h[0];
    sup[0] = h[0];
    sub[n - 1] = h[n - 2];
    diag[n - 1] = -h[n - 2];
  }
  if (!natural && n > 3) {
    const double d0 = (delta[1] - delta[0]) / (xs[2] - xs[0]), d1 = (delta[2] - delta[1]) / (xs[3] - xs[1]);
    const double e0 = (delta[n - 2] - delta[n - 3]) / (xs[n - 1] - xs[n - 3]);
    const double e1 = (delta[n - 3] - delta[n - 4]) / (xs[n - 2] - xs[n - 4]);
    rhs[0] = h[0] * h[0] * (d1 - d0) / (xs[3] - xs[0]);
    rhs[n - 1] = -h[n - 2] * h[n - 2] * (e0 - e1) / (xs[n - 1] - xs[n - 4]);
  }
  for (std::size_t i = 1; i < n; ++i) {  // Thomas algorithm
    const double t = sub[i] / diag[i - 1];
    diag[i] -= t * sup[i - 1];
    rhs[i] -= t * rhs[i - 1];
  }
  std::vector<double> s(n);
  s[n - 1] = rhs[n - 1] / diag[n - 1];
  for (std::size_t i = n - 1; i-- > 0;) s[i] = (rhs[i] - sup[i] * s[i + 1]) / diag[i];
  auto slope = [&](std::size_t i) { return delta[i] - h[i] * (s[i + 1] + 2 * s[i]); };
  if (x <= xs[0]) return ys[0] + (x - xs[0]) * slope(0);
  if (x >= xs[n - 1]) return ys[n - 1] + (x - xs[n - 1]) * (delta[n - 2] + h[n - 2] * (s[n - 2] + 2 * s[n - 1]));
  std::size_t i = 0;
  while (x > xs[i + 1]) ++i;
  const double t = x - xs[i];
  return ys[i] + t * (slope(i) + t * (3 * s[i] + t * (s[i + 1] - s[i]) / h[i]));
}

double piecewiseLinear(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  std::size_t i = 0;
  while (i + 2 < xs.size() && x > xs[i + 1]) ++i;
  return ys[i] + (x - xs[i]) * (ys[i + 1] - ys[i]) / (xs[i + 1] - xs[i]);
}

double evaluate(Element* f, double x, const Reader& r, const std::string& where);

double evaluateKnots(Element* f, const std::string& type, double x, const Reader& r, const std::string& where) {
  const std::vector<double> xs = numbersOf(child(f, "x"), r, where + " x"),
                            ys = numbersOf(child(f, "y"), r, where + " y");
  if (xs.size() != ys.size() || xs.size() < 2) r.fail(where + ": " + type + " needs as many x as y, at least 2");
  for (std::size_t i = 0; i + 1 < xs.size(); ++i)
    if (!(xs[i] < xs[i + 1])) r.fail(where + ": " + type + " x values must increase");
  if (type == "PiecewiseLinearFunction" || xs.size() == 2) return piecewiseLinear(xs, ys, x);
  return cubicSpline(xs, ys, x, type == "NaturalCubicSpline");
}

double evaluate(Element* f, double x, const Reader& r, const std::string& where) {
  if (!f) r.fail(where + ": no function");
  const std::string type = f->GetName();
  if (type == "Constant") {
    const std::vector<double> v = numbersOf(child(f, "value"), r, where + " value");
    if (v.size() != 1) r.fail(where + ": Constant needs one value");
    return v[0];
  }
  if (type == "LinearFunction" || type == "PolynomialFunction") {
    const std::vector<double> c = numbersOf(child(f, "coefficients"), r, where + " coefficients");
    if (c.empty() || (type == "LinearFunction" && c.size() != 2)) r.fail(where + ": bad " + type + " coefficients");
    double value = 0;
    for (double coefficient : c) value = value * x + coefficient;  // highest power first
    return value;
  }
  if (type == "PiecewiseLinearFunction" || type == "SimmSpline" || type == "NaturalCubicSpline")
    return evaluateKnots(f, type, x, r, where);
  if (type == "MultiplierFunction") {
    std::vector<Element*> inner = children(child(f, "function"));
    const std::vector<double> scale = numbersOf(child(f, "scale"), r, where + " scale");
    if (inner.size() != 1 || scale.size() > 1) r.fail(where + ": MultiplierFunction needs one function and a scale");
    return (scale.empty() ? 1.0 : scale[0]) * evaluate(inner[0], x, r, where);
  }
  r.fail(where + ": unsupported function " + type);
}

// The function element of a TransformAxis or MovingPathPoint property: the nested element named `name`.
Element* functionNamed(Element* owner, const char* name) {
  for (Element* e : children(owner))
    if (nameOf(e) == name) return e;
  return nullptr;
}

Eigen::Isometry3d offsetTransform(Element* frame, const Reader& r, const std::string& where) {
  const Eigen::Vector3d t = vectorOf(frame, "translation", Eigen::Vector3d::Zero(), r, where);
  const Eigen::Vector3d a = vectorOf(frame, "orientation", Eigen::Vector3d::Zero(), r, where);
  Eigen::Isometry3d x = Eigen::Isometry3d::Identity();
  x.translation() = t;
  // Body-fixed X-Y-Z Euler angles, OpenSim's convention for frame orientations.
  x.linear() = (Eigen::AngleAxisd(a.x(), Eigen::Vector3d::UnitX()) *
                Eigen::AngleAxisd(a.y(), Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(a.z(), Eigen::Vector3d::UnitZ()))
                   .toRotationMatrix();
  return x;
}

struct FrameRef {
  int body = -1;
  Eigen::Isometry3d inBody = Eigen::Isometry3d::Identity();
};

// A joint socket names one of the joint's own PhysicalOffsetFrames or, directly, a body or ground.
FrameRef resolveFrame(Element* joint, const std::string& socket, const Reader& r, const std::string& where) {
  Element* reference = child(joint, socket.c_str());
  if (!reference) reference = child(joint, (socket + "_connectee_name").c_str());
  const std::string name = textOf(reference);
  if (name.empty()) r.fail(where + ": no " + socket);
  for (Element* frame : children(child(joint, "frames"))) {
    if (nameOf(frame) != lastComponent(name)) continue;
    if (std::string(frame->GetName()) != "PhysicalOffsetFrame")
      r.fail(where + ": frame '" + name + "' is a " + frame->GetName() + ", not a PhysicalOffsetFrame");
    const std::string parent = lastComponent(textOf(child(frame, "socket_parent")));
    return {r.body(parent, where + " frame " + name), offsetTransform(frame, r, where + " frame " + name)};
  }
  return {r.body(lastComponent(name), where), Eigen::Isometry3d::Identity()};
}

// A CustomJoint's mobilizer transform with every coordinate 0; the identity for other joint types.
Eigen::Isometry3d jointAtZero(Element* joint, const Reader& r, const std::string& where) {
  Eigen::Isometry3d x = Eigen::Isometry3d::Identity();
  Element* spatial = child(joint, "SpatialTransform");
  const char* const axes[] = {"rotation1", "rotation2", "rotation3", "translation1", "translation2", "translation3"};
  for (int i = 0; spatial && i < 6; ++i) {
    Element* axisElement = functionNamed(spatial, axes[i]);
    if (!axisElement) continue;
    const std::string at = where + " " + axes[i];
    const Eigen::Vector3d axis = vectorOf(axisElement, "axis", Eigen::Vector3d::Zero(), r, at);
    if (axis.norm() == 0) r.fail(at + ": no axis");
    const double value = evaluate(functionNamed(axisElement, "function"), 0.0, r, at);
    if (i < 3)
      x.linear() = x.linear() * Eigen::AngleAxisd(value, axis.normalized()).toRotationMatrix();
    else
      x.translation() += value * axis.normalized();
  }
  return x;
}

struct BodyLink {
  int parent = -2;  // -2: no joint yet
  Eigen::Isometry3d restLocal = Eigen::Isometry3d::Identity();
};

void readJoint(Element* joint, const Reader& r, std::vector<BodyLink>& links) {
  const std::string where = std::string(joint->GetName()) + " '" + nameOf(joint) + "'";
  const FrameRef parent = resolveFrame(joint, "socket_parent_frame", r, where);
  const FrameRef child = resolveFrame(joint, "socket_child_frame", r, where);
  if (child.body < 0) r.fail(where + ": its child frame is on ground");
  BodyLink& link = links[std::size_t(child.body)];
  if (link.parent != -2) r.fail(where + ": body already has a joint (closed loops are not supported)");
  link.parent = parent.body;
  link.restLocal = parent.inBody * jointAtZero(joint, r, where) * child.inBody.inverse();
}

Element* modelSet(Element* model, const char* set, const Reader& r) {
  Element* e = child(child(model, set), "objects");
  if (!e) r.fail(std::string("no ") + set + " with objects");
  return e;
}

void readGeometry(Element* frame, int body, const Reader& r, MusculoskeletalModel& model) {
  for (Element* g : children(child(frame, "attached_geometry"))) {
    if (std::string(g->GetName()) != "Mesh") continue;
    const std::string where = "mesh '" + nameOf(g) + "'";
    const std::string socket = textOf(child(g, "socket_frame"));
    if (!socket.empty() && socket != "..") r.fail(where + ": attached to frame '" + socket + "', not to its body");
    const std::string file = textOf(child(g, "mesh_file"));
    if (file.empty()) r.fail(where + ": no mesh_file");
    model.geometry.push_back({body, file, vectorOf(g, "scale_factors", Eigen::Vector3d::Ones(), r, where)});
  }
}

// Bodies in depth-first order from ground so that parents come before children.
void orderBodies(const std::vector<std::string>& names, const std::vector<BodyLink>& links, const Reader& r,
                 MusculoskeletalModel& model, std::vector<int>& newIndex) {
  for (std::size_t b = 0; b < names.size(); ++b)
    if (links[b].parent == -2) r.fail("body '" + names[b] + "' has no joint");
  newIndex.assign(names.size(), -1);
  std::vector<int> stack;
  for (std::size_t b = names.size(); b-- > 0;)
    if (links[b].parent == -1) stack.push_back(int(b));
  while (!stack.empty()) {
    const int b = stack.back();
    stack.pop_back();
    newIndex[std::size_t(b)] = int(model.bodies.joints.size());
    const int parent = links[std::size_t(b)].parent;
    model.bodies.joints.push_back({names[std::size_t(b)], parent < 0 ? -1 : newIndex[std::size_t(parent)],
                                   links[std::size_t(b)].restLocal, Eigen::Vector3d::Zero()});
    for (std::size_t c = names.size(); c-- > 0;)
      if (links[c].parent == b) stack.push_back(int(c));
  }
  if (model.bodies.joints.size() != names.size()) r.fail("the joints form a loop that does not reach ground");
}

PathPoint readPathPoint(Element* p, const Reader& r, const std::string& where) {
  const std::string type = p->GetName();
  if (type != "PathPoint" && type != "ConditionalPathPoint" && type != "MovingPathPoint")
    r.fail(where + ": unsupported path point type " + type);
  PathPoint point;
  point.name = nameOf(p);
  point.body = r.body(lastComponent(textOf(child(p, "socket_parent_frame"))), where);
  if (type != "MovingPathPoint") {
    point.location = vectorOf(p, "location", Eigen::Vector3d::Zero(), r, where);
    return point;
  }
  const char* const locations[] = {"x_location", "y_location", "z_location"};
  for (int i = 0; i < 3; ++i)
    if (Element* f = functionNamed(p, locations[i]))
      point.location[i] = evaluate(f, 0.0, r, where + " " + locations[i]);
  return point;
}

void readMuscles(Element* model, const Reader& r, const std::vector<int>& newIndex, MusculoskeletalModel& out) {
  for (Element* force : children(modelSet(model, "ForceSet", r))) {
    const std::string type = force->GetName();
    if (type.size() < 6 || type.compare(type.size() - 6, 6, "Muscle") != 0) continue;
    Muscle muscle;
    muscle.name = nameOf(force);
    Element* points = child(child(child(force, "GeometryPath"), "PathPointSet"), "objects");
    for (Element* p : children(points)) {
      PathPoint point = readPathPoint(p, r, "muscle '" + muscle.name + "' point '" + nameOf(p) + "'");
      if (point.body >= 0) point.body = newIndex[std::size_t(point.body)];
      muscle.path.push_back(std::move(point));
    }
    out.muscles.push_back(std::move(muscle));
  }
}

MusculoskeletalModel readModel(Element* root, Reader& r) {
  if (!root || std::string(root->GetName()) != "OpenSimDocument") r.fail("not an OpenSim model (no <OpenSimDocument>)");
  const char* version = root->GetAttribute("Version");
  if (!version || std::atoi(version) < 40000)
    r.fail("OpenSim 3 model (document version " + std::string(version ? version : "?") +
           "); open and save it in OpenSim 4 first");
  Element* model = child(root, "Model");
  if (!model) r.fail("no <Model>");
  std::vector<std::string> names;
  for (Element* body : children(modelSet(model, "BodySet", r))) {
    if (r.bodyIndex.count(nameOf(body)) || nameOf(body) == "ground") r.fail("two bodies named '" + nameOf(body) + "'");
    r.bodyIndex[nameOf(body)] = int(names.size());
    names.push_back(nameOf(body));
  }
  std::vector<BodyLink> links(names.size());
  for (Element* joint : children(modelSet(model, "JointSet", r))) readJoint(joint, r, links);
  MusculoskeletalModel out;
  out.name = nameOf(model);
  std::vector<int> newIndex;
  orderBodies(names, links, r, out, newIndex);
  readGeometry(child(model, "Ground"), -1, r, out);
  std::vector<Element*> bodies = children(modelSet(model, "BodySet", r));
  for (std::size_t b = 0; b < bodies.size(); ++b) readGeometry(bodies[b], newIndex[b], r, out);
  readMuscles(model, r, newIndex, out);
  return out;
}

void keepMessage(vtkObject*, unsigned long, void* clientData, void* callData) {
  auto* message = static_cast<std::string*>(clientData);
  if (message->empty() && callData) *message = static_cast<const char*>(callData);
}

// VTK's message is "ERROR: In <file>, line N\nvtkXMLDataParser (0x...): Error parsing XML ...\n\n".
std::string xmlProblem(const std::string& message) {
  std::size_t start = message.find("): ");
  start = start == std::string::npos ? 0 : start + 3;
  return message.substr(start, message.find('\n', start) - start);
}

}  // namespace

MusculoskeletalModel readOpenSimModel(const std::string& osimPath) {
  if (!std::ifstream(osimPath)) throw BadInput(osimPath, std::string("cannot open: ") + std::strerror(errno));
  std::string vtkMessage;
  vtkNew<vtkCallbackCommand> observer;
  observer->SetCallback(keepMessage);
  observer->SetClientData(&vtkMessage);
  vtkNew<vtkXMLDataParser> parser;
  parser->AddObserver(vtkCommand::ErrorEvent, observer);
  parser->AddObserver(vtkCommand::WarningEvent, observer);
  parser->SetFileName(osimPath.c_str());
  parser->SetIgnoreCharacterData(0);
  if (!parser->Parse()) throw BadInput(osimPath, "invalid XML: " + xmlProblem(vtkMessage));
  Reader reader{osimPath, {}};
  MusculoskeletalModel model = readModel(parser->GetRootElement(), reader);
  model.bodies.validate(osimPath);
  return model;
}

}  // namespace vesalius::io
