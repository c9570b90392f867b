#include "patching/allocation.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <set>

#include "common/error.h"
#include "common/numbers.h"
#include "machine/machine_file.h"

namespace gearpatch::patching {

namespace {

/// Takes elements in circuit order; one method per part of the circuit.
class Allocator {
 public:
  explicit Allocator(const circuit::Circuit& c) : c_(c) {
    a_.scene = c.scene;
    a_.machine = c.machine;
    a_.beta = c.beta;
    a_.duration = c.duration;
    for (const auto& [name, value] : c.parameters) params_[name] = value;
  }

  Allocation run() {
    references();
    for (const auto& amp : c_.amplifiers)
      if (!is_inverter(amp)) amplifier(amp);
    for (const auto& block : c_.blocks) function_block(block);
    for (const auto& amp : c_.amplifiers)
      if (is_inverter(amp)) inverter(amp);
    for (const auto& amp : c_.amplifiers) inputs(amp);
    initial_conditions();
    watches();
    counts();
    return std::move(a_);
  }

 private:
  int free_on_first(ElementKind kind) const {
    auto it = used_.find(kind);
    return element_count(c_.machine, kind) - (it == used_.end() ? 0 : it->second);
  }
  std::string prefix(ElementKind kind) const {
    auto it = c_.machine.elements.find(kind);
    return it == c_.machine.elements.end() || it->second.label.empty() ? element_name(kind) : it->second.label;
  }

  const Element& take(ElementKind kind, const std::string& instance, const std::string& role,
                      const std::string& feature) {
    const int n = ++used_[kind], count = element_count(c_.machine, kind);
    Element e;
    e.kind = kind;
    e.machine = count > 0 ? (n - 1) / count + 1 : 0;
    e.number = count > 0 ? (n - 1) % count + 1 : n;
    e.label = (e.machine > 1 ? fmt::format("{}:", e.machine) : e.machine == 0 ? std::string("missing:") : "") +
              prefix(kind) + std::to_string(e.number);
    e.realises = instance;
    e.role = role;
    e.feature = feature;
    a_.elements.push_back(e);
    return a_.elements.back();
  }

  /// A potentiometer carrying `what` at `setting`, driving an input of `weight`.
  std::string potentiometer(const std::string& instance, const std::string& what, std::optional<Setting> name,
                            double setting, double loaded, int weight, const std::string& feature) {
    const Element& e = take(ElementKind::potentiometer, instance, what, feature);
    a_.potentiometers.push_back({e.label, what, name, setting, c_.machine.potentiometers_buffered ? setting : loaded,
                                 weight});
    return e.label;
  }

  /// The machine references, and a potentiometer for a constant that is not ±1 MU.
  void references() {
    for (const auto& [node, value] : c_.sources) {
      if (labels_.count(node)) continue;
      const std::string reference = value < 0 ? "−1 MU reference" : "+1 MU reference";
      if (is_one(value)) {
        labels_[node] = reference;
      } else {
        labels_[node] = potentiometer(node, fmt::format("{} = {} MU from the {}", node, format_number(value),
                                                        reference), std::nullopt, std::abs(value),
                                      std::abs(value), 1, c_.feature_of(node));
      }
    }
    // A drive that varies in time: a function generator of machine
    // time; a machine without one reports the shortfall.
    for (const auto& [node, points] : c_.pwl_sources)
      labels_[node] = take(ElementKind::function_generator, node,
                           fmt::format("{}: the drive torque over machine time, linear between {} points", node,
                                       points.size()),
                           c_.feature_of(node)).label;
  }

  void amplifier(const circuit::Amplifier& amp) {
    const ElementKind kind = amp.integrator ? ElementKind::integrator : ElementKind::summer;
    labels_[amp.out] = take(kind, amp.name, amp.comment, amp.feature).label;
  }

