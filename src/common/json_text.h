#pragma once
#include <nlohmann/json.hpp>
#include <string>

namespace gearpatch {

/// A JSON document as gearpatch writes it: indented, ending in a newline, and
/// text that is not UTF-8 (a file name) written as U+FFFD, not an exception
/// after the work.
template <class Json>
std::string json_text(const Json& j, int indent = 2) {
  return j.dump(indent, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace gearpatch
