#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <set>
#include <tuple>

#include "common/error.h"
#include "machine/machine_file.h"
#include "patching/allocation.h"
#include "patching/wiring.h"

namespace gearpatch::patching {

std::string Jack::name() const { return jack.empty() ? part : part + " " + jack; }

const Part* Wiring::find(const std::string& label) const {
  for (const Part& p : parts)
    if (p.label == label) return &p;
  return nullptr;
}

int Wiring::count(const std::string& kind) const {
  return static_cast<int>(std::count_if(parts.begin(), parts.end(), [&](const Part& p) { return p.kind == kind; }));
}

std::vector<std::string> required_jacks(const Part& p) {
  std::vector<std::string> jacks;
  for (const auto& [jack, weight] : p.inputs) jacks.push_back(jack);
  if (p.kind == "integrator") jacks.push_back("IC");
  if (p.kind == "potentiometer") jacks.push_back("in");
  if (p.kind == "comparator") jacks.insert(jacks.end(), {"A", "B", ">0", "<0"});
  if (p.kind == "diode") jacks.insert(jacks.end(), {"anode", "cathode"});
  if (p.kind == "function_generator") {
    if (p.function == "latched_switch") jacks.insert(jacks.end(), {"in", "set", "reset"});
    else if (p.function != "drive") jacks.push_back("in");
  }
  return jacks;
}

std::vector<std::string> output_jacks(const Part& p) {
  if (p.kind == "diode") return {};
  if (p.kind == "comparator") return {"OUT"};
  if (p.function == "halfwave") return {"pos", "neg"};
  return {"out"};
}

namespace {

const Jack ground{"GND", ""};
Jack reference(double sign) { return {"REF", sign > 0 ? "+1" : "-1"}; }

/// A comparator block of the program: what it compares and where its threshold comes from.
struct ComparatorUse {
  std::string label, in;
  Jack threshold;
  int switches = 0;  ///< switches already taken from it and its copies
};

/// Builds the wiring part by part (phase one, every output's jack known),
/// then wire by wire (phase two).
class Wirer {
 public:
  explicit Wirer(const circuit::Circuit& c) : c_(c) {
    w_.scene = c.scene;
    w_.machine = c.machine.name;
    w_.level = std::string(circuit::level_name(c.level));
    w_.scaling = c.scaling;
    w_.beta = c.beta;
    w_.duration = c.duration;
    w_.unit_volts = c.machine.unit_volts;
    w_.k0 = c.machine.integrator_constant;
    w_.k0_switch = c.machine.integrator_constant_label();
    for (const auto& [name, value] : c.parameters) params_[name] = value;
  }

  Wiring run() {
    sources();
    for (const auto& a : c_.amplifiers)
      if (!is_inverter(a)) amplifier(a);
    for (const auto& b : c_.blocks)
      if (b.block == circuit::BlockKind::comparator) comparator(b);
    for (const auto& a : c_.amplifiers)
      if (is_inverter(a)) amplifier(a);
    for (const auto& b : c_.blocks)
      if (b.block != circuit::BlockKind::comparator) function_block(b);
    for (auto& step : later_) step();
    for (const auto& a : c_.amplifiers) inputs(a);
    initial_conditions();
    watch();
    common_ground();
    return std::move(w_);
  }

 private:

  Part& take(ElementKind kind, const std::string& role, const std::string& node = "") {
    const int n = ++used_[kind], count = element_count(c_.machine, kind);
    auto type = c_.machine.elements.find(kind);
    const std::string prefix =
        type == c_.machine.elements.end() || type->second.label.empty() ? element_name(kind) : type->second.label;
    Part p;
    p.kind = element_name(kind);
    p.machine = count > 0 ? (n - 1) / count + 1 : 0;
    if (p.machine > c_.machine.chain) p.machine = 0;
    const int number = count > 0 && p.machine > 0 ? (n - 1) % count + 1 : n;
    p.label = (p.machine > 1 ? fmt::format("{}:", p.machine) : p.machine == 0 ? std::string("missing:") : "") +
              prefix + std::to_string(number);
    p.role = filled(role);
    p.node = node;
    p.signal = node.empty() ? "" : c_.signal_of(node);
    w_.parts.push_back(std::move(p));
    if (!node.empty()) driver_[node] = {w_.parts.back().label, output_jacks(w_.parts.back()).front()};
    return w_.parts.back();
  }

