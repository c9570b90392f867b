#include "scene/drive_table.h"

#include <cmath>
#include <sstream>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/numbers.h"

namespace gearpatch {
namespace {

/// The ranges of the scene's own values: 0, or 1e-30 … 1e30 in magnitude.
void check_magnitude(double value, const std::string& what) {
  if (std::abs(value) > 1e30) throw Error(what + ": larger in magnitude than 1e30, as no scene value may be");
  if (value != 0 && std::abs(value) < 1e-30)
    throw Error(what + ": smaller in magnitude than 1e-30 (and not 0), as no scene value may be");
}

}  // namespace

std::vector<std::pair<double, double>> parse_drive_table(const std::string& text,
                                                         const std::string& source) {
  std::vector<std::pair<double, double>> points;
  // A byte-order mark, as a spreadsheet writes it, is no part of the first time.
  std::istringstream in(text.starts_with("\xEF\xBB\xBF") ? text.substr(3) : text);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    for (char& c : line)
      if (c == ',' || c == ';' || c == '\t' || c == '\r') c = ' ';
    std::istringstream fields(line);
    std::vector<std::string> words;
    for (std::string w; fields >> w;) words.push_back(w);
    if (words.empty()) continue;
    const std::string where = source + ":" + std::to_string(number) + ": ";
    if (words.size() != 2) throw Error(where + "expected two numbers: time (s), torque (N·m)");
    const auto t = parse_finite(words[0]), m = parse_finite(words[1]);
    if (!t) throw Error(where + "time " + words[0] + ": not a finite number");
    if (!m) throw Error(where + "torque " + words[1] + ": not a finite number");
    if (*t < 0) throw Error(where + "time " + words[0] + ": must be >= 0");
    check_magnitude(*t, where + "time " + words[0]);
    check_magnitude(*m, where + "torque " + words[1]);
    if (points.size() == most_drive_table_rows)
      throw Error(where + "more than " + std::to_string(most_drive_table_rows) + " rows");
    if (!points.empty() && *t < points.back().first)
      throw Error(where + "time " + words[0] + ": earlier than the line before (times must not decrease)");
    points.emplace_back(*t, *m);
  }
  if (points.empty()) throw Error(source + ": the drive table has no points");
  return points;
}

std::vector<std::pair<double, double>> load_drive_table(const std::string& path) {
  return parse_drive_table(read_file(path), path);
}

}  // namespace gearpatch