  /// An inverter where the machine has one free, else a summer with one input.
  void inverter(const circuit::Amplifier& amp) {
    const bool use_summer = free_on_first(ElementKind::inverter) <= 0 && free_on_first(ElementKind::summer) > 0;
    const Element& e = take(use_summer ? ElementKind::summer : ElementKind::inverter, amp.name, amp.comment,
                            amp.feature);
    labels_[amp.out] = e.label;
    if (use_summer) a_.notes.push_back(fmt::format("{} serves as inverter for {} (no free inverter)", e.label, amp.name));
  }

  void function_block(const circuit::FunctionBlock& block) {
    const std::string kind = circuit::to_string(block.block);
    auto it = c_.machine.realisations.find(kind);
    const Realisation parts = it == c_.machine.realisations.end()
                                  ? Realisation{{1, ElementKind::function_generator}}
                                  : it->second;
    std::optional<Setting> threshold;
    if (block.parameter.size() > 2 && block.parameter.front() == '{')
      threshold = parse_setting(block.parameter.substr(1, block.parameter.size() - 2));
    const std::string& feature = block.feature;
    std::vector<std::string> taken;
    std::string output, amplifier_output, comparator_output;
    bool own_potentiometer = false;
    for (const auto& [n, element] : parts)
      for (int i = 0; i < n; ++i) {
        if (element == ElementKind::potentiometer) {
          own_potentiometer = true;
          const double value = threshold ? params_.at(*threshold) : 0;
          taken.push_back(potentiometer(block.name, fmt::format("{} threshold {} (bias from the {}1 MU reference)",
                                                                block.name, threshold ? to_string(*threshold) : "0",
                                                                i % 2 ? "+" : "−"),
                                        threshold, value, value, 1, feature));
          continue;
        }
        const Element& e = take(element, block.name, block.comment, feature);
        taken.push_back(e.label);
        // the block's output is its amplifier's, else its comparator's
        const bool drives = element == ElementKind::summer || element == ElementKind::function_generator;
        if (drives || (element == ElementKind::comparator && comparator_output.empty()))
          (drives ? amplifier_output : comparator_output) = e.label;
      }
    output = amplifier_output.empty() ? comparator_output : amplifier_output;
    if (threshold && !own_potentiometer && block.block == circuit::BlockKind::comparator) {
      if (!thresholds_.count(*threshold))
        thresholds_[*threshold] = potentiometer(
            to_string(*threshold), fmt::format("comparator threshold {} from the −1 MU reference, into input B",
                                               to_string(*threshold)),
            threshold, params_.at(*threshold), params_.at(*threshold), 1, feature);
      a_.notes.push_back(fmt::format("{}: input B from {} ({} = {})", output, thresholds_[*threshold],
                                     to_string(*threshold), format_number(params_.at(*threshold))));
    }
    for (std::size_t k = 1; k < block.nodes.size(); ++k)
      labels_[block.nodes[k]] = output.empty() ? taken.at(std::min(k - 1, taken.size() - 1)) : output;
  }