  /// A comment of the program with each "{setting}" replaced by its value, so
  /// that the sheet holds numbers, never a placeholder.
  std::string filled(std::string text) const {
    for (std::size_t open = text.find('{'); open != std::string::npos; open = text.find('{', open)) {
      const std::size_t close = text.find('}', open);
      if (close == std::string::npos) break;
      const std::string name = text.substr(open + 1, close - open - 1);
      const auto setting = parse_setting(name);
      const auto it = setting ? params_.find(*setting) : params_.end();
      const std::string value = it == params_.end() ? name : fmt::format("{} = {:.5g}", name, it->second);
      text.replace(open, close - open + 1, value);
    }
    return text;
  }

  Part& part(const std::string& label) {
    for (Part& p : w_.parts)
      if (p.label == label) return p;
    throw Error("internal: no part " + label, Error::Kind::internal);
  }

  Jack out_of(const std::string& node) const {
    auto it = driver_.find(node);
    if (it == driver_.end()) throw Error("internal: nothing drives node " + node, Error::Kind::internal);
    return it->second;
  }

  /// What a jack carries, in the paper's variables.
  std::string carried(const Jack& from) const {
    if (from.part == "REF") return from.jack == "+1" ? "+1 MU" : "−1 MU";
    if (from.part == "GND") return "0";
    const Part* p = w_.find(from.part);
    return p ? p->signal : "";
  }

  void wire(const Jack& from, const Jack& to) {
    w_.wires.push_back({static_cast<int>(w_.wires.size()) + 1, from, to, carried(from)});
  }

  /// The next free input jack of `weight` on an amplifier ("10a", "10b" …).
  Jack input_jack(const std::string& label, int weight) {
    Part& p = part(label);
    const int used = static_cast<int>(
        std::count_if(p.inputs.begin(), p.inputs.end(), [&](const auto& in) { return in.second == weight; }));
    const std::string jack = fmt::format("{}{}", weight, static_cast<char>('a' + used));
    p.inputs.emplace_back(jack, weight);
    return {label, jack};
  }

  /// A potentiometer from `from` at `value`: one per source and setting on a
  /// buffered machine (its follower feeds every input), else one per input.
  Jack potentiometer(const Jack& from, const std::string& name, double value, double dial, const std::string& role) {
    const std::string key = from.name() + "|" + name + "|" + fmt::format("{}", value);
    if (c_.machine.potentiometers_buffered)
      if (auto it = shared_.find(key); it != shared_.end()) return {it->second, "out"};
    Part& p = take(ElementKind::potentiometer, role);
    p.setting = value;
    p.dial = c_.machine.potentiometers_buffered ? value : dial;
    p.setting_name = name;
    p.signal = fmt::format("{:.5g} × ({})", value, carried(from));
    const std::string label = p.label;
    shared_[key] = label;
    wire(from, {label, "in"});
    return {label, "out"};
  }

  double dial_of(Setting s, double value) const {
    auto it = c_.dial_settings.find(s);
    return it == c_.dial_settings.end() ? value : it->second;
  }

  /// ±value from the references: a wire for 1 MU, else a potentiometer.
  Jack constant(double value, const std::string& name, const std::string& role) {
    if (value == 0) return ground;
    if (is_one(value)) return reference(value);
    return potentiometer(reference(value), name, std::abs(value), std::abs(value), role);
  }

  void sources() {
    for (const auto& [node, source_value] : c_.sources) {
      const double value = source_value;  // a copy: clang 14 lets no lambda capture a structured binding
      if (driver_.count(node)) continue;
      if (is_one(value)) {
        driver_[node] = reference(value);
        continue;
      }
      Part& p = take(ElementKind::potentiometer, fmt::format("{}: {}", node, c_.signal_of(node)), node);
      p.setting = p.dial = std::abs(value);
      p.setting_name = "alpha2_source";
      const std::string label = p.label;
      later_.push_back([this, label, value] { wire(reference(value), {label, "in"}); });
    }
    for (const auto& [node, points] : c_.pwl_sources) {
      Part& p = take(ElementKind::function_generator,
                     fmt::format("the drive torque over machine time, {} points", points.size()), node);
      p.function = "drive";
      p.points = points;
    }
  }

  void amplifier(const circuit::Amplifier& a) {
    ElementKind kind = a.integrator ? ElementKind::integrator : ElementKind::summer;
    if (is_inverter(a) && used_[ElementKind::inverter] < element_count(c_.machine, ElementKind::inverter))
      kind = ElementKind::inverter;
    else if (is_inverter(a) && used_[ElementKind::summer] >= element_count(c_.machine, ElementKind::summer) &&
             element_count(c_.machine, ElementKind::inverter) > 0)
      kind = ElementKind::inverter;  // on the next chained machine
    take(kind, a.comment, a.out);
  }

