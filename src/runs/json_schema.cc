#include "runs/json_schema.h"

#include <fmt/format.h>
#include <cmath>
#include <regex>

#include "common/error.h"

namespace gearpatch::runs {
namespace {

using nlohmann::json;

constexpr int most_depth = 64;

bool is_type(const json& v, const std::string& type) {
  if (type == "object") return v.is_object();
  if (type == "array") return v.is_array();
  if (type == "string") return v.is_string();
  if (type == "number") return v.is_number();
  if (type == "integer") return v.is_number_integer() || (v.is_number_float() && v.get<double>() == std::floor(v.get<double>()));
  if (type == "boolean") return v.is_boolean();
  if (type == "null") return v.is_null();
  throw Error("schema: unknown type " + type, Error::Kind::internal);
}

struct Checker {
  std::string source;

  [[noreturn]] void fail(const std::string& where, const std::string& problem) const {
    throw Error(fmt::format("{}: {}: {}", source, where.empty() ? "/" : where, problem));
  }

  void check_type(const json& v, const json& schema, const std::string& where) const {
    if (!schema.contains("type")) return;
    const json& type = schema["type"];
    std::string names;
    for (const json& t : type.is_array() ? type : json::array({type})) {
      if (is_type(v, t.get<std::string>())) return;
      names += (names.empty() ? "" : " or ") + t.get<std::string>();
    }
    fail(where, "must be of type " + names);
  }

  void check_object(const json& v, const json& schema, const std::string& where, int depth) const {
    if (schema.contains("maxProperties") && v.size() > schema["maxProperties"].get<std::size_t>())
      fail(where, fmt::format("more than {} members", schema["maxProperties"].get<std::size_t>()));
    for (const json& name : schema.value("required", json::array()))
      if (!v.contains(name.get<std::string>())) fail(where, "lacks \"" + name.get<std::string>() + "\"");
    const json properties = schema.value("properties", json::object());
    for (const auto& [key, member] : v.items()) {
      const std::string at = where + "/" + key;
      if (properties.contains(key)) check(member, properties[key], at, depth + 1);
      else if (schema.contains("additionalProperties")) {
        const json& extra = schema["additionalProperties"];
        if (extra.is_boolean() && !extra.get<bool>()) fail(at, "not expected here");
        if (extra.is_object()) check(member, extra, at, depth + 1);
      }
    }
  }

  void check_array(const json& v, const json& schema, const std::string& where, int depth) const {
    if (schema.contains("minItems") && v.size() < schema["minItems"].get<std::size_t>())
      fail(where, fmt::format("fewer than {} items", schema["minItems"].get<std::size_t>()));
    if (schema.contains("maxItems") && v.size() > schema["maxItems"].get<std::size_t>())
      fail(where, fmt::format("more than {} items", schema["maxItems"].get<std::size_t>()));
    if (!schema.contains("items")) return;
    for (std::size_t i = 0; i < v.size(); ++i) check(v[i], schema["items"], fmt::format("{}/{}", where, i), depth + 1);
  }

  void check_scalar(const json& v, const json& schema, const std::string& where) const {
    if (v.is_string()) {
      const std::string& s = v.get_ref<const std::string&>();
      if (schema.contains("maxLength") && s.size() > schema["maxLength"].get<std::size_t>())
        fail(where, fmt::format("longer than {} bytes", schema["maxLength"].get<std::size_t>()));
      if (schema.contains("pattern") && !std::regex_match(s, std::regex(schema["pattern"].get<std::string>())))
        fail(where, "not of the form " + schema["pattern"].get<std::string>());
    }
    if (v.is_number()) {
      const double x = v.get<double>();
      if (schema.contains("minimum") && x < schema["minimum"].get<double>())
        fail(where, fmt::format("must be >= {:g}", schema["minimum"].get<double>()));
      if (schema.contains("maximum") && x > schema["maximum"].get<double>())
        fail(where, fmt::format("must be <= {:g}", schema["maximum"].get<double>()));
    }
  }

  void check(const json& v, const json& schema, const std::string& where, int depth) const {
    if (depth > most_depth) fail(where, fmt::format("nested deeper than {} levels", most_depth));
    check_type(v, schema, where);
    if (v.is_object()) check_object(v, schema, where, depth);
    else if (v.is_array()) check_array(v, schema, where, depth);
    else check_scalar(v, schema, where);
  }
};

}  // namespace

void check_schema(const json& value, const json& schema, const std::string& source) {
  Checker{source}.check(value, schema, "", 0);
}

json parse_checked(const std::string& text, const json& schema, const std::string& source) {
  // The parser recurses per level: the depth is bounded before it runs.
  int level = 0;
  bool in_string = false, escaped = false;
  for (char c : text) {
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') in_string = true;
    else if (c == '[' || c == '{') {
      if (++level > most_depth) throw Error(fmt::format("{}: nested deeper than {} levels", source, most_depth));
    } else if (c == ']' || c == '}') --level;
  }
  json value;
  try {
    value = json::parse(text);
  } catch (const json::exception& e) {
    std::string why = e.what();
    if (const auto cut = why.find("] "); cut != std::string::npos) why = why.substr(cut + 2);
    throw Error(fmt::format("{}: not JSON: {}", source, why));
  }
  check_schema(value, schema, source);
  return value;
}

}  // namespace gearpatch::runs
