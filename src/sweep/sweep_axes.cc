#include "sweep/sweep_axes.h"

#include <cmath>
#include <fmt/format.h>
#include <sstream>

#include "common/error.h"
#include "common/numbers.h"
#include "runs/run_files.h"

namespace gearpatch::sweep {
namespace {

std::vector<std::string> split(const std::string& text, char at) {
  std::vector<std::string> parts;
  std::size_t from = 0;
  for (std::size_t cut; (cut = text.find(at, from)) != std::string::npos; from = cut + 1)
    parts.push_back(text.substr(from, cut - from));
  parts.push_back(text.substr(from));
  return parts;
}

/// The values of `start:stop:count`, or of `log:start:stop:count`.
std::vector<std::string> range_values(const std::vector<std::string>& parts, const std::string& option) {
  const bool log = parts.size() == 4;
  if (log && parts[0] != "log")
    throw Error(fmt::format("--set {}: a range is start:stop:count or log:start:stop:count", option));
  const auto start = parse_finite(parts[log ? 1 : 0]), stop = parse_finite(parts[log ? 2 : 1]);
  const auto count = parse_finite(parts[log ? 3 : 2]);
  if (!start || !stop) throw Error(fmt::format("--set {}: a range's ends must be finite numbers", option));
  if (!count || *count < 1 || *count > most_values || *count != std::floor(*count))
    throw Error(fmt::format("--set {}: a range's count must be a whole number in [1, {}]", option, most_values));
  if (log && (*start <= 0 || *stop <= 0))
    throw Error(fmt::format("--set {}: a log range's ends must be > 0", option));
  const auto n = static_cast<std::size_t>(*count);
  std::vector<std::string> values;
  for (std::size_t i = 0; i < n; ++i) {
    const double f = n == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(n - 1);
    const double v = log ? std::exp(std::log(*start) + f * (std::log(*stop) - std::log(*start)))
                         : *start + f * (*stop - *start);
    // The ends exactly as written: 1e-3 stays 1e-3, not 0.0010000000000000002.
    values.push_back(i == 0 ? fmt::format("{:.15g}", *start)
                            : i + 1 == n ? fmt::format("{:.15g}", *stop) : fmt::format("{:.12g}", v));
  }
  return values;
}

/// The line's key ("gear.restitution") in `section`, "" for none.
std::string line_key(const std::string& raw, std::string& section) {
  std::string line = raw.substr(0, raw.find('#'));
  const auto first = line.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  line = line.substr(first, line.find_last_not_of(" \t\r") + 1 - first);
  if (line.front() == '[' && line.back() == ']') {
    section = line.substr(1, line.size() - 2);
    return "";
  }
  std::string key = line.substr(0, line.find('='));
  key.erase(key.find_last_not_of(" \t\r") + 1);  // a CR before the '=' is a blank, as Boost reads it
  return section.empty() ? key : section + "." + key;
}

/// The key a scene gives instead of `key`, "" if none.
std::string alternative(const std::string& key) {
  if (key == "gear.restitution") return "gear.damping";
  if (key == "gear.damping") return "gear.restitution";
  return "";
}

}  // namespace

void check_value(const std::string& value, const std::string& what) {
  if (value.empty()) throw Error(fmt::format("{}: an empty value", what));
  if (value.size() > most_value_bytes) throw Error(fmt::format("{}: a value longer than {} bytes", what, most_value_bytes));
  for (char c : value) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f || c == '#' || c == '=' || c == '[' || c == ']')
      throw Error(fmt::format("{}: a value is one line of a scene key's value: no newline or other control "
                              "character, '#', '=', '[' or ']'",
                              what));
  }
}

void check_axis(const Axis& axis, const std::string& what) {
  if (axis.key == "name" || !scene_keys().count(axis.key))
    throw Error(fmt::format("{}: {}: {} (see `gearpatch --help-scene`)", what, runs::printable(axis.key),
                            axis.key == "name" ? "the scene's name is not swept" : "unknown scene key"));
  if (axis.values.empty() || axis.values.size() > most_values)
    throw Error(fmt::format("{}: {} values; an axis has 1 … {}", what, axis.values.size(), most_values));
  for (const std::string& v : axis.values) check_value(v, what);
}