  /// The threshold a comparator block compares with, as input B carries it (negated).
  Jack threshold(const circuit::FunctionBlock& b) {
    std::string name = "offset";
    double offset = 0;
    if (b.parameter.size() > 2 && b.parameter.front() == '{') {
      name = b.parameter.substr(1, b.parameter.size() - 2);
      offset = params_.at(parse_setting(name).value());
    } else if (!b.parameter.empty()) {
      offset = std::stod(b.parameter);
    }
    if (on_twist(b)) return constant(-offset, "a_contact", fmt::format(
        "contact threshold on Δφ: a + the comparator's hysteresis + the dead zone's corner = {:.5g} MU, into B "
        "(settings' {} is the threshold on Δφ')",
        offset, name));
    return constant(-offset, name, fmt::format("threshold {} = {:.5g} MU of the comparators, into B", name, offset));
  }

  /// A contact comparator that watches the twist itself against the dead
  /// zone's threshold (the hardware circuit's choice), not Δφ' against δ: its
  /// threshold is not the settings' delta, so the sheet gives it its own name.
  static bool on_twist(const circuit::FunctionBlock& b) {
    return (b.nodes[0] == "x" || b.nodes[0] == "x_n") && b.parameter.size() > 2 && b.parameter.front() == '{';
  }

  void comparator(const circuit::FunctionBlock& b) {
    std::string role = b.comment;
    if (on_twist(b))
      if (const auto at = role.find(b.parameter); at != std::string::npos) role.replace(at, b.parameter.size(), "a_contact");
    const Part& p = take(ElementKind::comparator, role);
    uses_[b.nodes[1]] = {p.label, b.nodes[0], {}, 0};
    const std::string ctrl = b.nodes[1];
    later_.push_back([this, ctrl, b] {
      ComparatorUse& u = uses_.at(ctrl);
      u.threshold = threshold(b);
      wire(out_of(u.in), {u.label, "A"});
      wire(u.threshold, {u.label, "B"});
    });
  }

  /// A comparator's switch routing `signal` (else ground) to OUT: the
  /// comparator's own for its first use, then a copy wired to the same inputs.
  /// On a machine whose idle throw is open (a relay contact) ground is left
  /// unwired, so that the switched-off input disconnects, as the deck models it.
  Jack switched(const std::string& ctrl, const Jack& signal, const Jack& otherwise = ground) {
    ComparatorUse& u = uses_.at(ctrl);
    std::string label = u.label;
    if (u.switches++ > 0) {
      label = take(ElementKind::comparator, fmt::format("a second switch for {}: the same inputs A and B", u.label))
                  .label;
      wire(out_of(u.in), {label, "A"});
      wire(u.threshold, {label, "B"});
    }
    wire(signal, {label, ">0"});
    const bool open = otherwise == ground && !c_.machine.idle_throw_grounded;
    if (open) part(label).unwired.push_back("<0");
    else wire(otherwise, {label, "<0"});
    part(label).signal =
        fmt::format("{} while A + B > 0, else {}", carried(signal), open ? "open (<0 unwired)" : carried(otherwise));
    return {label, "OUT"};
  }

  void function_block(const circuit::FunctionBlock& b) {
    const std::string kind = circuit::to_string(b.block);
    auto it = c_.machine.realisations.find(kind);
    const Realisation parts = it == c_.machine.realisations.end() ? Realisation{} : it->second;
    auto has = [&](ElementKind k) {
      return std::any_of(parts.begin(), parts.end(), [&](const auto& e) { return e.second == k; });
    };
    if (b.block == circuit::BlockKind::dead_zone && has(ElementKind::diode)) return diode_dead_zone(b);
    if (b.block == circuit::BlockKind::dead_zone && has(ElementKind::comparator)) return comparator_dead_zone(b);
    if (b.block == circuit::BlockKind::limiter && has(ElementKind::comparator))
      return std::stod(b.parameter) <= 0.02 ? comparator_limiter(b) : comparator_wide_limiter(b);
    if (b.block == circuit::BlockKind::abs && !negated(b.nodes[0]).empty()) {
      if (has(ElementKind::diode) && has(ElementKind::summer)) return diode_abs(b);
      if (has(ElementKind::comparator)) return comparator_abs(b);
    }
    if (b.block == circuit::BlockKind::halfwave && has(ElementKind::comparator)) return comparator_halfwave(b);
    if (b.block == circuit::BlockKind::halfwave && has(ElementKind::diode) && has(ElementKind::summer))
      return diode_halfwave(b);
    unit(b);
  }