  void inputs(const circuit::Amplifier& amp) {
    const Element target = *a_.find(amp.name);  // a copy: taking potentiometers grows the list
    const auto type = c_.machine.elements.find(target.kind);
    std::map<int, int> needed, offered;
    for (int w : type == c_.machine.elements.end() ? std::vector<int>{} : type->second.inputs) ++offered[w];
    for (std::size_t k = 0; k < amp.inputs.size(); ++k) {
      ++needed[amp.inputs[k].weight];
      // a chained path (AmplifierInput::otherwise) reaches the same input through the first path's switch
      for (const circuit::AmplifierInput* path : circuit::paths(amp.inputs[k])) {
        const circuit::AmplifierInput& in = *path;
        Connection wire;
        wire.number = static_cast<int>(a_.connections.size()) + 1;
        wire.from_node = in.from;
        wire.from_label = label(in.from);
        wire.from_signal = c_.signal_of(in.from);
        wire.to_instance = amp.name;
        wire.to_label = target.label;
        wire.input = static_cast<int>(k) + 1;
        wire.weight = in.weight;
        if (in.potentiometer) {
          wire.potentiometer = in.potentiometer;
          wire.setting = params_.at(*in.potentiometer);
          auto dial = c_.dial_settings.find(*in.potentiometer);
          wire.loaded_setting = c_.machine.potentiometers_buffered || dial == c_.dial_settings.end()
                                    ? wire.setting : dial->second;
          if (!is_one(wire.setting))
            wire.potentiometer_label = potentiometer(to_string(*in.potentiometer),
                                                     fmt::format("{} into {} input {}", to_string(*in.potentiometer),
                                                                 target.label, k + 1),
                                                     in.potentiometer, wire.setting, wire.loaded_setting, in.weight,
                                                     in.feature);
          else
            a_.notes.push_back(fmt::format("{} = 1: a plain wire into {} (weight {})", to_string(*in.potentiometer),
                                           target.label, in.weight));
        }
        if (!in.switched_by.empty()) {
          wire.switch_label = label(in.switched_by);
          wire.switch_node = in.switched_by;
        }
        if (!in.released_by.empty()) latch(wire, in);
        a_.connections.push_back(wire);
      }
    }
    for (const auto& [weight, n] : needed)
      if (n > offered[weight])
        a_.input_overflows.push_back(fmt::format("{} ({}) needs {} inputs of weight {}, an element has {}",
                                                 target.label, amp.name, n, weight, offered[weight]));
  }

  /// The lock latch of a switched input (circuit.h: AmplifierInput): a
  /// comparator of its own takes set − reset, with an inverter for −reset,
  /// and holds by feeding its switch back (±1 MU of hysteresis, as the deck's
  /// latch); its switch lies in parallel with the engagement switch.
  void latch(Connection& wire, const circuit::AmplifierInput& in) {
    const std::string name = "latch_" + wire.to_instance + "_" + std::to_string(wire.input);
    const std::string set = in.latched_by.empty() ? in.switched_by : in.latched_by;
    const std::string& feature = in.feature;
    const bool use_summer = free_on_first(ElementKind::inverter) <= 0 && free_on_first(ElementKind::summer) > 0;
    const Element& inv = take(use_summer ? ElementKind::summer : ElementKind::inverter, name + "_reset_n",
                              fmt::format("−{} for the lock latch of {} input {}", in.released_by, wire.to_label,
                                          wire.input), feature);
    const std::string inverter = inv.label;
    const Element& cmp =
        take(ElementKind::comparator, name,
             fmt::format("lock latch: input A from {} ({}, set), input B from {} (−{}, reset), its switch fed back "
                         "for ±1 MU of hysteresis (closed above 1.45 MU, open below −0.55 MU), in parallel with the "
                         "switch of {}", label(set), set, inverter, in.released_by, label(in.switched_by)),
             feature);
    wire.latch_label = cmp.label;
    wire.latch_set_node = set;
    wire.latch_reset_node = in.released_by;
  }

  void initial_conditions() {
    for (const auto& [node, setting] : c_.initial_conditions) {
      InitialCondition ic;
      ic.node = node;
      ic.integrator = label(node);
      if (!setting) {
        ic.how = "IC input to ground";
      } else {
        ic.value = params_.at(*setting);
        // every amplifier inverts, in IC mode too: the IC input takes the negated value
        const std::string reference = ic.value > 0 ? "−1 MU reference" : "+1 MU reference";
        if (is_one(ic.value))
          ic.how = "IC input ← " + reference + " (wire)";
        else
          ic.how = "IC input ← " + reference + " through " +
                   potentiometer(to_string(*setting), fmt::format("initial value {} of {}", to_string(*setting), ic.integrator),
                                 setting, std::abs(ic.value), std::abs(ic.value), 1, "");
      }
      a_.initial_conditions.push_back(ic);
    }
  }

  void watches() {
    for (const auto& [signal, probe] : c_.probes)
      a_.watches.push_back(
          {gearpatch::to_string(signal), label(probe.node), probe.node, gearpatch::unit(signal), probe.full_scale});
  }

  void counts() {
    a_.machines_needed = tally(a_, [&](ElementKind kind) { return used_.count(kind) ? used_.at(kind) : 0; });
    options();
  }

