#include "machine/machine_file.h"

#include <algorithm>
#include <boost/program_options.hpp>
#include <filesystem>
#include <fmt/format.h>
#include <sstream>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/numbers.h"
#include "common/ini_reader.h"
#include "machine/embedded_machines.h"

namespace gearpatch {

namespace {

const std::vector<std::pair<ElementKind, const char*>> kind_names = {
    {ElementKind::integrator, "integrator"},   {ElementKind::summer, "summer"},
    {ElementKind::inverter, "inverter"},       {ElementKind::potentiometer, "potentiometer"},
    {ElementKind::comparator, "comparator"},   {ElementKind::diode, "diode"},
    {ElementKind::multiplier, "multiplier"},   {ElementKind::function_generator, "function_generator"},
};

/// The keys a profile may hold, "section.key" → what it means.
std::map<std::string, std::string> profile_keys() {
  std::map<std::string, std::string> keys = {
      {"name", "the profile's name"},
      {"description", "one line for the patch sheet"},
      {"machine.unit", "volts per machine unit"},
      {"machine.rails", "± supply of the amplifiers, V"},
      {"machine.k0", "the integrator constant chosen, 1/s"},
      {"machine.k0_choices", "the integrator constants the machine offers, 1/s, comma-separated"},
      {"machine.k0_labels", "the k0 switch position of each choice"},
      {"machine.input_resistance", "ohms of a weight-1 input"},
      {"machine.weights", "the input weights n, comma-separated"},
      {"machine.smallest_setting", "the smallest potentiometer setting set precisely, (0, 1)"},
      {"machine.chain", "how many machines daisy-chain into one (1: none)"},
      {"potentiometer.resistance", "ohms, end to end"},
      {"potentiometer.buffered", "true if each wiper drives a follower"},
      {"potentiometer.resolution", "the finest setting step"},
      {"comparator.hysteresis", "MU on the comparator's summed inputs"},
      {"comparator.switch_resistance", "ohms of a closed switch"},
      {"comparator.idle_throw", "ground or open: what a switched input sees while its switch is off"},
      {"circuit.switched_spring", "true: the spring enters the torque summer only while the flanks touch"},
      {"circuit.lock_catch", "share of the run within which the strongest self-locking reaction stops the load"},
      {"amplifier.model", "the amplifier's name"},
      {"amplifier.offset", "typical input offset, V"},
      {"amplifier.offset_spread", "one standard deviation of the offset, V"},
      {"amplifier.offset_sign", "random (a sign per amplifier) or positive"},
      {"amplifier.gain", "open-loop gain, V/V"},
      {"amplifier.bandwidth", "gain-bandwidth product, Hz"},
      {"amplifier.slew", "slew rate, V/s"},
      {"functions.dead_zone", "elements of a dead zone: summer + 2 diode + 2 potentiometer"},
      {"functions.limiter", "elements of a limiter"},
      {"functions.abs", "elements of an absolute value"},
      {"functions.halfwave", "elements of a half-wave rectifier pair"},
      {"functions.comparator", "elements of a comparator with its switch"},
      {"run.modes", "the modes of the mode switch"},
      {"run.op_time", "longest OP time of a repetitive run, s (0: a single run)"},
  };
  for (const auto& [kind, name] : kind_names) {
    const std::string section = name;
    keys[section + ".count"] = "how many the machine has";
    keys[section + ".label"] = "the panel label, numbered from 1";
    keys[section + ".inputs"] = "the weights of one element's inputs, comma-separated";
  }
  return keys;
}

std::string trimmed(std::string text) {
  const auto hash = text.find('#');
  if (hash != std::string::npos) text.erase(hash);
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  text.erase(0, first);
  text.erase(text.find_last_not_of(" \t\r") + 1);
  return text;
}

/// The first line of every "section.key" (Boost's parser does not report lines);
/// refuses lines Boost would misread.
std::map<std::string, int> locate(const std::string& text, const std::string& source) {
  std::map<std::string, int> found;
  std::istringstream in(text);
  std::string line, section;
  for (int number = 1; std::getline(in, line); ++number) {
    line = trimmed(line);
    if (line.empty()) continue;
    const std::string where = fmt::format("{}:{}: ", source, number);
    if (line.front() == '[') {
      // Boost keeps blanks inside the brackets: "[ gear ]" would make keys " gear .x", found on no line.
      if (line.back() != ']' || trimmed(line.substr(1, line.size() - 2)).empty() ||
          line.find_first_of(" \t", 1) < line.size() - 1)
        throw Error(where + "bad section header '" + line + "' (no blanks inside the brackets: [machine])");
      section = trimmed(line.substr(1, line.size() - 2));
      continue;
    }
    const auto eq = line.find('=');
    if (eq == std::string::npos || eq == 0) throw Error(where + "invalid line '" + line + "': expected key = value");
    const std::string key = trimmed(line.substr(0, eq));
    const std::string full = section.empty() ? key : section + "." + key;
    if (found.count(full)) throw Error(fmt::format("{}{} is given twice (first at line {})", where, full, found[full]));
    found[full] = number;
  }
  return found;
}

/// Typed access to the profile's values with file:line:key messages.
class ProfileReader {
 public:
  ProfileReader(std::string source, std::map<std::string, int> lines, std::map<std::string, std::string> values)
      : source_(std::move(source)), lines_(std::move(lines)), values_(std::move(values)) {}