  /// pos = −max(in, 0) and neg = −min(in, 0): two comparators on in, each
  /// switch picking −in on its side and ground on the other; −in from an
  /// inverter of the program, else from an amplifier of its own.
  void comparator_halfwave(const circuit::FunctionBlock& b) {
    std::string minus = negated(b.nodes[0]);
    if (minus.empty()) {
      minus = b.nodes[0] + "_neg";
      const bool inverter = used_[ElementKind::inverter] < element_count(c_.machine, ElementKind::inverter);
      const std::string label =
          take(inverter ? ElementKind::inverter : ElementKind::summer, "−in for the half-wave " + b.name, minus).label;
      part(label).signal = "−(" + c_.signal_of(b.nodes[0]) + ")";
      later_.push_back([this, b, label] { wire(out_of(b.nodes[0]), input_jack(label, 1)); });
    }
    // an output the program leaves unused takes no comparator
    const std::string pos = used(b.nodes[1]) ? take(ElementKind::comparator, b.comment + ": pos", b.nodes[1]).label : "";
    const std::string neg = used(b.nodes[2]) ? take(ElementKind::comparator, b.comment + ": neg", b.nodes[2]).label : "";
    later_.push_back([this, b, minus, pos, neg] {
      for (const auto& [label, above, below] :
           {std::tuple{pos, out_of(minus), ground}, std::tuple{neg, ground, out_of(minus)}}) {
        if (label.empty()) continue;
        wire(out_of(b.nodes[0]), {label, "A"});
        wire(ground, {label, "B"});
        wire(above, {label, ">0"});
        wire(below, {label, "<0"});
      }
    });
  }

  /// pos = −max(in, 0) and neg = −min(in, 0): each side a diode into a
  /// summer's input, whose virtual ground lets it pass only its side's
  /// current (pos: anode at in; neg: cathode at in); an output the program
  /// leaves unused takes no diode and no summer.
  void diode_halfwave(const circuit::FunctionBlock& b) {
    std::vector<std::tuple<std::string, std::string, bool>> sides;  // summer, diode, anode at in
    for (const bool pos : {true, false}) {
      const std::string& node = b.nodes[pos ? 1 : 2];
      if (!used(node)) continue;
      const std::string what = pos ? "pos = −max(in, 0)" : "neg = −min(in, 0)";
      const std::string sum = take(ElementKind::summer, b.comment + ": " + what, node).label;
      const std::string d = take(ElementKind::diode, pos ? "half-wave: passes in > 0, anode at in"
                                                         : "half-wave: passes in < 0, cathode at in").label;
      part(d).signal = (pos ? "max(" : "min(") + c_.signal_of(b.nodes[0]) + ", 0)";
      sides.emplace_back(sum, d, pos);
    }
    later_.push_back([this, b, sides] {
      for (const auto& [sum, d, pos] : sides) {
        wire(out_of(b.nodes[0]), {d, pos ? "anode" : "cathode"});
        wire({d, pos ? "cathode" : "anode"}, input_jack(sum, 1));
      }
    });
  }

  /// Whether an amplifier or block takes the node.
  bool used(const std::string& node) const {
    for (const auto& a : c_.amplifiers)
      for (const auto& first : a.inputs)
        for (const circuit::AmplifierInput* in : circuit::paths(first))
          if (in->from == node || in->switched_by == node || in->released_by == node) return true;
    for (const auto& b : c_.blocks)
      if (!b.nodes.empty() && b.nodes[0] == node) return true;
    return false;
  }

  /// The node carrying −node, if the program has one (an inverter's other side).
  std::string negated(const std::string& node) const {
    for (const auto& a : c_.amplifiers)
      if (is_inverter(a)) {
        if (a.out == node) return a.inputs[0].from;
        if (a.inputs[0].from == node) return a.out;
      }
    return "";
  }

  double dead_zone_threshold() const { return params_.at(Setting::a); }

  /// dz = max(x, a) + min(x, −a): two diode gates into one summer (the
  /// summer's input resistors pull each gate towards 0 V, so each passes the
  /// larger, resp. smaller, of its two anodes', resp. cathodes' voltages).
  void diode_dead_zone(const circuit::FunctionBlock& b) {
    const std::string sum = take(ElementKind::summer, b.comment, b.nodes[1]).label;
    std::vector<std::string> d;
    for (int i = 0; i < 4; ++i)
      d.push_back(take(ElementKind::diode, i < 2 ? "upper gate: passes max(x, a)" : "lower gate: passes min(x, −a)")
                      .label);
    for (int i = 0; i < 4; ++i)
      part(d[i]).signal = i < 2 ? "max(" + c_.signal_of(b.nodes[0]) + ", +a)" : "min(" + c_.signal_of(b.nodes[0]) + ", −a)";
    later_.push_back([this, b, sum, d] {
      const double a = dead_zone_threshold();
      const Jack up = potentiometer(reference(1), "a", a, dial_of(Setting::a, a), "dead-zone threshold +a");
      const Jack down = potentiometer(reference(-1), "a", a, dial_of(Setting::a, a), "dead-zone threshold −a");
      const Jack x = out_of(b.nodes[0]);
      wire(x, {d[0], "anode"});
      wire(up, {d[1], "anode"});
      wire({d[0], "cathode"}, input_jack(sum, 1));
      wire({d[1], "cathode"}, {d[0], "cathode"});
      wire(x, {d[2], "cathode"});
      wire(down, {d[3], "cathode"});
      wire({d[2], "anode"}, input_jack(sum, 1));
      wire({d[3], "anode"}, {d[2], "anode"});
    });
  }

