// 3D Slicer markups JSON (.mrk.json): see marker_formats.h for what is read and written, and Slicer's
// vtkMRMLMarkupsJsonStorageNode for the behaviour we follow (schema check, defaults, "position": "").
#include "vesalius/io/marker_formats.h"

#include "vesalius/core/error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace vesalius::io {

namespace {

using Json = nlohmann::json;
using OrderedJson = nlohmann::ordered_json;

constexpr const char* kSchema =
    "https://raw.githubusercontent.com/slicer/slicer/master/Modules/Loadable/Markups/Resources/Schema/"
    "markups-schema-v1.0.3.json#";

// Where a markup's numbers go: LPS millimetres.
struct Conversion {
  double xySign = 1.0;  // -1 for RAS
  double scale = 1.0;   // 1e-3 for micrometres
};

struct Context {
  const std::string& source;
  std::string where;  // "markup 2 control point 5", for messages

  [[noreturn]] void fail(const std::string& problem) const {
    throw BadInput(source, printable(where.empty() ? problem : where + ": " + problem, 300));
  }
};

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

bool readDigits(const std::string& s, std::size_t& pos) {
  std::size_t start = pos;
  while (pos < s.size() && std::isdigit(static_cast<unsigned char>(s[pos]))) ++pos;
  return pos > start;
}

// Slicer accepts "...markups-schema-v1.<minor>.<patch>.json" with any minor and patch.
bool isMarkupsSchemaV1(const std::string& schema) {
  const std::string s = lower(schema);
  const std::string stem = "markups-schema-v1.";
  for (std::size_t at = s.find(stem); at != std::string::npos; at = s.find(stem, at + 1)) {
    std::size_t pos = at + stem.size();
    if (readDigits(s, pos) && pos < s.size() && s[pos] == '.' && readDigits(s, ++pos) &&
        s.compare(pos, 5, ".json") == 0)
      return true;
  }
  return false;
}

const Json* member(const Json& object, const char* key) {
  auto it = object.find(key);
  return it == object.end() || it->is_null() ? nullptr : &*it;
}

std::string stringMember(const Json& object, const char* key, const Context& ctx) {
  const Json* v = member(object, key);
  if (!v) return {};
  if (!v->is_string()) ctx.fail(std::string("\"") + key + "\" must be a string");
  return v->get<std::string>();
}

bool boolMember(const Json& object, const char* key, bool fallback, const Context& ctx) {
  const Json* v = member(object, key);
  if (!v) return fallback;
  if (!v->is_boolean()) ctx.fail(std::string("\"") + key + "\" must be true or false");
  return v->get<bool>();
}

Eigen::Vector3d vectorValue(const Json& v, const char* what, const Conversion& c, const Context& ctx) {
  if (!v.is_array() || v.size() != 3) ctx.fail(std::string(what) + " must be an array of 3 numbers");
  Eigen::Vector3d p;
  for (int i = 0; i < 3; ++i) {
    if (!v[i].is_number()) ctx.fail(std::string(what) + " must be an array of 3 numbers");
    p[i] = v[i].get<double>();
    if (!std::isfinite(p[i])) ctx.fail(std::string(what) + " is not finite");
  }
  return Eigen::Vector3d(c.xySign * p.x(), c.xySign * p.y(), p.z()) * c.scale;
}

MarkerStatus statusMember(const Json& point, const Context& ctx) {
  const std::string s = stringMember(point, "positionStatus", ctx);
  if (s.empty() || s == "defined") return MarkerStatus::Defined;
  if (s == "undefined") return MarkerStatus::Undefined;
  if (s == "preview") return MarkerStatus::Preview;
  if (s == "missing") return MarkerStatus::Missing;
  ctx.fail("unknown positionStatus '" + s + "' (defined, undefined, preview or missing)");
}

Marker readControlPoint(const Json& point, MarkerKind kind, const Conversion& c, const Context& ctx) {
  if (!point.is_object()) ctx.fail("a control point must be an object");
  Marker m;
  m.kind = kind;
  m.label = stringMember(point, "label", ctx);
  m.description = stringMember(point, "description", ctx);
  m.id = stringMember(point, "id", ctx);
  m.associatedNodeID = stringMember(point, "associatedNodeID", ctx);
  m.status = statusMember(point, ctx);
  const Json* position = member(point, "position");
  // Slicer writes "position": "" for a point without a position and reads a missing one as undefined.
  if (position && !(position->is_string() && position->get<std::string>().empty()))
    m.position = vectorValue(*position, "position", c, ctx);
  else if (m.status == MarkerStatus::Defined)
    m.status = MarkerStatus::Undefined;
  if (const Json* extra = member(point, "vesalius")) {
    if (!extra->is_object()) ctx.fail("\"vesalius\" must be an object");
    if (const Json* t = member(*extra, "templatePosition"))
      m.templatePosition = vectorValue(*t, "templatePosition", c, ctx);
    if (const Json* color = member(*extra, "color")) {
      m.color = vectorValue(*color, "color", Conversion{}, ctx);
      if (!(m.color->array() >= 0.0 && m.color->array() <= 1.0).all()) ctx.fail("color must lie in [0, 1]");
    }
    if (const Json* tags = member(*extra, "tags")) {
      if (!tags->is_array()) ctx.fail("\"tags\" must be an array of strings");
      for (const Json& tag : *tags) {
        if (!tag.is_string()) ctx.fail("\"tags\" must be an array of strings");
        m.tags.push_back(tag.get<std::string>());
      }
    }
  }
  m.selected = boolMember(point, "selected", true, ctx);
  m.locked = boolMember(point, "locked", false, ctx);
  m.visible = boolMember(point, "visibility", true, ctx);
  return m;
}

std::string pluralKindName(MarkerKind k) {
  const std::string singular = markerKindName(k);
  return k == MarkerKind::IcpMarker ? singular : singular + "s";
}

std::optional<MarkerKind> kindFromMarkupName(const std::string& name) {
  for (MarkerKind k : {MarkerKind::Landmark, MarkerKind::IcpMarker, MarkerKind::Attachment})
    if (name == markerKindName(k) || name == pluralKindName(k)) return k;
  return std::nullopt;
}

// A markup name says the kind ("icp"), the set's name ("liver"), or both ("liver (icp)").
struct MarkupName {
  std::string setName;
  std::optional<MarkerKind> kind;
};

MarkupName splitMarkupName(const std::string& name) {
  if (auto kind = kindFromMarkupName(name)) return {"", kind};
  const std::size_t open = name.rfind(" (");
  if (open != std::string::npos && open > 0 && name.back() == ')')
    if (auto kind = kindFromMarkupName(name.substr(open + 2, name.size() - open - 3)))
      return {name.substr(0, open), kind};
  return {name, std::nullopt};
}

Conversion markupConversion(const Json& markup, const Context& ctx) {
  Conversion c;
  const std::string system = stringMember(markup, "coordinateSystem", ctx);
  if (system == "RAS")
    c.xySign = -1.0;
  else if (!system.empty() && system != "LPS")
    ctx.fail("coordinateSystem must be LPS or RAS, not '" + system + "'");
  const Json* units = member(markup, "coordinateUnits");
  // Either a plain unit or a coded entry [code value, coding scheme, meaning].
  if (units && units->is_array() && !units->empty()) units = &(*units)[0];
  if (!units) return c;
  const std::string unit = units->is_string() ? units->get<std::string>() : std::string("?");
  if (unit == "um")
    c.scale = 1e-3;
  else if (unit != "mm")
    ctx.fail("coordinateUnits must be mm or um");
  return c;
}

void readMarkup(const Json& markup, MarkerKind defaultKind, MarkerSet& set, Context ctx) {
  if (!markup.is_object()) ctx.fail("a markup must be an object");
  const std::string type = stringMember(markup, "type", ctx);
  if (type != "Fiducial") ctx.fail("markup type '" + type + "' holds no markers (only Fiducial point lists do)");
  const MarkupName name = splitMarkupName(stringMember(markup, "name", ctx));
  const MarkerKind kind = name.kind.value_or(defaultKind);
  if (set.name.empty()) set.name = name.setName;
  const Conversion conversion = markupConversion(markup, ctx);
  const Json* points = member(markup, "controlPoints");
  if (!points) return;
  if (!points->is_array()) ctx.fail("\"controlPoints\" must be an array");
  const std::string markupWhere = ctx.where;
  for (std::size_t i = 0; i < points->size(); ++i) {
    ctx.where = markupWhere + " control point " + std::to_string(i + 1);
    set.markers.push_back(readControlPoint((*points)[i], kind, conversion, ctx));
  }
}

void checkSchema(const Json& doc, const Context& ctx) {
  if (!doc.is_object()) ctx.fail("not a markups file (the JSON is not an object)");
  const Json* schema = member(doc, "@schema");
  if (!schema || !schema->is_string())
    ctx.fail("not a markups file: no \"@schema\" (expected markups-schema-v1.x.y.json)");
  if (!isMarkupsSchemaV1(schema->get<std::string>()))
    ctx.fail("unsupported \"@schema\" '" + schema->get<std::string>() + "' (expected markups-schema-v1.x.y.json)");
}

// nlohmann's messages start with "[json.exception.parse_error.101] "; the rest is for people.
std::string jsonProblem(const char* what) {
  std::string s(what);
  std::size_t close = s.find("] ");
  return close == std::string::npos ? s : s.substr(close + 2);
}

MarkerSet parseDocument(const Json& doc, const std::string& source, MarkerKind defaultKind) {
  Context ctx{source, ""};
  checkSchema(doc, ctx);
  const Json* markups = member(doc, "markups");
  if (!markups || !markups->is_array()) ctx.fail("no \"markups\" array");
  MarkerSet set;
  for (std::size_t i = 0; i < markups->size(); ++i)
    readMarkup((*markups)[i], defaultKind, set, Context{source, "markup " + std::to_string(i + 1)});
  return set;
}

}  // namespace

