#include "patching/patch_sheet.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common/numbers.h"
#include "machine/machine_file.h"
#include "patching/wiring_json.h"

namespace gearpatch::patching {

namespace {

std::string header(const Allocation& a, const Wiring& w) {
  const MachineProfile& m = a.machine;
  std::string text = fmt::format("patch {} on {}{}\n", a.scene, m.name, m.description.empty() ? "" : ": " + m.description);
  text += fit_summary(a) + "\n";
  text += fmt::format("k0 switch: {} (k0 = {:.5g}/s); β = {:.5g}: machine time = β · real time\n", w.k0_switch, w.k0,
                      w.beta);
  text += fmt::format("mode: {}; 1 MU = {:.5g} V; every amplifier inverts; thresholds set for the {} level\n",
                      a.run_mode(), w.unit_volts, w.level);
  return text;
}

std::string counts(const Allocation& a) {
  std::string text = "\nelement               needed  available\n";
  for (const Count& c : a.counts)
    text += fmt::format("  {:<20}{:>6}  {:>9}{}\n", element_name(c.kind), c.needed, c.available,
                        c.needed > c.available ? fmt::format("  ({} short)", c.needed - c.available) : "");
  return text;
}

std::string elements(const Wiring& w) {
  std::string text = "\nelements:\n";
  for (const Part& p : w.parts) {
    if (p.kind == "potentiometer") continue;
    std::string what = p.role;
    if (!p.function.empty() && p.function != "drive" && p.function != "latched_switch")
      what = fmt::format("{} unit, parameter {}: {}", p.function, p.parameter.empty() ? "none" : p.parameter, p.role);
    text += fmt::format("  {:<10} {:<14} {}\n", p.label, p.kind, what);
  }
  return text;
}

std::string potentiometers(const Allocation& a, const Wiring& w) {
  const bool buffered = a.machine.potentiometers_buffered;
  std::string text = buffered ? "\npotentiometers (buffered: the dial is the setting; one may feed several inputs):\n"
                              : "\npotentiometers (not buffered: set the dial with the load connected):\n";
  for (const Part& p : w.parts) {
    if (p.kind != "potentiometer") continue;
    text += fmt::format("  {:<10} {:<9}", p.label, fmt::format("{:.5g}", p.setting));
    if (!buffered) text += fmt::format("  dial {:<9}", fmt::format("{:.5g}", p.dial));
    text += fmt::format("  {:<14} {}\n", p.setting_name, p.role);
  }
  return text;
}

std::string initial_conditions(const Wiring& w) {
  std::string text = "\ninitial values (IC mode; the IC input takes minus the start value):\n";
  for (const Wire& x : w.wires) {
    if (x.to.jack != "IC") continue;
    const Part* p = w.find(x.to.part);
    text += fmt::format("  {:<10} starts at {:.5g} MU ({}): wire {} from {}\n", x.to.part, p ? p->setting : 0,
                        p ? p->signal : "", x.number, x.from.name());
  }
  return text;
}

std::string wires(const Wiring& w) {
  std::string text = "\nwires (from an output socket to an input socket; outputs may be stacked, each input takes one cable):\n";
  for (const Wire& x : w.wires) {
    const Part* from = w.find(x.from.part);
    const Part* to = w.find(x.to.part);
    const bool crosses = (from && to && from->machine != to->machine) || x.to.part.find(":GND") != std::string::npos;
    text += fmt::format("  {:>3}. {:<16} → {:<16}{}{}\n", x.number, x.from.name(), x.to.name(),
                        x.carries.empty() ? "" : "  " + x.carries, crosses ? "  (crosses between machines)" : "");
  }
  return text;
}

std::string scope(const Wiring& w) {
  std::string text = fmt::format(
      "\noscilloscope: time base {:.5g} s/div (the run in 10 div); trigger {} on CH{}, {}, at {:.5g} V\n",
      w.scope.seconds_per_div, w.scope.mode, w.scope.channel, w.scope.slope, w.scope.level_volts);
  for (const ScopeChannel& s : w.watch)
    text += fmt::format("  CH{} {:<8} at {:<10} {:.5g} V/div; 1 MU = {:.5g} V = {}{:.5g} {}\n", s.channel, s.signal,
                        s.at.name(), s.volts_per_div, s.volts_per_mu, s.sign < 0 ? "−" : "+", s.full_scale, s.unit);
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

std::string to_text(const MachinePatch& p) {
  const Allocation& a = p.allocation;
  const Wiring& w = p.wiring;
  return header(a, w) + counts(a) + elements(w) + potentiometers(a, w) + initial_conditions(w) + wires(w) +
         scope(w) + lines("notes", w.notes) + lines("options", a.options);
}

nlohmann::ordered_json to_json(const MachinePatch& p) {
  const Allocation& a = p.allocation;
  using nlohmann::ordered_json;
  ordered_json j;
  j["scene"] = a.scene;
  j["machine"] = a.machine.name;
  j["fits"] = a.fits();
  j["machines_needed"] = a.machines_needed;
  j["summary"] = fit_summary(a);
  for (const Count& c : a.counts)
    j["counts"].push_back({{"element", element_name(c.kind)}, {"needed", c.needed}, {"available", c.available}});
  j["shortfalls"] = a.shortfalls;
  j["input_overflows"] = a.input_overflows;
  j["notes"] = p.wiring.notes;
  j["options"] = a.options;
  j["wiring"] = wiring_json(p.wiring);
  return j;
}

}  // namespace gearpatch::patching
