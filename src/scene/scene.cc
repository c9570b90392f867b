#include "scene/scene.h"

#include <boost/program_options.hpp>
#include <cmath>
#include <fmt/format.h>
#include <filesystem>
#include <functional>
#include <sstream>
#include <string_view>
#include <vector>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/numbers.h"
#include "common/utf8.h"
#include "common/ini_reader.h"
#include "machine/machine_file.h"
#include "model/stage_reduction.h"
#include "scene/drive_table.h"
#include "scene/units.h"

namespace gearpatch {

namespace {

/// Every key a scene may hold, with its line of --help-scene.
constexpr std::pair<std::string_view, std::string_view> scene_key_table[] = {
    {"name", "scene name (default: the file's stem)"},
    {"gear.inertia_primary", "Θp, kg·m², > 0"},
    {"gear.inertia_secondary", "Θs, kg·m², referred to the primary shaft, > 0"},
    {"gear.stiffness", "c, N·m/rad, > 0"},
    {"gear.restitution", "k in [0, 1] (give this or damping)"},
    {"gear.damping", "d, N·m·s/rad, >= 0 (give this or restitution)"},
    {"gear.backlash", "2ε, total play, >= 0, rad, or with its unit: 0.5 deg, 30 arcmin (default 0)"},
    {"friction.bearing_primary", "k_Rp, N·m, >= 0 (default 0)"},
    {"friction.bearing_secondary", "k_Rs, N·m, >= 0 (default 0)"},
    {"friction.mesh_efficiency", "η_z in (0, 1] (default 1: no tooth friction)"},
    {"friction.self_locking", "true|false (default false)"},
    {"drive.torque", "M_a, N·m on the primary (default 0)"},
    {"drive.load_torque", "N·m on the secondary, opposing positive rotation (default 0)"},
    {"drive.rated_torque", "M_am from the drive's data, N·m, > 0 (optional)"},
    {"drive.rated_speed", "φ̇pm = φ̇sm from the drive's data, rad/s or rpm, > 0 (optional)"},
    {"initial.speed_primary", "φ̇p(0), rad/s, or with its unit: deg/s, rpm (default 0)"},
    {"initial.speed_secondary", "φ̇s(0), rad/s, or with its unit: deg/s, rpm (default 0)"},
    {"initial.twist", "Δφ(0) = φp − φs, rad, or with its unit: deg (default 0)"},
    {"run.duration", "s of real time, > 0"},
    {"run.output_step", "s between output rows, > 0 (default duration/2000)"},
    {"maxima.drive_torque", "override M_am, N·m, > 0"},
    {"maxima.speed_primary", "override φ̇pm, rad/s, > 0"},
    {"maxima.speed_secondary", "override φ̇sm, rad/s, > 0"},
    {"maxima.relative_speed", "override Δφ̇m, rad/s, > 0"},
    {"maxima.contact_twist", "override Δφ'm, rad, > 0"},
    {"maxima.twist", "override Δφm, rad, > 0"},
    {"maxima.torque", "override M0m, N·m, > 0"},
    {"machine.profile", "the machine: a shipped profile (the-analog-thing, model-1, classic, generic) or a "
                        "profile file, relative to the scene (default generic); the machine.* keys below override it"},
    {"machine.unit", "volts per machine unit, 0.1 … 1e3 (default 10)"},
    {"machine.time_scale", "β (machine time = β·real time), 1e-6 … 1e6, or auto (default)"},
    {"machine.integrator_constant", "k0, 1/s at weight 1, 1e-3 … 1e6 (default 1)"},
    {"machine.input_resistance", "ohms of a weight-1 input, 1e3 … 1e9 (default 1e6)"},
    {"machine.potentiometer_resistance", "ohms, 10 … 1e8 (default 1e4)"},
    {"machine.supply", "± supply volts of the hardware op-amps, > unit, <= 1e4 (default 15)"},
    // What a drive engineer brings: values in each shaft's own
    // units, referred to the primary by the tool; drive profiles; motor line.
    {"gear.contact_law", "paper|capped (default paper): capped is Modelica's ElastoBacklash, the damping torque capped at the spring torque and no pull; k is inverted for the law chosen"},
    {"friction.characteristic", "coulomb|stribeck (default coulomb; add viscous_* for Coulomb + viscous): with stribeck, bearing_* are the break-away levels k_S"},
    {"friction.sliding_primary", "k_C, N·m, the primary's sliding level at high speed, 0 <= k_C <= bearing_primary (stribeck)"},
    {"friction.sliding_secondary", "k_C, N·m referred, the secondary's sliding level, 0 <= k_C <= bearing_secondary (stribeck)"},
    {"friction.stribeck_speed", "φ̇_S, rad/s or rpm, > 0: the level falls as k_C + (k_S − k_C)·exp(−|φ̇|/φ̇_S) (stribeck)"},
    {"gear.stages", "file of [stage] stiffness, damping sections referred to the primary (as for `gearpatch reduce`; path relative to the scene): c and d of the equivalent gear by (2.8), instead of gear.stiffness and restitution/damping"},
    {"gear.ratio", "i = φ̇p/φ̇load, the speed of the primary (motor) shaft over that of the load shaft, > 0 (default 1)"},
    {"load.inertia", "J, kg·m², on the load shaft, > 0: Θs = J/i² (instead of gear.inertia_secondary)"},
    {"load.stiffness", "N·m/rad, torsional stiffness of the coupling measured at the load shaft, > 0: c = c_load/i² (instead of gear.stiffness)"},
    {"load.backlash", "total play at the load shaft, rad or deg, >= 0: 2ε = i·play (instead of gear.backlash)"},
    {"load.bearing_friction", "N·m on the load shaft, >= 0: k_Rs = M/i (instead of friction.bearing_secondary)"},
    {"load.torque", "N·m on the load shaft: M_L = M/i (instead of drive.load_torque)"},
    {"load.viscous_friction", "N·m·s/rad on the load shaft, >= 0: b_s = b/i² (instead of friction.viscous_secondary)"},
    {"load.speed", "initial speed of the load shaft, rad/s or rpm: φ̇s(0) = i·speed (instead of initial.speed_secondary)"},
    {"drive.load", "active|reactive (default active): a reactive load resists motion like friction and never drives the shaft"},
    {"drive.profile", "constant|step|ramp|table|motor (default constant): how M_a varies"},
    {"drive.step_time", "s, >= 0: profile step, M_a = drive.torque before, drive.step_torque from then on"},
    {"drive.step_torque", "N·m: profile step, M_a after drive.step_time"},
    {"drive.ramp_start", "s, >= 0 (default 0): profile ramp, M_a = drive.torque until then"},
    {"drive.ramp_end", "s, > ramp_start: profile ramp, M_a linear from drive.torque to drive.ramp_torque"},
    {"drive.ramp_torque", "N·m: profile ramp, M_a from drive.ramp_end on"},
    {"drive.table", "file of 'time, torque' lines (s, N·m; linear between, constant outside; path relative to the scene; at most 100000 rows, values as the scene's): profile table"},
    {"drive.stall_torque", "M_stall, N·m, > 0: profile motor, M_a = M_stall·(1 − φ̇p/φ̇_noload)"},
    {"drive.no_load_speed", "φ̇_noload, rad/s or rpm, > 0: profile motor"},
    {"friction.viscous_primary", "b_p, N·m·s/rad, >= 0 (default 0): M = b_p·φ̇p"},
    {"friction.viscous_secondary", "b_s, N·m·s/rad referred to the primary, >= 0 (default 0)"},
};

}  // namespace

const std::map<std::string, std::string>& scene_keys() {
  static const std::map<std::string, std::string> keys = [] {
    std::map<std::string, std::string> table;
    for (const auto& [key, help] : scene_key_table) table.emplace(key, help);
    return table;
  }();
  return keys;
}

Quantity key_quantity(const std::string& key) {
  static const std::map<std::string, Quantity> stated = {
      {"gear.backlash", Quantity::angle},           {"initial.twist", Quantity::angle},
      {"load.backlash", Quantity::angle},           {"maxima.contact_twist", Quantity::angle},
      {"maxima.twist", Quantity::angle},            {"initial.speed_primary", Quantity::speed},
      {"initial.speed_secondary", Quantity::speed}, {"load.speed", Quantity::speed},
      {"drive.rated_speed", Quantity::speed},       {"drive.no_load_speed", Quantity::speed},
      {"friction.stribeck_speed", Quantity::speed}, {"maxima.speed_primary", Quantity::speed},
      {"maxima.speed_secondary", Quantity::speed},  {"maxima.relative_speed", Quantity::speed},
  };
  auto it = stated.find(key);
  return it == stated.end() ? Quantity::plain : it->second;
}

std::string Scene::where(const std::string& key) const {
  auto it = lines.find(key);
  if (it == lines.end() || it->second == 0) return source;
  return source + ":" + std::to_string(it->second);
}

namespace {

/// A scene line without its comment and surrounding blanks.
std::string significant(std::string line) {
  auto hash = line.find('#');
  if (hash != std::string::npos) line.erase(hash);
  auto first = line.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  line.erase(0, first);
  line.erase(line.find_last_not_of(" \t\r") + 1);
  return line;
}

/// The lines each "section.key" appears on, in order.
using KeyLines = std::map<std::string, std::vector<int>>;

// Boost's parser does not report lines, so we find them ourselves for messages.
KeyLines locate_keys(const std::string& text) {
  KeyLines found;
  std::istringstream in(text);
  std::string line, section;
  for (int number = 1; std::getline(in, line); ++number) {
    line = significant(line);
    if (line.empty()) continue;
    if (line.front() == '[' && line.back() == ']') {
      section = line.substr(1, line.size() - 2);
      continue;
    }
    auto eq = line.find('=');
    std::string key = line.substr(0, eq);
    key.erase(key.find_last_not_of(" \t\r") + 1);  // a CR before the '=' is a blank, as Boost reads it
    found[section.empty() ? key : section + "." + key].push_back(number);
  }
  return found;
}

/// Refuses, with their line, the lines Boost would refuse without one or
/// misread: a section header cut short, an empty one, a line without '='.
void check_lines(const std::string& text, const std::string& source) {
  std::istringstream in(text);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    line = significant(line);
    if (line.empty()) continue;
    const std::string where = source + ":" + std::to_string(number) + ": ";
    if (line.front() == '[') {
      if (line.back() != ']') throw Error(where + "section header " + quoted_excerpt(line) + " lacks its closing ']'");
      if (significant(line.substr(1, line.size() - 2)).empty())
        throw Error(where + "empty section header " + quoted_excerpt(line) + ": name the section ([gear], [run], ...)");
      if (line.find_first_of(" \t", 1) < line.size() - 1)
        throw Error(where + "section header " + quoted_excerpt(line) + ": no blanks inside the brackets ([gear], [run], ...)");
    } else if (line.find('=') == std::string::npos || line.front() == '=') {
      throw Error(where + "invalid line " + quoted_excerpt(line) + ": expected key = value");
    }
  }
}

/// Reads the raw strings of a scene, one per key, rejecting unknown keys.
std::map<std::string, std::string> read_values(const std::string& text, const KeyLines& key_lines,
                                               Scene& scene) {
  std::map<std::string, std::string> values;
  for (const auto& option : parse_ini_options(text, scene_keys(), scene.source)) {
    scene.lines.emplace(option.string_key, 0);
    if (option.unregistered)
      throw Error(scene.where(option.string_key) + ": " + option.string_key +
                  ": unknown key (see `gearpatch --help-scene`)");
    if (values.count(option.string_key)) {
      // Name the repeated line; the first one is where the key is found.
      auto lines = key_lines.find(option.string_key);
      const bool known = lines != key_lines.end() && lines->second.size() > 1;
      throw Error((known ? scene.source + ":" + std::to_string(lines->second[1]) : scene.where(option.string_key)) +
                  ": " + option.string_key + " is given twice (first at line " +
                  std::to_string(scene.lines[option.string_key]) + ")");
    }
    values[option.string_key] = option.value.empty() ? "" : option.value.front();
  }
  return values;
}

constexpr double largest_magnitude = 1e30, smallest_magnitude = 1e-30;


/// Typed access to the raw strings with the checks every key shares.
class Reader {
 public:
  Reader(const Scene& scene, std::map<std::string, std::string> values)
      : scene_(scene), values_(std::move(values)) {}

