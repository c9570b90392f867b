#pragma once
#include <string>
#include <string_view>

namespace gearpatch {

/// Whether `text` is well-formed UTF-8 (no overlong forms, surrogates or code
/// points past U+10FFFF): text that goes into JSON reports must be.
bool is_utf8(std::string_view text);

/// `text` in single quotes for a message: at most `limit` characters, bytes
/// that are not printable UTF-8 as \xNN, and how many bytes were cut off, so
/// a binary file named as a scene cannot flood or garble the terminal.
std::string quoted_excerpt(std::string_view text, std::size_t limit = 60);

}  // namespace gearpatch