  /// dz = max(x, a) + min(x, −a) with two comparators' switches picking x or the bias.
  void comparator_dead_zone(const circuit::FunctionBlock& b) {
    const std::string sum = take(ElementKind::summer, b.comment, b.nodes[1]).label;
    const std::string upper = take(ElementKind::comparator, "dead zone: OUT = max(x, a)").label;
    const std::string lower = take(ElementKind::comparator, "dead zone: OUT = min(x, −a)").label;
    later_.push_back([this, b, sum, upper, lower] {
      const double a = dead_zone_threshold();
      const Jack up = potentiometer(reference(1), "a", a, dial_of(Setting::a, a), "dead-zone threshold +a");
      const Jack down = potentiometer(reference(-1), "a", a, dial_of(Setting::a, a), "dead-zone threshold −a");
      const Jack x = out_of(b.nodes[0]);
      for (const auto& [label, bias, above, below] :
           {std::tuple{upper, down, x, up}, std::tuple{lower, up, down, x}}) {
        wire(x, {label, "A"});
        wire(bias, {label, "B"});
        wire(above, {label, ">0"});
        wire(below, {label, "<0"});
        wire({label, "OUT"}, input_jack(sum, 1));
      }
    });
  }

  /// −sign(in): the comparator's switch picks the −1 or the +1 reference (a
  /// limiter whose band is a few hundredths of 1 MU or less: wider ones, the
  /// Stribeck generator's, are units).
  void comparator_limiter(const circuit::FunctionBlock& b) {
    switch_on_sign(b, [] { return std::pair(reference(-1), reference(1)); });
  }

  /// A comparator of the block's input against ground whose switch passes
  /// the first of `passes()` (made once every driver is known) while the
  /// input is positive, else the second.
  void switch_on_sign(const circuit::FunctionBlock& b, std::function<std::pair<Jack, Jack>()> passes) {
    const std::string label = take(ElementKind::comparator, b.comment, b.nodes[1]).label;
    later_.push_back([this, b, label, passes] {
      const auto [above, below] = passes();
      wire(out_of(b.nodes[0]), {label, "A"});
      wire(ground, {label, "B"});
      wire(above, {label, ">0"});
      wire(below, {label, "<0"});
    });
  }

  /// −clip(in/band) for a band wider than a comparator's step (the Stribeck
  /// generator's, the hardware lock characteristic): two comparators clip in
  /// to ±band (each threshold and each clip level a potentiometer on a
  /// reference), a summer's weight-10 inputs amplify the clipped signal by
  /// 1/band, so no amplifier leaves ±1 MU.
  void comparator_wide_limiter(const circuit::FunctionBlock& b) {
    const std::string upper = take(ElementKind::comparator, b.comment + ": in above +band gives +band").label;
    const std::string lower = take(ElementKind::comparator, b.comment + ": in below −band gives −band, else in").label;
    const std::string gain = take(ElementKind::summer, b.comment, b.nodes[1]).label;
    part(upper).signal = "clip(" + c_.signal_of(b.nodes[0]) + ", ±band)";
    part(lower).signal = "max(" + c_.signal_of(b.nodes[0]) + ", −band)";
    later_.push_back([this, b, upper, lower, gain] {
      const double band = std::stod(b.parameter), g = 1 / band;
      const int inputs = static_cast<int>(std::ceil(g / 10 - 1e-9));
      const std::string role = fmt::format("limiter band {:.5g} MU", band);
      const Jack in = out_of(b.nodes[0]);
      const Jack plus = constant(band, "band", role), minus = constant(-band, "band", role);
      wire(in, {upper, "A"});
      wire(minus, {upper, "B"});
      wire(plus, {upper, ">0"});
      wire({lower, "OUT"}, {upper, "<0"});
      wire(in, {lower, "A"});
      wire(plus, {lower, "B"});
      wire(in, {lower, ">0"});
      wire(minus, {lower, "<0"});
      const double setting = g / (10.0 * inputs);
      const Jack scaled = is_one(setting) ? Jack{upper, "OUT"}
                                          : potentiometer({upper, "OUT"}, "gain", setting, setting,
                                                          fmt::format("limiter gain 1/band = {:.5g}: {:.5g} into {} "
                                                                      "weight-10 input{}", g, setting, inputs,
                                                                      inputs > 1 ? "s" : ""));
      feed(gain, std::vector<std::pair<Jack, int>>(static_cast<std::size_t>(inputs), {scaled, 10}));
    });
  }

