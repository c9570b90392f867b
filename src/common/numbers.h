#pragma once
#include <optional>
#include <string>
#include <string_view>

namespace gearpatch {

/// Parses a whole string as a finite double, locale-independently; empty on
/// anything else (trailing text, "nan", "inf", out of range).
std::optional<double> parse_finite(std::string_view text);

/// Shortest text that reads back to the same double, independent of locale
/// (netlists and CSV must not depend on LC_NUMERIC).
std::string format_number(double value);

}  // namespace gearpatch