  bool has(const std::string& key) const { return values_.count(key) != 0; }
  const std::string& raw(const std::string& key) const { return values_.at(key); }

  [[noreturn]] void fail(const std::string& key, const std::string& why) const {
    auto line = lines_.find(key);
    const std::string where = line == lines_.end() ? source_ : fmt::format("{}:{}", source_, line->second);
    throw Error(fmt::format("{}: {} = {}: {}", where, key, has(key) ? raw(key) : "(missing)", why));
  }

  double number(const std::string& key, double fallback, double least, double most) const {
    if (!has(key)) return fallback;
    const auto value = parse_finite(raw(key));
    if (!value) fail(key, "not a finite number");
    if (*value < least || *value > most) fail(key, fmt::format("must be in [{:g}, {:g}]", least, most));
    return *value;
  }

  std::vector<std::string> list(const std::string& key) const {
    std::vector<std::string> items;
    std::istringstream in(raw(key));
    for (std::string item; std::getline(in, item, ',');)
      if (!trimmed(item).empty()) items.push_back(trimmed(item));
    return items;
  }

  std::vector<double> numbers(const std::string& key, double least, double most) const {
    std::vector<double> values;
    for (const std::string& item : list(key)) {
      const auto value = parse_finite(item);
      if (!value || *value < least || *value > most)
        fail(key, fmt::format("'{}' is not a number in [{:g}, {:g}]", item, least, most));
      values.push_back(*value);
    }
    if (values.empty()) fail(key, "needs at least one value");
    return values;
  }

  std::vector<int> integers(const std::string& key, int least, int most) const {
    std::vector<int> values;
    for (double value : numbers(key, least, most)) {
      if (value != static_cast<int>(value)) fail(key, "the values must be whole numbers");
      values.push_back(static_cast<int>(value));
    }
    return values;
  }

  bool boolean(const std::string& key, bool fallback) const {
    if (!has(key)) return fallback;
    if (raw(key) == "true" || raw(key) == "yes") return true;
    if (raw(key) == "false" || raw(key) == "no") return false;
    fail(key, "must be true or false");
  }

  /// One of two words: true for `first`, false for `second`, `fallback` when absent.
  bool either(const std::string& key, const std::string& first, const std::string& second, bool fallback) const {
    if (!has(key)) return fallback;
    if (raw(key) == first) return true;
    if (raw(key) == second) return false;
    fail(key, "must be " + first + " or " + second);
  }