MarkerSet parseSlicerMarkups(std::string_view text, const std::string& source, MarkerKind defaultKind) {
  Json doc;
  try {
    doc = Json::parse(text.begin(), text.end());
  } catch (const Json::exception& e) {
    throw BadInput(source, "invalid JSON: " + jsonProblem(e.what()));
  }
  try {
    return parseDocument(doc, source, defaultKind);
  } catch (const Json::exception& e) {
    throw BadInput(source, jsonProblem(e.what()));
  }
}

// ---- writing ----

namespace {

OrderedJson lpsArray(const Eigen::Vector3d& p) { return OrderedJson::array({p.x(), p.y(), p.z()}); }

OrderedJson controlPoint(const Marker& m, const std::string& id) {
  OrderedJson p;
  p["id"] = id;
  p["label"] = m.label;
  p["description"] = m.description;
  p["associatedNodeID"] = m.associatedNodeID;
  // Slicer writes "" for every point that is not defined; a preview point keeps its position here
  // (a suggestion is a proposed position, and Slicer reads a position of any status).
  if (hasPosition(m.status))
    p["position"] = lpsArray(m.position);
  else
    p["position"] = "";
  // The identity orientation of RAS written in LPS, as Slicer writes it.
  p["orientation"] = OrderedJson::array({-1.0, -0.0, -0.0, -0.0, -1.0, -0.0, 0.0, 0.0, 1.0});
  p["selected"] = m.selected;
  p["locked"] = m.locked;
  p["visibility"] = m.visible;
  p["positionStatus"] = markerStatusName(m.status);
  if (m.templatePosition) p["vesalius"]["templatePosition"] = lpsArray(*m.templatePosition);
  if (m.color) p["vesalius"]["color"] = OrderedJson::array({m.color->x(), m.color->y(), m.color->z()});
  if (!m.tags.empty()) p["vesalius"]["tags"] = m.tags;
  return p;
}

// Slicer 5's display defaults; the point colour (selectedColor) tells the kinds apart.
OrderedJson display(MarkerKind kind) {
  static const double landmark[] = {1.0, 0.5000076295109483, 0.5000076295109483};
  static const double icp[] = {1.0, 0.8, 0.0};
  static const double attachment[] = {0.4, 0.6, 1.0};
  const double* rgb = kind == MarkerKind::Landmark ? landmark : kind == MarkerKind::IcpMarker ? icp : attachment;
  OrderedJson d;
  d["visibility"] = true;
  d["opacity"] = 1.0;
  d["color"] = OrderedJson::array({0.4, 1.0, 1.0});
  d["selectedColor"] = OrderedJson::array({rgb[0], rgb[1], rgb[2]});
  d["activeColor"] = OrderedJson::array({0.4, 1.0, 0.0});
  d["propertiesLabelVisibility"] = false;
  d["pointLabelsVisibility"] = true;
  d["textScale"] = 3.0;
  d["glyphType"] = "Sphere3D";
  d["glyphScale"] = 3.0;
  d["glyphSize"] = 5.0;
  d["useGlyphScale"] = true;
  d["sliceProjection"] = false;
  d["sliceProjectionUseFiducialColor"] = true;
  d["sliceProjectionOutlinedBehindSlicePlane"] = false;
  d["sliceProjectionColor"] = OrderedJson::array({1.0, 1.0, 1.0});
  d["sliceProjectionOpacity"] = 0.6;
  d["lineThickness"] = 0.2;
  d["lineColorFadingStart"] = 1.0;
  d["lineColorFadingEnd"] = 10.0;
  d["lineColorFadingSaturation"] = 1.0;
  d["lineColorFadingHueOffset"] = 0.0;
  d["handlesInteractive"] = false;
  d["translationHandleVisibility"] = true;
  d["rotationHandleVisibility"] = true;
  d["scaleHandleVisibility"] = true;
  d["interactionHandleScale"] = 3.0;
  d["snapMode"] = "toVisibleSurface";
  return d;
}

// The kind alone for an unnamed set; the set's name alone for a set of landmarks only (a Slicer point
// list read with the default kind goes back under its own name); else "name (kind)".
std::string markupName(const MarkerSet& set, MarkerKind kind, bool severalKinds) {
  if (set.name.empty()) return pluralKindName(kind);
  if (kind == MarkerKind::Landmark && !severalKinds && !splitMarkupName(set.name).kind) return set.name;
  return set.name + " (" + pluralKindName(kind) + ")";
}

OrderedJson markup(const MarkerSet& set, MarkerKind kind, bool severalKinds) {
  std::vector<const Marker*> markers;
  for (const Marker& m : set.markers)
    if (m.kind == kind) markers.push_back(&m);
  const std::vector<std::string> ids = uniqueMarkerIds(markers);
  OrderedJson points = OrderedJson::array();
  std::size_t lastNumber = markers.size();  // Slicer numbers new points' labels from here
  for (std::size_t i = 0; i < markers.size(); ++i) {
    points.push_back(controlPoint(*markers[i], ids[i]));
    if (ids[i].size() < 10 && ids[i].find_first_not_of("0123456789") == std::string::npos)
      lastNumber = std::max(lastNumber, std::size_t(std::stoul(ids[i])));
  }
  OrderedJson mk;
  mk["type"] = "Fiducial";
  mk["name"] = markupName(set, kind, severalKinds);
  mk["coordinateSystem"] = "LPS";
  mk["coordinateUnits"] = "mm";
  mk["locked"] = false;
  mk["fixedNumberOfControlPoints"] = false;
  mk["labelFormat"] = "%N-%d";
  mk["lastUsedControlPointNumber"] = lastNumber;
  mk["controlPoints"] = std::move(points);
  mk["measurements"] = OrderedJson::array();
  mk["display"] = display(kind);
  return mk;
}

std::string dumpScalar(const OrderedJson& v) {
  // Labels come from other formats and may not be UTF-8; replace bad bytes rather than fail.
  return v.dump(-1, ' ', false, OrderedJson::error_handler_t::replace);
}

// Slicer's layout: objects one member per line, arrays of numbers on one line.
void layout(const OrderedJson& v, int indent, std::string& out) {
  const std::string pad(std::size_t(indent) + 4, ' ');
  if (v.is_object() && !v.empty()) {
    out += "{\n";
    for (auto it = v.begin(); it != v.end(); ++it) {
      out += pad + dumpScalar(OrderedJson(it.key())) + ": ";
      layout(it.value(), indent + 4, out);
      out += std::next(it) == v.end() ? "\n" : ",\n";
    }
    out += std::string(std::size_t(indent), ' ') + "}";
  } else if (v.is_array() && std::any_of(v.begin(), v.end(), [](auto& e) { return e.is_structured(); })) {
    out += "[\n";
    for (auto it = v.begin(); it != v.end(); ++it) {
      out += pad;
      layout(*it, indent + 4, out);
      out += std::next(it) == v.end() ? "\n" : ",\n";
    }
    out += std::string(std::size_t(indent), ' ') + "]";
  } else if (v.is_array()) {
    out += "[";
    for (auto it = v.begin(); it != v.end(); ++it) out += (it == v.begin() ? "" : ", ") + dumpScalar(*it);
    out += "]";
  } else {
    out += dumpScalar(v);
  }
}

}  // namespace

std::string formatSlicerMarkups(const MarkerSet& set) {
  OrderedJson doc;
  doc["@schema"] = kSchema;
  doc["markups"] = OrderedJson::array();
  const MarkerKind kinds[] = {MarkerKind::Landmark, MarkerKind::IcpMarker, MarkerKind::Attachment};
  const bool severalKinds = std::count_if(std::begin(kinds), std::end(kinds), [&](MarkerKind k) { return set.count(k) > 0; }) > 1;
  for (MarkerKind k : kinds)
    if (set.count(k) > 0) doc["markups"].push_back(markup(set, k, severalKinds));
  if (doc["markups"].empty()) doc["markups"].push_back(markup(set, MarkerKind::Landmark, false));
  std::string out;
  layout(doc, 0, out);
  out += "\n";
  return out;
}

}  // namespace vesalius::io