  bool has(const std::string& key) const { return values_.count(key) != 0; }

  [[noreturn]] void fail(const std::string& key, const std::string& why) const {
    throw Error(scene_.where(key) + ": " + key + " = " + raw(key) + ": " + why);
  }

  std::string raw(const std::string& key) const {
    auto it = values_.find(key);
    return it == values_.end() ? std::string("(missing)") : it->second;
  }

  std::optional<double> number(const std::string& key) const {
    if (!has(key)) return std::nullopt;
    std::string why;
    auto value = parse_quantity(values_.at(key), key_quantity(key), why);
    if (!value) fail(key, why);
    // Physical values in SI units are kept within 1e-30 … 1e30 in magnitude:
    // the solver forms products and quotients of several of them (c/Θ,
    // (c/Θ)²·Δφ, d·Δφ̇ …), which must neither overflow nor underflow.
    // Dimensionless k and η_z have their own ranges; the machine is not simulated.
    const bool physical = key.rfind("machine.", 0) != 0 && key != "gear.restitution" &&
                          key != "friction.mesh_efficiency";
    if (physical && std::abs(*value) > largest_magnitude)
      fail(key, "larger in magnitude than 1e30, the most the reference model computes with "
                "(SI units); rescale the scene");
    if (physical && *value != 0 && std::abs(*value) < smallest_magnitude)
      fail(key, "smaller in magnitude than 1e-30, the least the reference model computes with "
                "(SI units); write 0 for none where 0 is allowed, or rescale the scene");
    return value;
  }

