#pragma once
#include <string>
#include <utility>
#include <vector>

namespace gearpatch {

/// A measured drive torque profile: one "time, torque" pair a line (s, N·m;
/// comma, semicolon or blanks between), '#' comments, times not decreasing
/// (a repeated time is a step). Throws Error naming file:line on bad input.
std::vector<std::pair<double, double>> parse_drive_table(const std::string& text,
                                                         const std::string& source);
std::vector<std::pair<double, double>> load_drive_table(const std::string& path);

}  // namespace gearpatch
