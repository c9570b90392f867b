#include "component_spread/offset_check.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>

#include "circuit/circuit.h"
#include "circuit/quality.h"
#include "common/error.h"
#include "patching/allocation.h"
#include "scaling/scaled_program.h"
#include "scene/scene.h"
#include "scene/scene_inputs.h"
#include "component_spread/component_draw.h"
#include "component_spread/error_budget.h"
#include "component_spread/variants.h"

namespace gearpatch::component_spread {

std::vector<const StageOffset*> OffsetCheck::limiting() const {
  std::vector<const StageOffset*> out;
  for (const StageOffset& s : stages)
    if (s.moved > tolerance) out.push_back(&s);
  return out;
}

namespace {

using circuit::Amplifier;
using circuit::AmplifierInput;
using circuit::Circuit;

/// The largest offset the profile draws for one amplifier.
double largest_offset(const AmplifierModel& oa) { return oa.offset_volts + oa.offset_spread_volts; }

double setting_of(const Circuit& c, const AmplifierInput& in) {
  if (!in.potentiometer) return 1;
  for (const auto& [setting, value] : c.parameters)
    if (setting == *in.potentiometer) return std::abs(value);
  return 1;
}

/// How often the op-amp's input offset appears at the output: 1 + Σ n of a
/// summer; an integrator's offset drives Σ n times its current into the capacitor.
double noise_gain(const Amplifier& a) {
  double sum = 0;
  for (const AmplifierInput& in : a.inputs) sum += in.weight;
  return a.integrator ? sum : 1 + sum;
}

/// What 1 MU at `node` becomes at most, first order: through each summer it
/// feeds (its input's α·n), integrated over the run by the first integrator
/// it reaches (α·n·k0·β·T). Loops beyond the first integrator are not followed.
double reach(const Circuit& c, const std::string& node, double run_gain, int depth) {
  double most = 1;
  if (depth > 8) return most;
  for (const Amplifier& a : c.amplifiers)
    for (const AmplifierInput& in : a.inputs) {
      if (in.from != node) continue;
      const double g = setting_of(c, in) * in.weight;
      most = std::max(most, a.integrator ? g * run_gain : g * reach(c, a.out, run_gain, depth + 1));
    }
  return most;
}

/// The circuit verify generates for the scene at the hardware level.
Circuit generated_circuit(const Scene& scene, const verify::VerifyOptions& base) {
  ScalingOptions o;
  o.comparator_offset = circuit::comparator_offset(circuit::Level::hardware);
  o.lock_catch = false;
  o.autoscale = base.autoscale;
  if (base.paper_scaling) o.method = ScalingMethod::paper;
  return circuit::build_circuit(scale_program(scene, o), circuit::Level::hardware);
}

std::string panel_element(const patching::Allocation* allocation, const std::string& instance) {
  if (!allocation) return "";
  const patching::Element* e = allocation->find(instance);
  return e ? e->label : "";
}

/// Every stage whose first-order estimate reaches a tenth of the tolerance, largest first.
std::vector<StageOffset> screen(const Circuit& c, const OffsetCheck& k) {
  const double run_gain = c.machine.integrator_constant * c.beta * c.duration;
  std::optional<patching::Allocation> allocation;
  try {
    allocation = patching::allocate(c);
  } catch (const Error&) {
    // a circuit the machine cannot hold is named by its subckts alone
  }
  std::vector<StageOffset> out;
  for (const Amplifier& a : c.amplifiers) {
    StageOffset s;
    s.stage = amplifier_subckt(a);
    s.element = panel_element(allocation ? &*allocation : nullptr, a.name);
    s.meaning = a.comment;
    s.noise_gain = noise_gain(a);
    const double output = k.offset_volts / c.machine.unit_volts * s.noise_gain;
    s.estimate = a.integrator ? output * run_gain : output * reach(c, a.out, run_gain, 0);
    if (s.estimate >= 0.1 * k.tolerance) out.push_back(std::move(s));
  }
  std::sort(out.begin(), out.end(), [](const StageOffset& x, const StageOffset& y) { return x.estimate > y.estimate; });
  return out;
}

/// Every offset zero but `subckt`'s, which is `volts`.
Variant one_offset(const std::string& subckt, double volts) {
  const std::string name = subckt.empty() ? "every offset zero" : fmt::format("offset of {} at {:.3g} mV alone", subckt, 1e3 * volts);
  return {name, [subckt, volts](verify::VerifyOptions& o) {
            also_alter(o, [subckt, volts](Circuit& c) {
              for (const Amplifier& a : c.amplifiers) c.machine.amplifier.offsets_by_name[amplifier_subckt(a)] = 0;
              if (!subckt.empty()) c.machine.amplifier.offsets_by_name[subckt] = volts;
            });
          }};
}

/// The largest displacement of any signal, and which.
std::pair<Signal, double> farthest(const verify::VerifyResult& perfect, const VariantRun& run) {
  std::pair<Signal, double> most{Signal::omega_p, 0};
  if (!run.result) return most;
  for (const auto& [signal, d] : displacement(perfect, *run.result))
    if (d > most.second) most = {signal, d};
  return most;
}

/// The perfect deck's run, and each measured stage's worse sign.
struct Measured {
  std::optional<verify::VerifyResult> perfect;
  std::vector<int> worse;
};

/// Runs the perfect deck and each stage at ±offset; fills `moved` and `signal`.
Measured measure(const Scene& scene, const verify::VerifyOptions& base, unsigned workers, OffsetCheck& k) {
  std::vector<Variant> variants{one_offset("", 0)};
  for (const StageOffset& s : k.stages)
    for (int sign : {+1, -1}) variants.push_back(one_offset(s.stage, sign * k.offset_volts));
  std::vector<VariantRun> runs = run_variants(scene, base, variants, workers, "");
  k.runs += static_cast<unsigned>(runs.size());
  for (const VariantRun& r : runs)
    if (!r.result) k.failed.push_back(r.failure);
  if (!runs[0].result) throw Error(fmt::format("offset check: the deck with perfect components failed: {}", runs[0].failure));
  Measured m;
  for (std::size_t i = 0; i < k.stages.size(); ++i) {
    const auto plus = farthest(*runs[0].result, runs[1 + 2 * i]), minus = farthest(*runs[0].result, runs[2 + 2 * i]);
    const bool up = plus.second >= minus.second;
    std::tie(k.stages[i].signal, k.stages[i].moved) = up ? plus : minus;
    m.worse.push_back(up ? +1 : -1);
  }
  m.perfect = std::move(runs[0].result);
  return m;
}

/// For each limiting stage: the offset that would move its signal by half
/// the tolerance if the displacement were linear, measured at that offset.
void measure_trim(const Scene& scene, const verify::VerifyOptions& base, unsigned workers, OffsetCheck& k,
                  const Measured& m) {
  std::vector<Variant> variants;
  std::vector<std::size_t> which;
  for (std::size_t i = 0; i < k.stages.size(); ++i) {
    StageOffset& s = k.stages[i];
    if (s.moved <= k.tolerance) continue;
    s.trim_volts = k.offset_volts * 0.5 * k.tolerance / s.moved;
    variants.push_back(one_offset(s.stage, m.worse[i] * s.trim_volts));
    which.push_back(i);
  }
  if (which.empty()) return;
  const std::vector<VariantRun> runs = run_variants(scene, base, variants, workers, "");
  k.runs += static_cast<unsigned>(runs.size());
  for (std::size_t j = 0; j < which.size(); ++j)
    if (runs[j].result) k.stages[which[j]].moved_trimmed = farthest(*m.perfect, runs[j]).second;
    else k.failed.push_back(runs[j].failure);
}

}  // namespace

OffsetCheck check_offsets(const Scene& scene, verify::VerifyOptions base, unsigned workers, std::size_t max_stages) {
  const auto start = std::chrono::steady_clock::now();
  base.level = circuit::Level::hardware;
  base.deck_text.reset();
  base.deck_header.reset();
  base.limits.keep_deck_as.clear();
  base.check_step = false;
  // Draft steps: the check compares decks with each other, not with the
  // reference, and draft moves the perfect deck's errors by under 0.01 % of
  // full scale on bild6c at 2.4 times the speed.
  base.transient = circuit::quality_preset("draft").control;
  OffsetCheck k;
  k.scene = scene.name;
  k.machine = scene.machine.name;
  k.tolerance = base.tolerance.value_or(verify::default_tolerance(circuit::Level::hardware));
  k.offset_volts = largest_offset(scene.machine.amplifier);
  k.stages = screen(generated_circuit(scene, base), k);
  if (k.stages.empty())
    k.skipped = fmt::format("no amplifier's offset ({:.3g} mV at most) reaches a tenth of the tolerance by a "
                            "first-order estimate",
                            1e3 * k.offset_volts);
  if (k.stages.size() > max_stages) k.stages.resize(max_stages);
  if (!k.stages.empty()) measure_trim(scene, base, workers, k, measure(scene, base, workers, k));
  std::stable_sort(k.stages.begin(), k.stages.end(),
                   [](const StageOffset& x, const StageOffset& y) { return x.moved > y.moved; });
  k.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return k;
}

std::vector<std::string> OffsetCheck::warnings() const {
  std::vector<std::string> out;
  for (const StageOffset* s : limiting()) {
    std::string w = fmt::format(
        "{}{} ({}; output offset {:g} × its op-amp's): that offset alone at {:.3g} mV moves {} by {:.3g} % of full "
        "scale (measured on a copy of the deck, every other offset zero), beyond the tolerance of {:.3g} %: on {}'s "
        "untrimmed parts {} cannot reliably pass. What lifts it: ",
        s->element.empty() ? "" : s->element + " ", s->stage, s->meaning, s->noise_gain, 1e3 * offset_volts,
        to_string(s->signal), 100 * s->moved, 100 * tolerance, machine, scene);
    if (s->moved_trimmed)
      w += fmt::format("that amplifier's offset trimmed to {:.3g} mV (measured: {:.3g} %), ", 1e3 * s->trim_volts,
                       100 * *s->moved_trimmed);
    out.push_back(w + "or a machine with trimmed offsets (--machine classic)");
  }
  return out;
}

std::string to_text(const OffsetCheck& k) {
  if (!k.skipped.empty()) return fmt::format("offset check: skipped, {}\n", k.skipped);
  std::string t = fmt::format("offset check of {} on {} (before the run: each amplifier's offset alone at {:.3g} mV, "
                              "both signs, against the deck with perfect components; {} ngspice runs)\n",
                              k.scene, k.machine, 1e3 * k.offset_volts, k.runs);
  for (const StageOffset& s : k.stages)
    t += fmt::format("  {:<6} {:<14} moves {:<8} {:7.3f} %{}\n", s.element, s.stage, to_string(s.signal), 100 * s.moved,
                     s.moved > k.tolerance ? fmt::format("  beyond the tolerance of {:.3g} %", 100 * k.tolerance) : "");
  for (const std::string& w : k.warnings()) t += "warning: " + w + "\n";
  for (const std::string& f : k.failed) t += "  could not run: " + f + "\n";
  return t;
}

nlohmann::json to_json(const OffsetCheck& k) {
  nlohmann::json stages = nlohmann::json::array();
  for (const StageOffset& s : k.stages)
    stages.push_back({{"stage", s.stage},
                      {"element", s.element},
                      {"meaning", s.meaning},
                      {"noise_gain", s.noise_gain},
                      {"estimate", s.estimate},
                      {"signal", to_string(s.signal)},
                      {"moved", s.moved},
                      {"limits", s.moved > k.tolerance},
                      {"trim_volts", s.moved > k.tolerance ? nlohmann::json(s.trim_volts) : nlohmann::json(nullptr)},
                      {"moved_trimmed", s.moved_trimmed ? nlohmann::json(*s.moved_trimmed) : nlohmann::json(nullptr)}});
  return {{"machine", k.machine},
          {"tolerance", k.tolerance},
          {"offset_volts", k.offset_volts},
          {"skipped", k.skipped.empty() ? nlohmann::json(nullptr) : nlohmann::json(k.skipped)},
          {"stages", stages},
          {"warnings", k.warnings()},
          {"failed", k.failed},
          {"runs", k.runs},
          {"seconds", k.seconds}};
}

}  // namespace gearpatch::component_spread