  double required(const std::string& key) const {
    if (!has(key)) throw Error(scene_.source + ": " + key + " is missing: " + scene_keys().at(key));
    return *number(key);
  }

  double positive(const std::string& key, std::optional<double> fallback = std::nullopt) const {
    auto value = has(key) || !fallback ? std::optional<double>(required(key)) : fallback;
    if (*value <= 0) fail(key, "must be > 0");
    return *value;
  }

  double non_negative(const std::string& key, double fallback) const {
    double value = number(key).value_or(fallback);
    if (value < 0) fail(key, "must be >= 0");
    return value;
  }

  bool boolean(const std::string& key, bool fallback) const {
    if (!has(key)) return fallback;
    const std::string& text = values_.at(key);
    if (text == "true" || text == "yes" || text == "1") return true;
    if (text == "false" || text == "no" || text == "0") return false;
    fail(key, "must be true or false");
  }

 private:
  const Scene& scene_;
  std::map<std::string, std::string> values_;
};

void read_gear(const Reader& r, Scene& s) {
  s.inertia_primary = r.positive("gear.inertia_primary");
  if (!r.has("load.inertia")) s.inertia_secondary = r.positive("gear.inertia_secondary");
  if (r.has("gear.stages")) {  // c and d come from the stages (read_stages)
    for (const char* key : {"gear.stiffness", "gear.restitution", "gear.damping", "load.stiffness"})
      if (r.has(key)) r.fail(key, "give either gear.stages or the coupling's stiffness and damping, not both");
    s.backlash = r.non_negative("gear.backlash", 0);
    return;
  }
  if (!r.has("load.stiffness")) s.stiffness = r.positive("gear.stiffness");
  s.backlash = r.non_negative("gear.backlash", 0);
  s.restitution = r.number("gear.restitution");
  s.damping = r.number("gear.damping");
  if (s.restitution && s.damping)
    r.fail("gear.damping", "give either restitution or damping, not both");
  if (!s.restitution && !s.damping)
    throw Error(s.source + ": [gear] needs restitution (k) or damping (d)");
  if (s.restitution && (*s.restitution < 0 || *s.restitution > 1))
    r.fail("gear.restitution", "must be in [0, 1]");
  if (s.damping && *s.damping < 0) r.fail("gear.damping", "must be >= 0");
}

void read_friction_and_drive(const Reader& r, Scene& s) {
  s.bearing_primary = r.non_negative("friction.bearing_primary", 0);
  s.bearing_secondary = r.non_negative("friction.bearing_secondary", 0);
  s.mesh_efficiency = r.number("friction.mesh_efficiency").value_or(1.0);
  if (s.mesh_efficiency <= 0 || s.mesh_efficiency > 1)
    r.fail("friction.mesh_efficiency", "must be in (0, 1]");
  s.self_locking = r.boolean("friction.self_locking", false);
  s.drive_torque = r.number("drive.torque").value_or(0);
  s.load_torque = r.number("drive.load_torque").value_or(0);
  if (r.has("drive.rated_torque")) s.rated_torque = r.positive("drive.rated_torque");
  if (r.has("drive.rated_speed")) s.rated_speed = r.positive("drive.rated_speed");
}

/// The physical range of a machine key and why: the machine is not simulated
/// by the reference model, but its values divide and multiply every setting,
/// so a value no analog computer has would reach the deck as inf or NaN.
struct MachineRange {
  const char* key;
  double least, most;
  const char* unit;
  const char* why;
};

constexpr MachineRange machine_ranges[] = {
    {"machine.unit", 0.1, 1e3, "V", "analog computers' machine units (±10 V and ±100 V are usual)"},
    {"machine.integrator_constant", 1e-3, 1e6, "1/s",
     "analog computers' integrator constants (1, 10, 100 and 1000 /s are usual)"},
    {"machine.input_resistance", 1e3, 1e9, "ohms", "the input resistors of analog computers (1 MΩ is usual)"},
    {"machine.potentiometer_resistance", 10, 1e8, "ohms",
     "coefficient potentiometers (10 kΩ to 100 kΩ are usual)"},
    {"machine.supply", 0.1, 1e4, "V", "op-amp supplies (±15 V is usual)"},
    {"machine.time_scale", 1e-6, 1e6, "",
     "a machine time from a millionth to a million times the real time"},
};

double machine_value(const Reader& r, const std::string& key, double fallback) {
  for (const MachineRange& range : machine_ranges) {
    if (key != range.key) continue;
    const double value = r.positive(key, fallback);
    if (value < range.least || value > range.most)
      r.fail(key, fmt::format("must be in [{:g}, {:g}]{}{}, the range of {}", range.least, range.most,
                              *range.unit ? " " : "", range.unit, range.why));
    return value;
  }
  throw Error("no range for " + key, Error::Kind::internal);
}

/// The profile the machine.* keys start from: `chosen` (--machine) over the
/// scene's machine.profile over generic; a bad one is an error at that key.
MachineProfile machine_profile(const Reader& r, const Scene& s, const std::string& chosen) {
  if (!chosen.empty()) return load_machine_profile(chosen);
  if (!r.has("machine.profile")) return load_machine_profile("generic");
  try {
    return load_machine_profile(r.raw("machine.profile"), s.source);
  } catch (const Error& e) {
    r.fail("machine.profile", e.what());
  }
}

void read_machine(const Reader& r, Scene& s, const std::string& chosen) {
  s.machine = machine_profile(r, s, chosen);
  MachineProfile& m = s.machine;
  m.unit_volts = machine_value(r, "machine.unit", m.unit_volts);
  m.integrator_constant = machine_value(r, "machine.integrator_constant", m.integrator_constant);
  if (r.has("machine.integrator_constant")) m.integrator_constants.clear();  // the scene's k0 is the one
  m.input_resistance = machine_value(r, "machine.input_resistance", m.input_resistance);
  m.potentiometer_resistance = machine_value(r, "machine.potentiometer_resistance", m.potentiometer_resistance);
  m.supply_volts = machine_value(r, "machine.supply", m.supply_volts);
  if (m.supply_volts <= m.unit_volts)
    r.fail(r.has("machine.supply") ? "machine.supply" : "machine.unit",
           "the supply must exceed the machine unit");
  if (r.has("machine.time_scale") && r.raw("machine.time_scale") != "auto")
    m.time_scale = machine_value(r, "machine.time_scale", 1);
}

/// One key on the load shaft, referred to the primary into `target`;
/// refused beside the key it replaces.
void refer(const Reader& r, Scene& s, const std::string& key, const std::string& replaces,
           double factor, const std::string& symbol, const std::string& formula, double& target,
           bool non_negative = true) {
  if (!r.has(key)) return;
  if (r.has(replaces)) r.fail(key, "give either " + key + " (load shaft) or " + replaces + " (referred), not both");
  const double given = *r.number(key);
  if (non_negative && given < 0) r.fail(key, "must be >= 0");
  target = given * factor;
  s.extras.referrals.push_back({key, given, target, symbol, formula});
}

void read_load_shaft(const Reader& r, Scene& s) {
  DriveExtras& x = s.extras;
  x.ratio = r.positive("gear.ratio", 1.0);
  const double i = x.ratio;
  if (r.has("load.inertia")) {
    if (r.has("gear.inertia_secondary"))
      r.fail("load.inertia", "give either load.inertia (load shaft) or gear.inertia_secondary (referred), not both");
    r.positive("load.inertia");
  }
  refer(r, s, "load.inertia", "gear.inertia_secondary", 1 / (i * i), "Θs kg·m²", "J/i²", s.inertia_secondary);
  if (r.has("load.stiffness")) r.positive("load.stiffness");
  refer(r, s, "load.stiffness", "gear.stiffness", 1 / (i * i), "c N·m/rad", "c/i²", s.stiffness);
  refer(r, s, "load.backlash", "gear.backlash", i, "2ε rad", "i·play", s.backlash);
  refer(r, s, "load.bearing_friction", "friction.bearing_secondary", 1 / i, "k_Rs N·m", "M/i", s.bearing_secondary);
  refer(r, s, "load.torque", "drive.load_torque", 1 / i, "M_L N·m", "M/i", s.load_torque, false);
  refer(r, s, "load.viscous_friction", "friction.viscous_secondary", 1 / (i * i), "b_s N·m·s/rad", "b/i²",
        x.viscous_secondary);
  refer(r, s, "load.speed", "initial.speed_secondary", i, "φ̇s(0) rad/s", "i·ω", s.speed_secondary, false);
}

/// The keys of one drive profile, refused with any other profile.
void only_with(const Reader& r, const std::string& profile, const std::vector<std::string>& keys) {
  for (const auto& key : keys)
    if (r.has(key) && r.raw("drive.profile") != profile)
      r.fail(key, "only with drive.profile = " + profile);
}

void read_drive_profile(const Reader& r, Scene& s) {
  DriveExtras& x = s.extras;
  x.profile = r.has("drive.profile") ? r.raw("drive.profile") : "constant";
  only_with(r, "step", {"drive.step_time", "drive.step_torque"});
  only_with(r, "ramp", {"drive.ramp_start", "drive.ramp_end", "drive.ramp_torque"});
  only_with(r, "table", {"drive.table"});
  only_with(r, "motor", {"drive.stall_torque", "drive.no_load_speed"});
  const double m0 = s.drive_torque;
  auto& points = x.profile_points;
  if (x.profile == "constant") return;
  if (x.profile == "step") {
    const double at = r.non_negative("drive.step_time", 0);
    if (!r.has("drive.step_time")) r.required("drive.step_time");
    points = {{at, m0}, {at, r.required("drive.step_torque")}};
  } else if (x.profile == "ramp") {
    const double start = r.non_negative("drive.ramp_start", 0);
    const double end = r.required("drive.ramp_end");
    if (!(end > start)) r.fail("drive.ramp_end", "must be later than drive.ramp_start");
    points = {{start, m0}, {end, r.required("drive.ramp_torque")}};
  } else if (x.profile == "table") {
    if (!r.has("drive.table")) r.required("drive.table");
    std::filesystem::path file = r.raw("drive.table");
    if (file.is_relative()) file = std::filesystem::path(s.source).parent_path() / file;
    std::error_code ec;  // a device or FIFO would never end
    if (!std::filesystem::is_regular_file(file, ec)) r.fail("drive.table", "not a regular file: " + file.string());
    try {
      points = load_drive_table(file.string());
    } catch (const Error& e) {
      r.fail("drive.table", e.what());
    }
  } else if (x.profile == "motor") {
    if (r.has("drive.torque")) r.fail("drive.torque", "drive.profile = motor takes drive.stall_torque instead");
    s.drive_torque = r.positive("drive.stall_torque");
    x.motor_slope = s.drive_torque / r.positive("drive.no_load_speed");
    return;
  } else {
    r.fail("drive.profile", "must be constant, step, ramp, table or motor");
  }
  // The scaling's a-priori drive maximum: the profile's largest |M_a|, signed.
  s.drive_torque = 0;
  for (const auto& [t, m] : points)
    if (std::abs(m) > std::abs(s.drive_torque)) s.drive_torque = m;
}

/// gear.stages: n elastic members in series reduced to one c, d by (2.8).
void read_stages(const Reader& r, Scene& s) {
  if (!r.has("gear.stages")) return;
  std::filesystem::path file = r.raw("gear.stages");
  if (file.is_relative()) file = std::filesystem::path(s.source).parent_path() / file;
  std::error_code ec;  // a device or FIFO would never end
  if (!std::filesystem::is_regular_file(file, ec)) r.fail("gear.stages", "not a regular file: " + file.string());
  try {
    const StageReduction reduced = reduce_stages(load_stages(file.string()));
    s.stiffness = reduced.stiffness;
    s.damping = reduced.damping;
  } catch (const Error& e) {
    r.fail("gear.stages", e.what());
  }
}

/// A Stribeck dip: the sliding levels below the break-away levels and the speed it decays over.
void read_stribeck(const Reader& r, Scene& s) {
  const std::string kind = r.has("friction.characteristic") ? r.raw("friction.characteristic") : "coulomb";
  if (kind != "coulomb" && kind != "stribeck")
    r.fail("friction.characteristic", "must be coulomb or stribeck");
  for (const char* key : {"friction.sliding_primary", "friction.sliding_secondary", "friction.stribeck_speed"})
    if (r.has(key) && kind != "stribeck") r.fail(key, "only with friction.characteristic = stribeck");
  if (kind != "stribeck") return;
  DriveExtras& x = s.extras;
  x.stribeck_speed = r.positive("friction.stribeck_speed");
  x.sliding_primary = r.non_negative("friction.sliding_primary", s.bearing_primary);
  x.sliding_secondary = r.non_negative("friction.sliding_secondary", s.bearing_secondary);
  if (x.sliding_primary > s.bearing_primary)
    r.fail("friction.sliding_primary", "must not exceed the break-away level friction.bearing_primary");
  if (x.sliding_secondary > s.bearing_secondary)
    r.fail("friction.sliding_secondary", "must not exceed the break-away level friction.bearing_secondary");
}

/// gear.ratio, [load], drive.load, drive.profile and viscous friction.
void read_drive_engineer(const Reader& r, Scene& s) {
  read_stages(r, s);
  read_load_shaft(r, s);
  if (r.has("drive.load")) {
    const std::string kind = r.raw("drive.load");
    if (kind != "active" && kind != "reactive") r.fail("drive.load", "must be active or reactive");
    s.extras.reactive_load = kind == "reactive";
    if (s.extras.reactive_load && s.load_torque < 0)
      r.fail(r.has("load.torque") ? "load.torque" : "drive.load_torque",
             "a reactive load is a magnitude (it opposes whichever way the shaft turns): must be >= 0");
  }
  if (r.has("gear.contact_law")) {
    const std::string law = r.raw("gear.contact_law");
    if (law != "paper" && law != "capped") r.fail("gear.contact_law", "must be paper or capped");
    s.extras.capped_contact = law == "capped";
    if (s.extras.capped_contact && s.backlash == 0)
      r.fail("gear.contact_law", "the capped law needs backlash > 0 (gear.backlash or load.backlash)");
    if (s.extras.capped_contact && s.restitution && *s.restitution == 0)
      r.fail("gear.restitution", "the capped law reaches k = 0 only with infinite damping: must be > 0");
  }
  read_stribeck(r, s);
  s.extras.viscous_primary = r.non_negative("friction.viscous_primary", 0);
  if (r.has("friction.viscous_secondary"))
    s.extras.viscous_secondary = r.non_negative("friction.viscous_secondary", 0);
  read_drive_profile(r, s);
}

}  // namespace