  /// How many inputs of `weight` one element of the part's kind has on the panel.
  int jacks_of(const Part& p, int weight) const {
    for (const auto& [kind, type] : c_.machine.elements)
      if (element_name(kind) == p.kind)
        return static_cast<int>(std::count(type.inputs.begin(), type.inputs.end(), weight));
    return 0;
  }

  /// How many inputs of each weight take their source directly: all where
  /// the panel has enough jacks of that weight, else one fewer than it has,
  /// the last jack taking the sum of the rest (see feed).
  std::map<int, int> direct_jacks(const std::string& target, const std::vector<int>& weights) {
    std::map<int, int> needed;
    for (int weight : weights) ++needed[weight];
    for (auto& [weight, n] : needed)
      if (const int offered = jacks_of(part(target), weight); offered > 0 && n > offered) n = offered - 1;
    return needed;
  }

  /// Wires a source into the next free input of its weight on `target`, or,
  /// once the direct jacks are spent, keeps it in `rest`: the sources the
  /// panel has no jack for, which feed() wires as one sum.
  void to_input(const std::string& target, const Jack& from, int weight, std::map<int, int>& direct,
                std::map<int, std::vector<Jack>>& rest) {
    if (direct[weight]-- > 0) wire(from, input_jack(target, weight));
    else rest[weight].push_back(from);
  }

  /// Wires each (source, weight) into the next free input of that weight on
  /// `target`. Where the panel has fewer inputs of a weight than the program
  /// needs, the last jack takes the sum of the rest, made by summers on
  /// weight-1 inputs (and the sign restored), so that every jack named exists.
  void feed(const std::string& target, const std::vector<std::pair<Jack, int>>& sources) {
    std::vector<int> weights;
    for (const auto& source : sources) weights.push_back(source.second);
    std::map<int, int> direct = direct_jacks(target, weights);
    std::map<int, std::vector<Jack>> rest;
    for (const auto& [from, weight] : sources) to_input(target, from, weight, direct, rest);
    sum_rest(target, rest);
  }

  void sum_rest(const std::string& target, const std::map<int, std::vector<Jack>>& rest) {
    for (const auto& [weight, from] : rest) wire(positive_sum(from, target), input_jack(target, weight));
  }

  /// A jack carrying +Σ of the sources: a summer's −Σ turned round by an inverter.
  Jack positive_sum(const std::vector<Jack>& from, const std::string& target) {
    if (from.size() == 1) return from.front();
    const Jack minus = negative_sum(from, target);
    const bool inverter = used_[ElementKind::inverter] < element_count(c_.machine, ElementKind::inverter);
    const std::string label =
        take(inverter ? ElementKind::inverter : ElementKind::summer, "turns the sum for " + target + " round").label;
    part(label).signal = "+Σ into " + target;
    wire(minus, input_jack(label, 1));
    return {label, "out"};
  }

  /// A summer's output −Σ of the sources on its weight-1 inputs; more sources
  /// than it has take a further +Σ on its last input.
  Jack negative_sum(const std::vector<Jack>& from, const std::string& target) {
    const std::string label = take(ElementKind::summer, "sums inputs " + target + " has no jack for").label;
    part(label).signal = "−Σ into " + target;
    const std::size_t room = static_cast<std::size_t>(std::max(2, jacks_of(part(label), 1)));
    const std::size_t direct = from.size() <= room ? from.size() : room - 1;
    for (std::size_t k = 0; k < direct; ++k) wire(from[k], input_jack(label, 1));
    if (direct < from.size())
      wire(positive_sum({from.begin() + static_cast<std::ptrdiff_t>(direct), from.end()}, target),
           input_jack(label, 1));
    return {label, "out"};
  }

  /// −|in| = −(relu(in) + relu(−in)): each diode passes its side's current into the summer.
  void diode_abs(const circuit::FunctionBlock& b) {
    const std::string sum = take(ElementKind::summer, b.comment, b.nodes[1]).label;
    const std::string d1 = take(ElementKind::diode, "passes the positive half").label;
    const std::string d2 = take(ElementKind::diode, "passes the negative half").label;
    part(d1).signal = "max(" + c_.signal_of(b.nodes[0]) + ", 0)";
    part(d2).signal = "max(" + c_.signal_of(negated(b.nodes[0])) + ", 0)";
    later_.push_back([this, b, sum, d1, d2] {
      wire(out_of(b.nodes[0]), {d1, "anode"});
      wire({d1, "cathode"}, input_jack(sum, 1));
      wire(out_of(negated(b.nodes[0])), {d2, "anode"});
      wire({d2, "cathode"}, input_jack(sum, 1));
    });
  }

