#pragma once
#include <string>

#include <nlohmann/json.hpp>

namespace gearpatch::runs {

/// Checks `value` against `schema`, a subset of JSON Schema (draft 7): "type"
/// (a name or a list: object, array, string, number, integer, boolean, null),
/// "properties", "required", "additionalProperties" (false or a schema),
/// "maxProperties", "items", "minItems", "maxItems", "maxLength", "pattern"
/// (the whole string, ECMAScript), "minimum", "maximum". Files of a run folder
/// are checked this way before anything reads a field of them, so a damaged
/// or hostile file is an Error (exit 2) naming `source` and the place in it
/// ("results/0003.json: /figures/impacts: must be an integer"), never a
/// library exception. The value may be nested at most 64 levels deep.
void check_schema(const nlohmann::json& value, const nlohmann::json& schema, const std::string& source);

/// `text` parsed as JSON (at most 64 levels deep) and checked against
/// `schema`; an Error naming `source` for anything else.
nlohmann::json parse_checked(const std::string& text, const nlohmann::json& schema, const std::string& source);

}  // namespace gearpatch::runs