Scene parse_scene(const std::string& file_text, const std::string& source) {
  return parse_scene(file_text, source, "");
}

Scene parse_scene(const std::string& file_text, const std::string& source, const std::string& machine) {
  // A byte-order mark, as some Windows editors write, is not part of the first line.
  constexpr std::string_view bom = "\xEF\xBB\xBF";
  const std::string text = file_text.starts_with(bom) ? file_text.substr(bom.size()) : file_text;
  Scene s;
  s.source = source;
  s.name = std::filesystem::path(source).stem().string();
  check_lines(text, source);
  const KeyLines key_lines = locate_keys(text);
  for (const auto& [key, lines] : key_lines) s.lines[key] = lines.front();
  Reader r(s, read_values(text, key_lines, s));
  if (r.has("name")) s.name = r.raw("name");
  if (r.has("name") && !is_utf8(s.name)) r.fail("name", "not UTF-8 text (save the file as UTF-8)");
  read_gear(r, s);
  read_friction_and_drive(r, s);
  s.speed_primary = r.number("initial.speed_primary").value_or(0);
  s.speed_secondary = r.number("initial.speed_secondary").value_or(0);
  s.twist = r.number("initial.twist").value_or(0);
  read_drive_engineer(r, s);
  s.duration = r.positive("run.duration");
  if (r.has("run.output_step")) s.output_step = r.positive("run.output_step");
  for (const auto& [key, help] : scene_keys())
    if (key.rfind("maxima.", 0) == 0 && r.has(key)) s.maxima[key.substr(7)] = r.positive(key);
  read_machine(r, s, machine);
  return s;
}

Scene load_scene(const std::string& path) { return parse_scene(read_file(path), path); }

Scene load_scene(const std::string& path, const std::string& machine) {
  return parse_scene(read_file(path), path, machine);
}

}  // namespace gearpatch
