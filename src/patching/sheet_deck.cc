#include "patching/sheet_deck.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <set>

#include "circuit/quality.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/numbers.h"
#include "machine/machine_file.h"
#include "patching/wiring_json.h"
#include "spice/deck_reader.h"

namespace gearpatch::patching {

namespace {

using circuit::Level;

/// A deck name for a jack or element: letters, digits and '_' only.
std::string spice_name(const std::string& text) {
  std::string s;
  for (char ch : text) {
    if (std::isalnum(static_cast<unsigned char>(ch))) s += ch;
    else if (ch == '+') s += "p";
    else if (ch == '-') s += "n";
    else if (ch == '>') s += "gt";
    else if (ch == '<') s += "lt";
    else s += '_';
  }
  return s;
}

/// Machine 1's ground jack "GND", another chained machine's "2:GND".
bool is_ground(const std::string& part) {
  return part == "GND" || (part.size() > 4 && part.compare(part.size() - 4, 4, ":GND") == 0);
}

/// A jack the sheet leaves unwired on purpose (a comparator's idle throw on a
/// machine whose switched-off inputs disconnect).
bool left_open(const Part& p, const std::string& jack) {
  return std::find(p.unwired.begin(), p.unwired.end(), jack) != p.unwired.end();
}

bool is_amplifier(const Part& p) { return p.kind == "integrator" || p.kind == "summer" || p.kind == "inverter"; }

/// The machine's comparator with its own switch: A + B > 0 routes >0 to OUT,
/// else <0. Ideal: a smooth choice over 1e-6 MU; hardware: the library's
/// Schmitt trigger and two analog switches behind a follower.
/// `held`: a comparator whose OUT feeds its own input holds its state (a
/// flip-flop); IC mode resets it, so until the run starts it reads A + B > 0.
/// At the ideal level its output follows with a lag of `lag` seconds (a
/// comparator's switching time): without one the loop is algebraic and
/// ngspice's Newton steps can land in the other stable state (measured on
/// extremes/lock-zero-backlash on model-1: the latch closed at t = 0.91 s
/// while set and reset both held, 1.35 % of full scale; with a lag of 1e-4
/// of the run 0.051 %). A lag far below ngspice's largest step lets the
/// trapezoidal rule ring it over (bild6c on classic, latched with backlash:
/// 55 % at 1e-6 of the run, 0.018 % at 1e-4). A set shorter than the lag
/// never closes the latch (random-25-017-self-locking's shallow catch: ω_s
/// 9.2 % of full scale at 1e-4 of the run on every machine, a pass at 3e-5).
/// `buffered`: OUT behind a follower (a throw patched to ground gives 0 V);
/// else OUT is the switch's common contact (a relay: an unwired throw opens).
std::string comparator_model(Level level, double unit, bool held, double lag, bool buffered) {
  const std::string name = held ? "gp_machine_comparator_held" : "gp_machine_comparator";
  const std::string sum = held ? "(time > 0 ? v(a) + v(b) : 1)" : "(v(a) + v(b))";
  if (level == Level::ideal)
    return fmt::format(
        "* the machine's comparator{3}, ideal: OUT = >0 while A + B > 0, else <0 (smooth over {1} V)\n"
        ".subckt {0} a b gt lt out\n"
        "Bsel {4} 0 V = v(lt) + (v(gt) - v(lt)) * (1 + tanh({2}/{1}))/2\n{5}"
        ".ends {0}\n",
        name, format_number(1e-6 * unit), sum, held ? " holding its state, reset to >0 in IC mode" : "",
        held ? "o" : "out",
        held ? fmt::format("Rlag o l 1\nClag l 0 {}\nEbuf out 0 l 0 1\n", format_number(lag)) : "");
  return fmt::format("* the machine's comparator{2}, hardware: Schmitt trigger on A + B, two switches{5}\n"
                     ".subckt {0} a b gt lt out\n"
                     "Bsum s 0 V = {1}\n"
                     "Xc s ctrl gp_comparator params: offset=0\n"
                     "Einv nctrl 0 ctrl 0 -1\n"
                     "Xs1 gt {3} ctrl gp_switch\n"
                     "Xs2 lt {3} nctrl gp_switch\n"
                     "{4}"
                     ".ends {0}\n",
                     name, sum, held ? " holding its state, reset to >0 in IC mode" : "", buffered ? "o" : "out",
                     buffered ? "Ro o 0 1e9\nEbuf out 0 o 0 1\n" : "", buffered ? ", output follower" : "");
}

std::string diode_model(Level level) {
  if (level == Level::hardware) return "";  // gp_d1n4148 of the shared models
  return "* a loose diode, ideal: 1 Ohm forward, 1e12 Ohm reverse\n"
         ".subckt gp_ideal_diode anode cathode\n"
         "Bd anode cathode I = max(v(anode,cathode), 0) + v(anode,cathode)*1e-12\n"
         ".ends gp_ideal_diode\n";
}

/// The jacks joined into nodes by the wires, and the checks a person's panel makes.
class Nets {
 public:
  /// `open_throws`: the jacks a part lists as unwired may stay so (the
  /// machine's idle throw is open, comparator idle_throw = open).
  Nets(const Wiring& w, bool open_throws) : w_(w), open_throws_(open_throws) {
    for (const Wire& wire : w.wires) {
      check_jack(wire, wire.from);
      check_jack(wire, wire.to);
      join(wire.from, wire.to);
      ++cables_[wire.to];
      ++cables_[wire.from];
    }
    check_parts();
    name_nodes();
  }