  /// −|in|: the switch picks −in while in > 0, else in.
  void comparator_abs(const circuit::FunctionBlock& b) {
    switch_on_sign(b, [this, b] { return std::pair(out_of(negated(b.nodes[0])), out_of(b.nodes[0])); });
  }

  /// A block the machine has as a ready unit (a diode function generator), or
  /// one this sheet draws as a unit: its model is the block library's.
  void unit(const circuit::FunctionBlock& b) {
    Part& p = take(ElementKind::function_generator, b.comment, b.nodes[1]);
    p.function = circuit::to_string(b.block);
    p.parameter = b.parameter;
    if (p.parameter.size() > 2 && p.parameter.front() == '{')  // a setting: the unit is set to its value
      p.parameter = fmt::format("{:.5g}", params_.at(parse_setting(p.parameter.substr(1, p.parameter.size() - 2)).value()));
    else if (!p.parameter.empty())
      p.parameter = fmt::format("{:.5g}", std::stod(p.parameter));
    if (b.block == circuit::BlockKind::halfwave) p.node.clear();
    const std::string label = p.label;
    if (b.block == circuit::BlockKind::halfwave) {
      driver_[b.nodes[1]] = {label, "pos"};
      driver_[b.nodes[2]] = {label, "neg"};
    }
    later_.push_back([this, b, label] { wire(out_of(b.nodes[0]), {label, "in"}); });
    const bool ready = c_.machine.realisations.count(p.function) &&
                       c_.machine.realisations.at(p.function) == Realisation{{1, ElementKind::function_generator}};
    w_.notes.push_back(fmt::format("{} is {} {} unit{}{}", label, ready ? "a ready" : "drawn as one", p.function,
                                   p.parameter.empty() ? "" : ", set to " + p.parameter,
                                   ready ? "" : ": this sheet does not draw its elements inside"));
  }

  /// The lock's switch with a latch in parallel, element by element: a
  /// summer forms −(set − reset) from the two decisions (±1 MU each); a
  /// holding comparator adds its own output to that, so it turns to −1 MU
  /// once set (engaged, not stopped), to +1 MU once reset (stopped, not
  /// engaged) and keeps its state in between; a second comparator on the same
  /// inputs passes the signal while latched, else the lock's own switch
  /// (switched by `lock_switch`; `set` is its own comparator where it differs).
  Jack latched(const std::string& lock_switch, const std::string& set, const std::string& reset,
               const Jack& signal) {
    const Jack lock = switched(lock_switch, signal);
    const std::string sum = take(ElementKind::summer, "lock latch: −(set − reset), each a decision of ±1 MU").label;
    part(sum).signal = "−(set − reset)";
    const Jack engaged = decision(set), not_stopped = switched(reset, reference(-1), reference(1));
    const std::string hold =
        take(ElementKind::comparator, "lock latch: holds its state (OUT on B): −1 MU once set, +1 MU once reset; "
                                      "+1 MU in IC mode")
            .label;
    const std::string pass = take(ElementKind::comparator, "lock latch: the signal while latched, else the lock's "
                                                           "switch; the same inputs as " + hold)
                                 .label;
    part(hold).signal = "−1 MU while latched, else +1 MU";
    wire(engaged, input_jack(sum, 1));
    wire(not_stopped, input_jack(sum, 1));
    wire({sum, "out"}, {hold, "A"});
    wire({hold, "OUT"}, {hold, "B"});
    wire(reference(1), {hold, ">0"});
    wire(reference(-1), {hold, "<0"});
    wire({sum, "out"}, {pass, "A"});
    wire({hold, "OUT"}, {pass, "B"});
    wire(lock, {pass, ">0"});
    wire(signal, {pass, "<0"});
    part(pass).signal = carried(signal) + " while latched, else the lock's switch";
    return {pass, "OUT"};
  }

  /// A comparator's decision as ±1 MU: a copy of it whose switch picks the references.
  Jack decision(const std::string& ctrl) { return switched(ctrl, reference(1), reference(-1)); }

  void inputs(const circuit::Amplifier& a) {
    const std::string target = out_of(a.out).part;
    std::vector<int> weights;
    for (const circuit::AmplifierInput& in : a.inputs) weights.push_back(in.weight);
    std::map<int, int> direct = direct_jacks(target, weights);
    std::map<int, std::vector<Jack>> rest;
    for (const circuit::AmplifierInput& in : a.inputs) to_input(target, path(in), in.weight, direct, rest);
    sum_rest(target, rest);
  }