 private:
  std::string source_;
  std::map<std::string, int> lines_;
  std::map<std::string, std::string> values_;
};

std::map<std::string, std::string> read_values(const std::string& text, const std::string& source,
                                               const std::map<std::string, int>& lines) {
  std::map<std::string, std::string> values;
  for (const auto& option : parse_ini_options(text, profile_keys(), source)) {
    if (option.unregistered) {
      auto line = lines.find(option.string_key);
      throw Error(fmt::format("{}{}: {}: unknown key (a machine profile knows {})", source,
                              line == lines.end() ? "" : ":" + std::to_string(line->second), option.string_key,
                              "the keys of machines/the-analog-thing.ini"));
    }
    values[option.string_key] = option.value.empty() ? "" : option.value.front();
  }
  return values;
}

ElementKind parse_kind(const ProfileReader& r, const std::string& key, const std::string& name) {
  for (const auto& [kind, text] : kind_names)
    if (name == text) return kind;
  r.fail(key, "'" + name + "' is no element (integrator, summer, inverter, potentiometer, comparator, "
              "diode, multiplier, function_generator)");
}

/// "summer + 2 diode + 2 potentiometer".
Realisation parse_realisation(const ProfileReader& r, const std::string& key) {
  Realisation parts;
  std::istringstream in(r.raw(key));
  for (std::string part; std::getline(in, part, '+');) {
    std::istringstream words(trimmed(part));
    std::string first, second, extra;
    words >> first >> second >> extra;
    if (first.empty() || !extra.empty()) r.fail(key, "write it as 'summer + 2 diode + 2 potentiometer'");
    if (second.empty()) {
      parts.emplace_back(1, parse_kind(r, key, first));
    } else {
      const auto n = parse_finite(first);
      if (!n || *n < 1 || *n > 100 || *n != static_cast<int>(*n)) r.fail(key, "'" + first + "' is no count");
      parts.emplace_back(static_cast<int>(*n), parse_kind(r, key, second));
    }
  }
  if (parts.empty()) r.fail(key, "names no element");
  return parts;
}

void read_machine_section(const ProfileReader& r, MachineProfile& m) {
  m.unit_volts = r.number("machine.unit", m.unit_volts, 0.1, 1e3);
  m.supply_volts = r.number("machine.rails", m.supply_volts, 0.1, 1e4);
  if (m.supply_volts <= m.unit_volts) r.fail("machine.rails", "the rails must exceed the machine unit");
  m.integrator_constant = r.number("machine.k0", m.integrator_constant, 1e-3, 1e6);
  if (r.has("machine.k0_choices")) m.integrator_constants = r.numbers("machine.k0_choices", 1e-3, 1e6);
  if (r.has("machine.k0_labels")) m.integrator_constant_labels = r.list("machine.k0_labels");
  if (m.integrator_constant_labels.size() != m.integrator_constants.size() && r.has("machine.k0_labels"))
    r.fail("machine.k0_labels", "needs one label for each of machine.k0_choices");
  if (!m.integrator_constants.empty() &&
      std::find(m.integrator_constants.begin(), m.integrator_constants.end(), m.integrator_constant) ==
          m.integrator_constants.end())
    r.fail("machine.k0", "is not one of machine.k0_choices");
  m.input_resistance = r.number("machine.input_resistance", m.input_resistance, 1e3, 1e9);
  if (r.has("machine.weights")) m.weights = r.integers("machine.weights", 1, 1000);
  m.smallest_setting = r.number("machine.smallest_setting", m.smallest_setting, 1e-4, 0.99);
  m.chain = static_cast<int>(r.number("machine.chain", m.chain, 1, 16));
}

void read_elements(const ProfileReader& r, MachineProfile& m) {
  for (const auto& [kind, name] : kind_names) {
    const std::string section = name;
    if (!r.has(section + ".count")) continue;
    ElementType& e = m.elements[kind];
    e.count = static_cast<int>(r.number(section + ".count", 0, 0, 10000));
    e.label = r.has(section + ".label") ? r.raw(section + ".label") : section;
    if (r.has(section + ".inputs")) {
      e.inputs = r.integers(section + ".inputs", 1, 1000);
      for (int w : e.inputs)
        if (std::find(m.weights.begin(), m.weights.end(), w) == m.weights.end())
          r.fail(section + ".inputs", fmt::format("weight {} is not one of machine.weights", w));
    }
  }
  m.potentiometer_resistance = r.number("potentiometer.resistance", m.potentiometer_resistance, 10, 1e8);
  m.potentiometers_buffered = r.boolean("potentiometer.buffered", m.potentiometers_buffered);
  m.potentiometer_resolution = r.number("potentiometer.resolution", m.potentiometer_resolution, 1e-7, 0.1);
  m.comparator_hysteresis = r.number("comparator.hysteresis", m.comparator_hysteresis, 1e-6, 0.5);
  m.switch_resistance = r.number("comparator.switch_resistance", m.switch_resistance, 1e-3, 1e6);
  m.idle_throw_grounded = r.either("comparator.idle_throw", "ground", "open", m.idle_throw_grounded);
  m.switched_spring = r.boolean("circuit.switched_spring", m.switched_spring);
  m.lock_catch_share = r.number("circuit.lock_catch", m.lock_catch_share, 1e-4, 0.05);
}

void read_amplifier_and_run(const ProfileReader& r, MachineProfile& m) {
  AmplifierModel& a = m.amplifier;
  if (r.has("amplifier.model")) a.name = r.raw("amplifier.model");
  a.offset_volts = r.number("amplifier.offset", a.offset_volts, 0, 1);
  a.offset_spread_volts = r.number("amplifier.offset_spread", a.offset_spread_volts, 0, 1);
  a.random_sign = r.either("amplifier.offset_sign", "random", "positive", a.random_sign);
  a.gain = r.number("amplifier.gain", a.gain, 10, 1e12);
  a.bandwidth_hz = r.number("amplifier.bandwidth", a.bandwidth_hz, 1, 1e10);
  a.slew_volts_per_second = r.number("amplifier.slew", a.slew_volts_per_second, 1, 1e12);
  for (const char* block : {"dead_zone", "limiter", "abs", "halfwave", "comparator"}) {
    const std::string key = std::string("functions.") + block;
    if (r.has(key)) m.realisations[block] = parse_realisation(r, key);
  }
  if (r.has("run.modes")) m.modes = r.list("run.modes");
  m.op_time = r.number("run.op_time", m.op_time, 0, 1e6);
}

bool is_file_name(const std::string& name) {
  return name.find('/') != std::string::npos || name.find('.') != std::string::npos;
}

}  // namespace

std::string element_name(ElementKind kind) {
  for (const auto& [k, name] : kind_names)
    if (k == kind) return name;
  throw Error("unknown element kind", Error::Kind::internal);
}

const std::vector<ElementKind>& element_kinds() {
  static const std::vector<ElementKind> kinds = [] {
    std::vector<ElementKind> all;
    for (const auto& [kind, name] : kind_names) all.push_back(kind);
    return all;
  }();
  return kinds;
}

std::vector<std::string> machine_names() {
  std::vector<std::string> names;
  for (const auto& [name, text] : embedded_machines()) names.push_back(name);
  return names;
}

std::string MachineProfile::integrator_constant_label() const {
  for (std::size_t i = 0; i < integrator_constants.size() && i < integrator_constant_labels.size(); ++i)
    if (integrator_constants[i] == integrator_constant) return integrator_constant_labels[i];
  return format_number(integrator_constant);
}

MachineProfile parse_machine_profile(const std::string& text, const std::string& source) {
  const std::map<std::string, int> lines = locate(text, source);
  const ProfileReader r(source, lines, read_values(text, source, lines));
  MachineProfile m;
  m.name = r.has("name") ? r.raw("name") : std::filesystem::path(source).stem().string();
  if (r.has("description")) m.description = r.raw("description");
  read_machine_section(r, m);
  read_elements(r, m);
  read_amplifier_and_run(r, m);
  return m;
}

std::string machine_profile_text(const std::string& name) {
  const auto& shipped = embedded_machines();
  if (auto it = shipped.find(name); it != shipped.end()) return it->second;
  return read_file(name);
}

MachineProfile load_machine_profile(const std::string& name, const std::string& relative_to) {
  const auto& shipped = embedded_machines();
  if (auto it = shipped.find(name); it != shipped.end()) return parse_machine_profile(it->second, name);
  std::string names;
  for (const auto& [known, text] : shipped) names += (names.empty() ? "" : ", ") + known;
  if (!is_file_name(name)) throw Error("no machine named '" + name + "' (shipped: " + names + "; or a profile file)");
  std::filesystem::path path(name);
  if (!std::filesystem::exists(path) && !relative_to.empty() && path.is_relative())
    path = std::filesystem::path(relative_to).parent_path() / path;
  if (!std::filesystem::is_regular_file(path))
    throw Error("no machine profile file '" + name + "' (shipped machines: " + names + ")");
  return parse_machine_profile(read_file(path.string()), path.string());
}

}  // namespace gearpatch