  std::string node(const Jack& j) const {
    const Jack r = root(j);
    auto it = names_.find(r);
    return it == names_.end() ? "n_" + spice_name(r.part + "_" + r.jack) : it->second;
  }
  bool wired(const Jack& j) const { return cables_.count(j) > 0; }

  /// The DC value (MU) an IC input takes: a reference, ground, or a potentiometer on one.
  double constant(const Jack& j, const std::string& what) const {
    const Jack r = root(j);
    for (const auto& [jack, parent] : parent_) {
      if (root(jack) != r) continue;
      if (is_ground(jack.part)) return 0;
      if (jack.part == "REF") return jack.jack == "+1" ? 1 : -1;
      if (jack.jack == "out")
        if (const Part* p = w_.find(jack.part); p && p->kind == "potentiometer")
          return p->setting * constant({p->label, "in"}, what);
    }
    throw Error(fmt::format("{} is wired to no reference, potentiometer on one, or ground", what));
  }

 private:
  void check_jack(const Wire& wire, const Jack& j) const {
    if (is_ground(j.part)) return;
    if (j.part == "REF") {
      if (j.jack != "+1" && j.jack != "-1")
        throw Error(fmt::format("wire {}: the references are REF +1 and REF -1, not {}", wire.number, j.name()));
      return;
    }
    const Part* p = w_.find(j.part);
    if (!p) throw Error(fmt::format("wire {}: no element {} on the sheet", wire.number, j.part));
    std::vector<std::string> jacks = required_jacks(*p), outs = output_jacks(*p);
    jacks.insert(jacks.end(), outs.begin(), outs.end());
    if (std::find(jacks.begin(), jacks.end(), j.jack) == jacks.end())
      throw Error(fmt::format("wire {}: {} has no jack {} on this sheet", wire.number, p->label, j.jack));
  }

  void check_parts() const {
    for (const Part& p : w_.parts)
      if (p.machine > 1 && !wired({fmt::format("{}:GND", p.machine), ""}))
        throw Error(fmt::format("{} is on machine {}, whose ground {}:GND is open: no wire joins it to GND of "
                                "machine 1", p.label, p.machine, p.machine));
    for (const Part& p : w_.parts) {
      for (const std::string& jack : required_jacks(p))
        if (!wired({p.label, jack}) && !(open_throws_ && left_open(p, jack)))
          throw Error(fmt::format("{} {} is open: no wire ends there", p.label, jack));
      for (const auto& [jack, weight] : p.inputs)
        if (cables_.at({p.label, jack}) > 1)
          throw Error(fmt::format("{} {} takes {} cables; an input jack takes one", p.label, jack,
                                  cables_.at({p.label, jack})));
      if (p.kind == "function_generator" || p.kind == "diode") continue;
      for (const std::string& jack : output_jacks(p))
        if (!wired({p.label, jack})) throw Error(fmt::format("{} {} goes nowhere: no wire starts there", p.label, jack));
    }
  }

  bool drives(const Jack& j) const {
    if (j.part == "REF" || is_ground(j.part)) return true;
    const Part* p = w_.find(j.part);
    if (!p) return false;
    const auto outs = output_jacks(*p);
    return std::find(outs.begin(), outs.end(), j.jack) != outs.end();
  }