  /// The jack an input path ends at: its potentiometer, then its switch,
  /// whose idle throw takes the chained path (AmplifierInput::otherwise) if any.
  Jack path(const circuit::AmplifierInput& in) {
    Jack from = out_of(in.from);
    if (in.potentiometer) {
      const double value = params_.at(*in.potentiometer);
      if (!is_one(value))
        from = potentiometer(from, to_string(*in.potentiometer), value, dial_of(*in.potentiometer, value),
                             fmt::format("{} = {:.5g}", to_string(*in.potentiometer), value));
    }
    if (!in.released_by.empty())
      return latched(in.switched_by, in.latched_by.empty() ? in.switched_by : in.latched_by, in.released_by, from);
    if (in.switched_by.empty()) return from;
    if (in.otherwise.empty()) return switched(in.switched_by, from);
    const Jack other = path(in.otherwise.front());
    return switched(in.switched_by, from, other);
  }

  void initial_conditions() {
    for (const auto& [node, setting] : c_.initial_conditions) {
      const double value = setting ? params_.at(*setting) : 0;
      // every amplifier inverts, in IC mode too: the IC input takes the negated value
      const Jack from = constant(-value, setting ? to_string(*setting) : "",
                                 fmt::format("initial value {} = {:.5g} MU", setting ? to_string(*setting) : "", value));
      part(out_of(node).part).setting = value;
      wire(from, {out_of(node).part, "IC"});
    }
  }

  /// Chained machines share one ground: the first wire joins machine 1's
  /// ground jack to each other machine's.
  void common_ground() {
    int machines = 1;
    for (const Part& p : w_.parts) machines = std::max(machines, p.machine);
    std::vector<Wire> grounds;
    for (int m = 2; m <= machines; ++m) grounds.push_back({0, ground, {fmt::format("{}:GND", m), ""}, "0 (common ground)"});
    if (grounds.empty()) return;
    w_.wires.insert(w_.wires.begin(), grounds.begin(), grounds.end());
    for (std::size_t k = 0; k < w_.wires.size(); ++k) w_.wires[k].number = static_cast<int>(k) + 1;
  }

  /// One oscilloscope channel per compared signal at the finest 1-2-5 volts
  /// per division holding its simulated peak (at least 0.05 MU, at most 1 MU)
  /// in ±4 divisions, so that a scope's 8-bit steps stay fine; the time base holds the run in
  /// ten; the trigger catches the run's start on the first signal that leaves
  /// a nonzero initial value (else the first channel leaving 0).
  void watch() {
    for (const auto& [signal, probe] : c_.probes) {
      ScopeChannel s;
      s.channel = static_cast<int>(w_.watch.size()) + 1;
      s.signal = gearpatch::to_string(signal);
      s.at = out_of(probe.node);
      s.node = probe.node;
      s.full_scale = probe.full_scale;
      s.unit = gearpatch::unit(signal);
      s.volts_per_mu = w_.unit_volts;
      s.volts_per_div = one_two_five(std::clamp(probe.peak_mu, 0.05, 1.0) * w_.unit_volts / 4);
      w_.watch.push_back(s);
    }
    ScopeSetup& scope = w_.scope;
    scope.seconds_per_div = one_two_five(w_.beta * w_.duration / 10);
    w_.mode = run_mode(c_.machine, w_.beta * w_.duration);
    scope.mode = w_.mode == "OP" ? "single" : "normal";
    for (const ScopeChannel& s : w_.watch) {
      double start = 0;
      for (const auto& [node, setting] : c_.initial_conditions)
        if (node == s.node && setting) start = params_.at(*setting);
      if (start == 0) continue;
      scope.channel = s.channel;
      scope.slope = start > 0 ? "rising" : "falling";
      scope.level_volts = 0.5 * start * w_.unit_volts;
      return;
    }
    scope.channel = 1;
    scope.slope = "rising";
    scope.level_volts = 0.05 * w_.unit_volts;
  }

  static double one_two_five(double x) {
    const double decade = std::pow(10.0, std::floor(std::log10(x)));
    for (double m : {1.0, 2.0, 5.0, 10.0})
      if (m * decade >= x * (1 - 1e-9)) return m * decade;
    return 10 * decade;
  }

  const circuit::Circuit& c_;
  Wiring w_;
  std::map<ElementKind, int> used_;
  std::map<std::string, Jack> driver_;  ///< node → the jack driving it
  std::map<std::string, std::string> shared_;
  std::map<std::string, ComparatorUse> uses_;  ///< comparator output node → its comparator
  std::map<Setting, double> params_;
  std::vector<std::function<void()>> later_;
};

}  // namespace

Wiring wire_up(const circuit::Circuit& circuit) { return Wirer(circuit).run(); }

}  // namespace gearpatch::patching
