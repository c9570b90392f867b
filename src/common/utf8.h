#pragma once
#include <string_view>

namespace gearpatch {

/// Whether `text` is well-formed UTF-8 (no overlong forms, surrogates or code
/// points past U+10FFFF): text that goes into JSON reports must be.
bool is_utf8(std::string_view text);

}  // namespace gearpatch