  /// Each node its driver's name: ground "0", a reference ref_p1/ref_n1, the
  /// program's name where the element records one (a watched output is read there).
  void name_nodes() {
    std::map<Jack, Jack> driver;
    for (const auto& [jack, parent] : parent_) {
      if (!drives(jack)) continue;
      const Jack r = root(jack);
      if (auto it = driver.find(r); it != driver.end() && !(it->second == jack) &&
                                    !(is_ground(it->second.part) && is_ground(jack.part)))
        throw Error(fmt::format("the wires join two outputs, {} and {}: never join outputs", it->second.name(),
                                jack.name()));
      driver[r] = jack;
    }
    for (const auto& [r, jack] : driver) {
      std::string name = "n_" + spice_name(jack.part + "_" + jack.jack);
      if (is_ground(jack.part)) name = "0";
      else if (jack.part == "REF") name = jack.jack == "+1" ? "ref_p1" : "ref_n1";
      else if (const Part* p = w_.find(jack.part); p && !p->node.empty()) name = spice_name(p->node);
      names_[r] = name;
    }
  }

  void join(const Jack& a, const Jack& b) {
    parent_.emplace(a, a);
    parent_.emplace(b, b);
    const Jack ra = root(a), rb = root(b);
    if (!(ra == rb)) parent_[ra] = rb;
  }
  Jack root(Jack j) const {
    for (auto it = parent_.find(j); it != parent_.end() && !(it->second == j); it = parent_.find(j)) j = it->second;
    return j;
  }