  /// What to do when the patch does not fit: chain machines, or leave a feature out.
  void options() {
    const int chain = c_.machine.chain;
    if (a_.machines_needed > 1 && a_.machines_needed <= chain)
      a_.options.push_back(fmt::format("daisy-chain {} machines (this machine chains up to {}): the elements "
                                       "labelled 2:… are on the second", a_.machines_needed, chain));
    else if (a_.machines_needed != 1)
      a_.options.push_back(fmt::format("more elements than {} chained machine{} hold", chain, chain > 1 ? "s" : ""));
    std::map<std::string, std::map<ElementKind, int>> by_feature;
    for (const Element& e : a_.elements)
      if (!e.feature.empty()) ++by_feature[e.feature][e.kind];
    for (const auto& [feature, kinds] : by_feature) {
      std::string saves;
      for (const auto& [kind, n] : kinds) saves += fmt::format("{}{} {}", saves.empty() ? "" : ", ", n, element_name(kind));
      if (!a_.shortfalls.empty() || !a_.input_overflows.empty())
        a_.options.push_back(fmt::format("a scene without {} saves {}", feature, saves));
    }
  }

  std::string label(const std::string& node) const {
    auto it = labels_.find(node);
    if (it == labels_.end()) throw Error("internal: no element drives node " + node, Error::Kind::internal);
    return it->second;
  }

  const circuit::Circuit& c_;
  Allocation a_;
  std::map<ElementKind, int> used_;
  std::map<std::string, std::string> labels_;  ///< node → the element (or reference) driving it
  std::map<Setting, double> params_;
  std::map<Setting, std::string> thresholds_;  ///< comparator threshold → its potentiometer
};

}  // namespace

const Element* Allocation::find(const std::string& instance) const {
  for (const Element& e : elements)
    if (e.realises == instance && e.kind != ElementKind::potentiometer) return &e;
  return nullptr;
}

std::string run_mode(const MachineProfile& m, double machine_seconds) {
  auto has = [&](const char* mode) { return std::find(m.modes.begin(), m.modes.end(), mode) != m.modes.end(); };
  if (has("REPF") && m.op_time > 0 && machine_seconds <= m.op_time / 100) return "REPF";
  if (has("REP") && m.op_time > 0 && machine_seconds <= m.op_time) return "REP";
  return "OP";
}

std::string Allocation::run_mode() const {
  const double machine_time = beta * duration;
  const std::string mode = patching::run_mode(machine, machine_time);
  if (mode == "OP") return fmt::format("OP (single run), {:.5g} s of machine time", machine_time);
  return fmt::format("{} (repetitive{}), OP time {:.5g} s", mode, mode == "REPF" ? ", fast" : "", machine_time);
}

Allocation allocate(const circuit::Circuit& circuit) { return Allocator(circuit).run(); }

bool is_inverter(const circuit::Amplifier& a) {
  return !a.integrator && a.inputs.size() == 1 && !a.inputs[0].potentiometer && a.inputs[0].weight == 1 &&
         a.inputs[0].switched_by.empty();
}

bool is_one(double value) { return std::abs(std::abs(value) - 1.0) < 1e-12; }

int element_count(const MachineProfile& machine, ElementKind kind) {
  auto it = machine.elements.find(kind);
  return it == machine.elements.end() ? 0 : it->second.count;
}

int tally(Allocation& a, const std::function<int(ElementKind)>& needed_of) {
  int machines = 1;
  for (ElementKind kind : element_kinds()) {
    const int needed = needed_of(kind), have = element_count(a.machine, kind);
    if (needed == 0 && have == 0) continue;
    a.counts.push_back({kind, needed, have});
    if (needed <= have) continue;
    a.shortfalls.push_back(fmt::format("{}: needs {}, the machine has {} ({} short)", element_name(kind), needed,
                                       have, needed - have));
    machines = have == 0 || machines == 0 ? 0 : std::max(machines, (needed + have - 1) / have);
  }
  return machines;
}

}  // namespace gearpatch::patching
