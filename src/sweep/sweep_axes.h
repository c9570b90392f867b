#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene.h"

namespace gearpatch::sweep {

/// One swept scene key and its values as text, from `--set KEY=VALUES`.
struct Axis {
  std::string key;                  ///< "gear.restitution"
  std::vector<std::string> values;  ///< "0", "0.25", ...
};

/// The scene keys and values of one point of the sweep.
using Assignment = std::vector<std::pair<std::string, std::string>>;

/// Parses `KEY=VALUES`: VALUES is a comma-separated list whose items are a
/// value, a linear range `start:stop:count` or a logarithmic one
/// `log:start:stop:count` (both ends included). Error (exit 2) naming the
/// --set for an unknown scene key, the key `name`, a malformed range or a
/// count below 1 or above 10000.
Axis parse_axis(const std::string& option);

/// Most values of an axis and most points of a sweep; most bytes of a value.
inline constexpr std::size_t most_values = 10000;
inline constexpr std::size_t most_value_bytes = 1024;

/// Error naming `what` unless `value` is one scene value: not empty, at most
/// most_value_bytes, no control character (a newline would add a line to
/// the scene), '#', '=', '[' or ']'.
void check_value(const std::string& value, const std::string& what);
/// Error naming `what` unless the axis names a scene key (not `name`) and
/// has 1 … most_values values, each a scene value.
void check_axis(const Axis& axis, const std::string& what);

/// The number of points of the axes' product; Error above most_values,
/// found before any point is made.
std::size_t point_count(const std::vector<Axis>& axes);

/// Every point of the cartesian product of the axes, the last axis fastest.
std::vector<Assignment> cartesian_points(const std::vector<Axis>& axes);

/// The value the scene text gives `key` ("drive.table"), as written; none if absent.
std::optional<std::string> scene_value(const std::string& scene_text, const std::string& key);

/// "gear.restitution=0.25 gear.backlash=0.1": a point's name in tables and plots.
std::string point_label(const Assignment& point);

/// The scene text with the point's values in place: a key already in the
/// file keeps its line (so the reader's file:line messages point at it),
/// a new one goes into a section appended at the end; setting
/// gear.restitution comments out gear.damping and the other way round,
/// since a scene gives one of them.
std::string assign(const std::string& scene_text, const Assignment& point);

/// The point's scene read from the assigned text; a bad value is refused
/// with the scene reader's own file:line: key message behind the --set it
/// came from.
Scene point_scene(const std::string& scene_text, const std::string& source, const Assignment& point,
                  const std::string& machine = "");

}  // namespace gearpatch::sweep