  const Wiring& w_;
  bool open_throws_ = false;
  std::map<Jack, Jack> parent_;
  std::map<Jack, int> cables_;
  std::map<Jack, std::string> names_;
};

/// A comparator whose output is wired back to its input A or B: a flip-flop.
bool holds(const Part& p, const Nets& nets) {
  if (p.kind != "comparator") return false;
  const std::string out = nets.node({p.label, "OUT"});
  return out == nets.node({p.label, "A"}) || out == nets.node({p.label, "B"});
}

std::string amplifier_lines(const Part& p, const Nets& nets, Level level, const MachineProfile& m) {
  std::vector<circuit::Input> pins;
  std::string nodes;
  for (const auto& [jack, weight] : p.inputs) {
    pins.push_back({"in_" + jack, weight});
    nodes += nets.node({p.label, jack}) + " ";
  }
  const std::string subckt = "gp_" + spice_name(p.label);
  return "\n" + circuit::render_amplifier(level, p.kind == "integrator" ? "integrator" : "summer", subckt, pins, m) +
         fmt::format("X{} {}{} {}\n", spice_name(p.label), nodes, nets.node({p.label, "out"}), subckt);
}

std::string unit_lines(const Part& p, const Nets& nets, double unit) {
  const std::string n = spice_name(p.label);
  auto at = [&](const char* jack) { return nets.node({p.label, jack}); };
  if (p.function == "drive") {
    std::string text = fmt::format("V{} {} 0 PWL(", n, at("out"));
    const char* gap = "";
    for (const auto& [t, mu] : p.points) {
      text += fmt::format("{}{} {}", gap, format_number(t), format_number(mu * unit));
      gap = " ";
    }
    return text + ")\n";
  }
  if (p.function == "latched_switch")
    return fmt::format("Xsw_{0} {1} {2} {3} gp_switch\nXlatch_{0} {1} {2} {3} {4} gp_latch\n", n, at("in"), at("out"),
                       at("set"), at("reset"));
  if (p.function == "halfwave") return fmt::format("X{} {} {} {} gp_halfwave\n", n, at("in"), at("pos"), at("neg"));
  const auto& info = circuit::block_info(p.function);
  std::string text = fmt::format("X{} {} {} gp_{}", n, at("in"), at("out"), p.function);
  if (!info.param.empty() && !p.parameter.empty()) text += fmt::format(" params: {}={}", info.param, p.parameter);
  return text + "\n";
}

std::string library(const Wiring& w, const Nets& nets, Level level, const MachineProfile& m) {
  std::set<std::string> blocks;
  for (const Part& p : w.parts) {
    if (p.kind == "potentiometer") blocks.insert("potentiometer");
    if (p.kind == "comparator" && level == Level::hardware) blocks.insert({"comparator", "switch"});
    if (p.function == "latched_switch") blocks.insert({"switch", "latch"});
    else if (p.kind == "function_generator" && p.function != "drive") blocks.insert(p.function);
  }
  std::string text = "\n" + circuit::render_models(level, m);
  for (const std::string& b : blocks) text += "\n" + circuit::render_block(level, b, m);
  if (w.count("comparator")) text += "\n" + comparator_model(level, m.unit_volts, false, 0, m.idle_throw_grounded);
  if (std::any_of(w.parts.begin(), w.parts.end(), [&](const Part& p) { return holds(p, nets); }))
    text += "\n" + comparator_model(level, m.unit_volts, true, 3e-5 * w.beta * w.duration, m.idle_throw_grounded);
  if (w.count("diode")) text += "\n" + diode_model(level);
  return text;
}

std::string instances(const Wiring& w, const Nets& nets, Level level, const MachineProfile& m) {
  std::string text = "\n* The elements as the sheet wires them\n", amplifiers;
  for (const Part& p : w.parts) {
    const std::string n = spice_name(p.label);
    auto at = [&](const char* jack) { return nets.node({p.label, jack}); };
    if (is_amplifier(p)) amplifiers += amplifier_lines(p, nets, level, m);
    else if (p.kind == "potentiometer")
      text += fmt::format("X{} {} {} gp_potentiometer params: setting={}\n", n, at("in"), at("out"),
                          format_number(level == Level::hardware ? p.dial : p.setting));
    else if (p.kind == "comparator") {
      text += fmt::format("X{} {} {} {} {} {} {}\n", n, at("A"), at("B"), at(">0"), at("<0"), at("OUT"),
                          holds(p, nets) ? "gp_machine_comparator_held" : "gp_machine_comparator");
      for (const char* jack : {">0", "<0"})  // an unwired throw: only the leakage to ground fixes its node
        if (!nets.wired({p.label, jack}))
          text += fmt::format("R{}_{}_open {} 0 1e12\n", n, jack[0] == '>' ? "gt" : "lt", at(jack));
    }
    else if (p.kind == "diode")
      text += level == Level::hardware ? fmt::format("D{} {} {} gp_d1n4148\n", n, at("anode"), at("cathode"))
                                       : fmt::format("X{} {} {} gp_ideal_diode\n", n, at("anode"), at("cathode"));
    else text += unit_lines(p, nets, m.unit_volts);
  }
  return amplifiers + text;
}

std::string analysis(const Wiring& w, const Nets& nets, const circuit::TransientControl& t) {
  std::string text = "\n* References (the machine's +-1 MU)\n";
  text += fmt::format("Vref_p1 ref_p1 0 DC {}\nVref_n1 ref_n1 0 DC -{}\n", format_number(w.unit_volts),
                      format_number(w.unit_volts));
  text += "\n* Initial conditions: each integrator's output starts at minus its IC input\n";
  for (const Part& p : w.parts)
    if (p.kind == "integrator") {
      const double start = -nets.constant({p.label, "IC"}, p.label + " IC");
      text += fmt::format(".ic v({})={}\n", nets.node({p.label, "out"}), format_number(start * w.unit_volts));
    }
  const double stop = w.beta * w.duration;
  if (!(std::isfinite(stop) && stop > 0)) throw Error(fmt::format("the sheet's run lasts {} s of machine time", stop));
  text += fmt::format(
      "\n* Transient in machine time: {} s of real time x beta {}\n"
      ".options method={} reltol={} abstol=1e-12 vntol=1e-9 chgtol={} itl4=100\n"
      ".tran {} {} 0 {}\n.end\n",
      format_number(w.duration), format_number(w.beta), t.method, format_number(t.reltol), format_number(t.chgtol),
      format_number(stop / t.output_points), format_number(stop), format_number(stop / t.max_step_points));
  return text;
}

}  // namespace

std::string sheet_deck(const Wiring& w, Level level, const circuit::TransientControl& control) {
  MachineProfile m = load_machine_profile(w.machine);
  m.integrator_constant = w.k0;
  m.unit_volts = w.unit_volts;
  const Nets nets(w, !m.idle_throw_grounded);
  spice::DeckHeader h;
  h.level = std::string(circuit::level_name(level));
  h.scaling = w.scaling;
  h.beta = w.beta;
  h.unit_volts = w.unit_volts;
  h.integrator_constant = w.k0;
  h.quality = circuit::quality_name(control);
  const std::string head = fmt::format(
      "* gearpatch: the patch sheet of scene '{}' on {}, run as wired, level {}\n{}"
      "* every element is its kind's model from the machine profile; nodes are the sheet's numbered wires\n",
      w.scene, w.machine, circuit::level_name(level), spice::format_deck_header(h));
  return head + library(w, nets, level, m) + instances(w, nets, level, m) + analysis(w, nets, control);
}

}  // namespace gearpatch::patching

namespace gearpatch::patching {

SheetRun sheet_run(const std::string& path, std::optional<circuit::Level> level,
                   const circuit::TransientControl& control) {
  const Wiring w = wiring_from_json(read_file(path), path);
  try {
    return {sheet_deck(w, level.value_or(circuit::parse_level(w.level)), control), w.machine};
  } catch (const Error& e) {
    if (e.kind() != Error::Kind::input) throw;
    throw Error(fmt::format("{}: {}", path, e.what()));
  }
}

}  // namespace gearpatch::patching
