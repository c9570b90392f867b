#pragma once
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace gearpatch {

/// Most rows of a drive table.
inline constexpr std::size_t most_drive_table_rows = 100000;

/// A measured drive torque profile: one "time, torque" pair a line (s, N·m;
/// comma, semicolon or blanks between), '#' comments, times not decreasing
/// (a repeated time is a step), each value 0 or 1e-30 … 1e30 in magnitude
/// as a scene's, at most most_drive_table_rows rows, a leading byte-order
/// mark skipped. Throws Error naming file:line on bad input.
std::vector<std::pair<double, double>> parse_drive_table(const std::string& text,
                                                         const std::string& source);
std::vector<std::pair<double, double>> load_drive_table(const std::string& path);

}  // namespace gearpatch