Axis parse_axis(const std::string& option) {
  const std::string what = "--set " + runs::printable(option);
  const auto eq = option.find('=');
  if (eq == std::string::npos || eq == 0)
    throw Error(fmt::format("{}: expected KEY=VALUES (gear.restitution=0,0.5,1)", what));
  Axis axis{option.substr(0, eq), {}};
  check_axis({axis.key, {"0"}}, what);
  for (const std::string& item : split(option.substr(eq + 1), ',')) {
    const std::vector<std::string> parts = split(item, ':');
    check_value(item, what);
    if (parts.size() == 1) axis.values.push_back(item);
    else if (parts.size() == 3 || parts.size() == 4)
      for (std::string& v : range_values(parts, option)) axis.values.push_back(std::move(v));
    else throw Error(fmt::format("--set {}: {}: a range is start:stop:count or log:start:stop:count", option, item));
    if (axis.values.size() > most_values)
      throw Error(fmt::format("--set {}: more than {} values", option, most_values));
  }
  return axis;
}

std::size_t point_count(const std::vector<Axis>& axes) {
  std::size_t count = 1;
  for (const Axis& axis : axes) {
    // Checked before any point is made: three axes of 1000 values would be 1e9 points.
    if (axis.values.size() > 0 && count > most_values / axis.values.size())
      throw Error(fmt::format("the sweep has more than {} points (the product of its axes' values)", most_values));
    count *= axis.values.size();
  }
  return count;
}

std::vector<Assignment> cartesian_points(const std::vector<Axis>& axes) {
  point_count(axes);
  std::vector<Assignment> points{{}};
  for (const Axis& axis : axes) {
    std::vector<Assignment> longer;
    for (const Assignment& p : points)
      for (const std::string& v : axis.values) {
        longer.push_back(p);
        longer.back().emplace_back(axis.key, v);
      }
    points = std::move(longer);
  }
  return points;
}

std::string point_label(const Assignment& point) {
  std::string label;
  for (const auto& [key, value] : point) label += (label.empty() ? "" : " ") + key + "=" + value;
  return label;
}

std::string assign(const std::string& scene_text, const Assignment& point) {
  std::istringstream in(scene_text);
  std::string out, raw, section, appended;
  std::vector<bool> placed(point.size(), false);
  while (std::getline(in, raw)) {
    const std::string key = line_key(raw, section);
    std::string line = raw;
    for (std::size_t i = 0; i < point.size() && !key.empty(); ++i) {
      const std::string name = point[i].first.substr(point[i].first.find('.') + 1);
      if (key == point[i].first) {
        line = name + " = " + point[i].second + "   # --set";
        placed[i] = true;
      } else if (key == alternative(point[i].first)) {
        line = "# " + raw + "   (replaced by --set " + point[i].first + ")";
      }
    }
    out += line + "\n";
  }
  for (std::size_t i = 0; i < point.size(); ++i) {
    if (placed[i]) continue;
    const auto dot = point[i].first.find('.');
    appended += fmt::format("[{}]\n{} = {}   # --set\n", point[i].first.substr(0, dot),
                            point[i].first.substr(dot + 1), point[i].second);
  }
  return out + appended;
}

std::optional<std::string> scene_value(const std::string& scene_text, const std::string& key) {
  std::istringstream in(scene_text);
  std::string raw, section;
  std::optional<std::string> value;
  while (std::getline(in, raw)) {
    if (line_key(raw, section) != key) continue;
    std::string v = raw.substr(0, raw.find('#'));
    v = v.substr(v.find('=') + 1);
    const auto first = v.find_first_not_of(" \t\r");
    value = first == std::string::npos ? "" : v.substr(first, v.find_last_not_of(" \t\r") + 1 - first);
  }
  return value;
}

Scene point_scene(const std::string& scene_text, const std::string& source, const Assignment& point,
                  const std::string& machine) {
  try {
    return parse_scene(assign(scene_text, point), source, machine);
  } catch (const Error& e) {
    throw Error(fmt::format("--set {}: {}", point_label(point), e.what()), e.kind());
  }
}

}  // namespace gearpatch::sweep
