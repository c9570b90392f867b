#include "patching/patch_sheet.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common/numbers.h"
#include "machine/machine_file.h"
#include "patching/signal_names.h"

namespace gearpatch::patching {

namespace {

std::string through(const Connection& c) {
  std::string text;
  if (c.potentiometer)
    text += c.potentiometer_label.empty()
                ? fmt::format(" → wire ({} = 1)", to_string(*c.potentiometer))
                : fmt::format(" → {} ({} = {:.5f})", c.potentiometer_label, to_string(*c.potentiometer), c.setting);
  if (!c.switch_label.empty()) text += " → switch of " + c.switch_label;
  if (!c.latch_label.empty()) text += " ∥ latch " + c.latch_label;
  return text;
}

std::string header(const Allocation& a) {
  const MachineProfile& m = a.machine;
  std::string text = fmt::format("patch {} on {}{}\n", a.scene, m.name, m.description.empty() ? "" : ": " + m.description);
  text += fit_summary(a) + "\n";
  text += fmt::format("k0 switch: {} (k0 = {}/s); β = {:.6g}: machine time = β · real time\n",
                      m.integrator_constant_label(), format_number(m.integrator_constant), a.beta);
  text += fmt::format("mode: {}; 1 MU = {} V; every amplifier inverts\n", a.run_mode(), format_number(m.unit_volts));
  return text;
}

std::string counts(const Allocation& a) {
  std::string text = "\nelement               needed  available\n";
  for (const Count& c : a.counts)
    text += fmt::format("  {:<20}{:>6}  {:>9}{}\n", element_name(c.kind), c.needed, c.available,
                        c.needed > c.available ? fmt::format("  ({} short)", c.needed - c.available) : "");
  return text;
}

std::string elements(const Allocation& a) {
  std::string text = "\nelements:\n";
  for (const Element& e : a.elements)
    if (e.kind != ElementKind::potentiometer)
      text += fmt::format("  {:<10} {:<14} {}\n", e.label, e.realises, e.role);
  return text;
}

std::string potentiometers(const Allocation& a) {
  std::string text = a.machine.potentiometers_buffered
                         ? "\npotentiometers (buffered: the dial is the setting):\n"
                         : "\npotentiometers (not buffered: dial 'loaded' with the load connected):\n";
  for (const PotentiometerUse& p : a.potentiometers) {
    text += fmt::format("  {:<10} {:.5f}", p.label, p.setting);
    if (!a.machine.potentiometers_buffered) text += fmt::format("  loaded {:<9}", fmt::format("{:.5f}", p.loaded_setting));
    text += "  " + p.what + "\n";
  }
  return text;
}

std::string initial_conditions(const Allocation& a) {
  std::string text = "\ninitial conditions (set in IC mode):\n";
  for (const InitialCondition& ic : a.initial_conditions)
    text += fmt::format("  {:<10} output starts at {} MU ({}): {}\n", ic.integrator, format_number(ic.value),
                        signal_of(ic.node), ic.how);
  return text;
}

std::string connections(const Allocation& a) {
  std::string text = "\nconnections (element output → element input, weight):\n";
  for (const Connection& c : a.connections)
    text += fmt::format("  {:>3}. {} ({}){} → {} input {} (weight {})\n", c.number, c.from_label, c.from_signal,
                        through(c), c.to_label, c.input, c.weight);
  return text;
}

std::string watch(const Allocation& a) {
  std::string text = "\nwatch:\n";
  for (const Watch& w : a.watches)
    text += fmt::format("  {:<8} at {} output: 1 MU ({} V) = {} {}\n", w.signal, w.label,
                        format_number(a.machine.unit_volts), format_number(w.full_scale), w.unit);
  return text;
}

std::string lines(const std::string& title, const std::vector<std::string>& items) {
  if (items.empty()) return "";
  std::string text = "\n" + title + ":\n";
  for (const auto& item : items) text += "  " + item + "\n";
  return text;
}

}  // namespace



std::string fit_summary(const Allocation& a) {
  if (a.fits()) {
    std::string used;
    for (const Count& c : a.counts)
      if (c.needed > 0) used += fmt::format("{}{} of {} {}", used.empty() ? "" : ", ", c.needed, c.available,
                                            element_name(c.kind));
    return fmt::format("fits one {}: {}", a.machine.name, used);
  }
  std::string why;
  for (const auto& s : a.shortfalls) why += (why.empty() ? "" : "; ") + s;
  for (const auto& s : a.input_overflows) why += (why.empty() ? "" : "; ") + s;
  std::string text = fmt::format("does NOT fit one {}: {}", a.machine.name, why);
  if (a.machines_needed > 1 && a.machines_needed <= a.machine.chain && a.input_overflows.empty())
    text += fmt::format("; fits on {} chained machines", a.machines_needed);
  return text;
}

std::string to_text(const Allocation& a) {
  return header(a) + counts(a) + elements(a) + potentiometers(a) + initial_conditions(a) + connections(a) +
         watch(a) + lines("notes", a.notes) + lines("options", a.options);
}

std::string to_json(const Allocation& a) {
  using nlohmann::ordered_json;
  ordered_json j;
  j["scene"] = a.scene;
  j["machine"] = a.machine.name;
  j["fits"] = a.fits();
  j["machines_needed"] = a.machines_needed;
  j["summary"] = fit_summary(a);
  j["k0"] = a.machine.integrator_constant;
  j["k0_switch"] = a.machine.integrator_constant_label();
  j["beta"] = a.beta;
  j["mode"] = a.run_mode();
  j["unit_volts"] = a.machine.unit_volts;
  for (const Count& c : a.counts)
    j["counts"].push_back({{"element", element_name(c.kind)}, {"needed", c.needed}, {"available", c.available}});
  for (const Element& e : a.elements)
    j["elements"].push_back({{"label", e.label}, {"element", element_name(e.kind)}, {"machine", e.machine},
                             {"realises", e.realises}, {"role", e.role}});
  for (const PotentiometerUse& p : a.potentiometers)
    j["potentiometers"].push_back({{"label", p.label}, {"setting_name", p.setting_name ? to_string(*p.setting_name) : ""},
                                   {"setting", p.setting}, {"loaded_setting", p.loaded_setting},
                                   {"weight", p.weight}, {"what", p.what}});
  for (const InitialCondition& ic : a.initial_conditions)
    j["initial_conditions"].push_back({{"integrator", ic.integrator}, {"node", ic.node}, {"value", ic.value},
                                       {"how", ic.how}});
  for (const Connection& c : a.connections)
    j["connections"].push_back({{"number", c.number}, {"from", c.from_label}, {"from_node", c.from_node},
                                {"signal", c.from_signal},
                                {"potentiometer", c.potentiometer ? to_string(*c.potentiometer) : ""},
                                {"potentiometer_label", c.potentiometer_label}, {"setting", c.setting},
                                {"loaded_setting", c.loaded_setting}, {"switch", c.switch_label},
                                {"latch", c.latch_label}, {"to", c.to_label}, {"to_instance", c.to_instance}, {"input", c.input},
                                {"weight", c.weight}});
  for (const Watch& w : a.watches)
    j["watch"].push_back({{"signal", w.signal}, {"at", w.label}, {"node", w.node}, {"full_scale", w.full_scale},
                          {"unit", w.unit}});
  j["shortfalls"] = a.shortfalls;
  j["input_overflows"] = a.input_overflows;
  j["notes"] = a.notes;
  j["options"] = a.options;
  return j.dump(2) + "\n";
}

}  // namespace gearpatch::patching
