// A validator for the part of JSON Schema (draft-07) that 3D Slicer's markups schema uses: type, enum,
// required, properties, additionalProperties (true/false), items (one schema for every item), minItems,
// maxItems, minimum, maximum, anyOf. Annotations ($id, $schema, title, description, default, examples)
// are ignored, as is additionalItems, which has no effect when items is a single schema. A keyword
// outside this subset throws, so a schema that needs more is never validated in part.
#pragma once

#include <nlohmann/json.hpp>

#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace vesalius::test {

struct SchemaViolation {
  std::string path;     // "/markups/0/controlPoints/2/position"
  std::string problem;  // "expected array, found string"
};

class JsonSchemaSubset {
 public:
  explicit JsonSchemaSubset(nlohmann::json schema) : schema_(std::move(schema)) { checkKeywords(schema_, ""); }

  std::vector<SchemaViolation> validate(const nlohmann::json& document) const {
    std::vector<SchemaViolation> violations;
    check(schema_, document, "", violations);
    return violations;
  }

 private:
  using Json = nlohmann::json;

  static void checkKeywords(const Json& schema, const std::string& where) {
    static const std::set<std::string> known = {
        "type",     "enum",     "required", "properties", "additionalProperties", "items",   "minItems",
        "maxItems", "minimum",  "maximum",  "anyOf",      "additionalItems",      "$id",     "$schema",
        "title",    "description", "default", "examples"};
    if (!schema.is_object()) throw std::invalid_argument("schema at '" + where + "' is not an object");
    for (auto it = schema.begin(); it != schema.end(); ++it) {
      if (!known.count(it.key())) throw std::invalid_argument("unsupported keyword '" + it.key() + "' at '" + where + "'");
      if (it.key() == "additionalProperties" && !it->is_boolean())
        throw std::invalid_argument("additionalProperties other than true/false at '" + where + "'");
      if (it.key() == "additionalItems" && !it->is_boolean())
        throw std::invalid_argument("additionalItems other than true/false at '" + where + "'");
    }
    if (schema.contains("properties"))
      for (auto it = schema["properties"].begin(); it != schema["properties"].end(); ++it)
        checkKeywords(*it, where + "/properties/" + it.key());
    if (schema.contains("items")) {
      if (!schema["items"].is_object()) throw std::invalid_argument("items other than one schema at '" + where + "'");
      checkKeywords(schema["items"], where + "/items");
    }
    if (schema.contains("anyOf"))
      for (std::size_t i = 0; i < schema["anyOf"].size(); ++i)
        checkKeywords(schema["anyOf"][i], where + "/anyOf/" + std::to_string(i));
  }

  static std::string typeOf(const Json& v) {
    if (v.is_object()) return "object";
    if (v.is_array()) return "array";
    if (v.is_string()) return "string";
    if (v.is_boolean()) return "boolean";
    if (v.is_null()) return "null";
    return v.is_number_integer() || v.is_number_unsigned() ? "integer" : "number";
  }

  static bool hasType(const Json& v, const std::string& type) {
    const std::string actual = typeOf(v);
    if (type == "number") return actual == "number" || actual == "integer";
    if (type == "integer")
      return actual == "integer" || (actual == "number" && v.get<double>() == static_cast<double>(static_cast<long long>(v.get<double>())));
    return actual == type;
  }

  static void check(const Json& schema, const Json& v, const std::string& path, std::vector<SchemaViolation>& out) {
    auto fail = [&](const std::string& problem) { out.push_back({path.empty() ? "/" : path, problem}); };
    if (schema.contains("type")) {
      const Json& t = schema["type"];
      bool ok = false;
      if (t.is_string()) ok = hasType(v, t.get<std::string>());
      for (const Json& each : t.is_array() ? t : Json::array()) ok = ok || hasType(v, each.get<std::string>());
      if (!ok) {
        fail("expected " + t.dump() + ", found " + typeOf(v));
        return;  // the other keywords would only repeat the problem
      }
    }
    if (schema.contains("enum")) {
      bool found = false;
      for (const Json& e : schema["enum"]) found = found || e == v;
      if (!found) fail(v.dump() + " is not one of " + schema["enum"].dump());
    }
    if (schema.contains("anyOf")) {
      // When no option fits, the problems of the closest one (fewest violations) say why.
      std::vector<SchemaViolation> closest;
      bool any = false, first = true;
      for (const Json& option : schema["anyOf"]) {
        std::vector<SchemaViolation> trial;
        check(option, v, path, trial);
        any = any || trial.empty();
        if (first || trial.size() < closest.size()) closest = trial;
        first = false;
      }
      if (!any) out.insert(out.end(), closest.begin(), closest.end());
    }
    if (v.is_number()) {
      if (schema.contains("minimum") && v.get<double>() < schema["minimum"].get<double>())
        fail(v.dump() + " < minimum " + schema["minimum"].dump());
      if (schema.contains("maximum") && v.get<double>() > schema["maximum"].get<double>())
        fail(v.dump() + " > maximum " + schema["maximum"].dump());
    }
    if (v.is_object()) {
      for (const Json& key : schema.value("required", Json::array()))
        if (!v.contains(key.get<std::string>())) fail("required member \"" + key.get<std::string>() + "\" is absent");
      const Json properties = schema.value("properties", Json::object());
      for (auto it = v.begin(); it != v.end(); ++it) {
        if (properties.contains(it.key()))
          check(properties[it.key()], *it, path + "/" + it.key(), out);
        else if (!schema.value("additionalProperties", true))
          fail("member \"" + it.key() + "\" is not allowed");
      }
    }
    if (v.is_array()) {
      if (schema.contains("minItems") && v.size() < schema["minItems"].get<std::size_t>())
        fail(std::to_string(v.size()) + " items, fewer than " + schema["minItems"].dump());
      if (schema.contains("maxItems") && v.size() > schema["maxItems"].get<std::size_t>())
        fail(std::to_string(v.size()) + " items, more than " + schema["maxItems"].dump());
      if (schema.contains("items"))
        for (std::size_t i = 0; i < v.size(); ++i) check(schema["items"], v[i], path + "/" + std::to_string(i), out);
    }
  }

  Json schema_;
};

}  // namespace vesalius::test
