#include "tolerance/error_budget.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "common/error.h"
#include "scene/scene.h"
#include "tolerance/component_draw.h"
#include "verify/tube.h"

namespace gearpatch::tolerance {

double ComponentShare::largest() const {
  double most = 0;
  for (const auto& [signal, e] : error) most = std::max(most, e);
  return most;
}

namespace {

/// The RMS of an offset magnitude uniform in [a, b]: what one amplifier contributes typically.
double offset_rms(const AmplifierModel& oa) {
  const double a = std::max(0.0, oa.offset_volts - oa.offset_spread_volts), b = oa.offset_volts + oa.offset_spread_volts;
  return std::sqrt((a * a + a * b + b * b) / 3);
}

/// Every offset zero and every setting as computed: the perfect machine, plus `then`.
std::function<void(verify::VerifyOptions&)> perfect(std::function<void(circuit::Circuit&)> then = {}) {
  return [then](verify::VerifyOptions& o) {
    also_alter(o, [then](circuit::Circuit& c) {
      for (const circuit::Amplifier& a : c.amplifiers) c.machine.amplifier.offsets_by_name[amplifier_subckt(a)] = 0;
      if (then) then(c);
    });
  };
}

std::function<void(circuit::Circuit&)> one_offset(std::string subckt, double volts) {
  return [subckt, volts](circuit::Circuit& c) { c.machine.amplifier.offsets_by_name[subckt] = volts; };
}

std::function<void(circuit::Circuit&)> all_settings(double by) {
  return [by](circuit::Circuit& c) {
    for (auto& [setting, value] : c.parameters) {
      if (!c.weights.count(setting)) continue;
      value += by;
      if (auto dial = c.dial_settings.find(setting); dial != c.dial_settings.end()) dial->second += by;
    }
  };
}

/// The variants: [perfect, then per component its + (and −) variant], with the component names.
struct Plan {
  std::vector<Variant> variants;
  std::vector<std::string> components;  ///< one per component, variants 1 + k·signs …
  int signs = 1;
};

Plan plan(const circuit::Circuit& c) {
  Plan p;
  const AmplifierModel& oa = c.machine.amplifier;
  p.signs = oa.random_sign ? 2 : 1;
  p.variants.push_back({"perfect components", perfect()});
  const double rms = offset_rms(oa);
  const auto add = [&](const std::string& component, auto make) {
    p.components.push_back(component);
    p.variants.push_back({component + " +", perfect(make(+1))});
    if (p.signs == 2) p.variants.push_back({component + " -", perfect(make(-1))});
  };
  if (rms > 0)
    for (const circuit::Amplifier& a : c.amplifiers)
      add("offset " + amplifier_subckt(a), [&](int s) { return one_offset(amplifier_subckt(a), s * rms); });
  // A setting error is uniform in ± half a step: its RMS is step/√12.
  const double step = c.machine.potentiometer_resolution / std::sqrt(12.0);
  if (step > 0) add("potentiometer resolution", [&](int s) { return all_settings(s * step); });
  return p;
}

/// The worst signal's prediction with the dominant component removed from the RSS.
double without_dominant(const ErrorBudget& b) {
  double others = 0;
  for (const ComponentShare& s : b.shares)
    if (s.component != b.dominant) others += std::pow(s.moved.at(b.worst_signal), 2);
  return b.nominal.at(b.worst_signal) + std::sqrt(others);
}

/// The worst signal's prediction on a machine whose offsets are ten times
/// smaller: an offset's share scales with the offset, a hundredth of its square.
double offsets_tenth(const ErrorBudget& b) {
  double squares = 0;
  for (const ComponentShare& s : b.shares) {
    const double e = s.moved.at(b.worst_signal);
    squares += s.component.rfind("offset ", 0) == 0 ? e * e / 100 : e * e;
  }
  return b.nominal.at(b.worst_signal) + std::sqrt(squares);
}

/// What would shrink a prediction beyond the tolerance: only a change whose
/// shares, measured on copies, move it by at least a tenth of its excess.
void advise(ErrorBudget& b, double tolerance) {
  const double nominal = b.nominal.at(b.worst_signal), worst = b.worst();
  if (nominal > tolerance)
    b.advice.push_back(fmt::format("with perfect components the circuit errs {:.3g} % already: the blocks' own "
                                   "imperfections (bandwidth, diode corners, δ, hysteresis) or the scaling (β, k0) "
                                   "dominate, not the tolerances",
                                   100 * nominal));
  const double excess = worst - tolerance;
  if (excess <= 0) return;
  const auto worth = [&](double after) { return worst - after >= 0.1 * excess; };
  const bool dominant_known = std::any_of(b.shares.begin(), b.shares.end(),
                                          [&](const ComponentShare& s) { return s.component == b.dominant; });
  if (const double without = without_dominant(b); dominant_known && worth(without)) {
    if (b.dominant.rfind("offset ", 0) == 0)
      b.advice.push_back(fmt::format("trim the offset of {}: the budget of {} falls from {:.3g} % to {:.3g} %",
                                     b.dominant.substr(7), to_string(b.worst_signal), 100 * worst, 100 * without));
    else
      b.advice.push_back(fmt::format("set the potentiometers finer: the budget of {} falls from {:.3g} % to {:.3g} %",
                                     to_string(b.worst_signal), 100 * worst, 100 * without));
  }
  if (const double trimmed = offsets_tenth(b); b.offset_rms_volts > 0 && worth(trimmed))
    b.advice.push_back(fmt::format("use a machine with every offset ten times smaller (about {:.0f} µV): the budget "
                                   "of {} falls to {:.3g} %",
                                   1e6 * b.offset_rms_volts / 10, to_string(b.worst_signal), 100 * trimmed));
}

}  // namespace

/// How far one component moves each signal of the circuit: the variant's
/// trace against the perfect deck's, in verify's tube (the best shift within
/// its time tolerance), as a fraction of full scale. Not the change of the
/// error's maximum: a component that moves the signal where the nominal error
/// is not largest changed that maximum little one at a time, yet adds up
/// with the others (measured on bild5b, the-analog-thing: shares so taken
/// predicted omega_p 1.01 % and the profile's deck erred 1.22 %, the Monte
/// Carlo's p90 1.68 %).
std::map<Signal, double> displacement(const verify::VerifyResult& perfect, const verify::VerifyResult& variant) {
  std::map<Signal, double> out;
  const double shift = perfect.comparison.time_tolerance;
  for (const verify::SignalError& e : perfect.comparison.signals) {
    const auto from = perfect.circuit.signals.find(e.signal), to = variant.circuit.signals.find(e.signal);
    if (from == perfect.circuit.signals.end() || to == variant.circuit.signals.end()) continue;
    const verify::Tube tube(perfect.circuit.t, from->second, {shift, 0});
    out[e.signal] = tube.fit(variant.circuit.t, to->second).worst_distance / e.full_scale;
  }
  return out;
}

ErrorBudget error_budget(const Scene& scene, verify::VerifyOptions base, unsigned workers) {
  base.level = circuit::Level::hardware;
  ErrorBudget b;
  b.scene = scene.name;
  b.machine = scene.machine.name;
  b.offset_rms_volts = offset_rms(scene.machine.amplifier);
  circuit::Circuit shape;  // the circuit verify builds: its amplifiers and settings
  Plan p;
  std::optional<verify::VerifyResult> perfect_run;
  {
    // Build once through a variant that records the circuit; it is the perfect run itself.
    std::vector<Variant> first{{"perfect components", [&](verify::VerifyOptions& o) {
                                  perfect()(o);
                                  also_alter(o, [&](circuit::Circuit& c) { shape = c; });
                                }}};
    std::vector<VariantRun> runs = run_variants(scene, base, first, 1, "gearpatch budget (perfect deck)");
    if (!runs[0].result) throw Error(fmt::format("error budget: the deck with perfect components failed: {}", runs[0].failure));
    b.nominal = signal_errors(*runs[0].result);
    perfect_run = std::move(runs[0].result);
    p = plan(shape);
  }
  p.variants.erase(p.variants.begin());
  const std::vector<VariantRun> runs = run_variants(scene, base, p.variants, workers, "gearpatch budget");
  for (std::size_t k = 0; k < p.components.size(); ++k) {
    ComponentShare share{p.components[k], {}, {}};
    for (const auto& [signal, e0] : b.nominal) {
      double most = 0, farthest = 0;
      for (int s = 0; s < p.signs; ++s) {
        const VariantRun& run = runs[k * p.signs + s];
        if (!run.result) continue;
        const double change = std::abs(signal_errors(*run.result).at(signal) - e0);
        most = std::max(most, change);
        const std::map<Signal, double> moved = displacement(*perfect_run, *run.result);
        const auto it = moved.find(signal);
        farthest = std::max({farthest, change, it == moved.end() ? 0.0 : it->second});
      }
      share.error[signal] = most;
      share.moved[signal] = farthest;
    }
    for (int s = 0; s < p.signs; ++s)
      if (!runs[k * p.signs + s].result) b.failed.push_back(runs[k * p.signs + s].failure);
    b.shares.push_back(std::move(share));
  }
  std::sort(b.shares.begin(), b.shares.end(),
            [](const ComponentShare& x, const ComponentShare& y) { return x.largest() > y.largest(); });
  double worst = -1;
  for (const auto& [signal, e0] : b.nominal) {
    double sum = 0;
    for (const ComponentShare& s : b.shares) sum += s.moved.at(signal) * s.moved.at(signal);
    b.predicted[signal] = e0 + std::sqrt(sum);
    if (b.predicted[signal] > worst) worst = b.predicted[signal], b.worst_signal = signal;
  }
  double heaviest = -1;
  for (const ComponentShare& s : b.shares)
    if (s.error.at(b.worst_signal) > heaviest) heaviest = s.error.at(b.worst_signal), b.dominant = s.component;
  advise(b, base.tolerance.value_or(verify::default_tolerance(circuit::Level::hardware)));
  return b;
}

std::string to_table(const ErrorBudget& b) {
  std::string t = fmt::format("error budget of {} on {} (offsets of {:.3g} mV RMS, random sign): nominal with "
                              "perfect components + RSS of how far each tolerance alone moves the signal\n",
                              b.scene, b.machine, 1e3 * b.offset_rms_volts);
  t += fmt::format("{:<32}", "% of full scale");
  for (const auto& [signal, e] : b.nominal) t += fmt::format(" {:>9}", to_string(signal));
  t += fmt::format("\n{:<32}", "perfect components");
  for (const auto& [signal, e] : b.nominal) t += fmt::format(" {:>9.3f}", 100 * e);
  for (const ComponentShare& s : b.shares) {
    if (s.largest() < 1e-3 * b.worst() && &s != &b.shares.front()) continue;
    t += fmt::format("\n{:<32}", s.component);
    for (const auto& [signal, e] : s.moved) t += fmt::format(" {:>9.3f}", 100 * e);
  }
  t += fmt::format("\n{:<32}", "predicted (nominal + RSS)");
  for (const auto& [signal, e] : b.predicted) t += fmt::format(" {:>9.3f}", 100 * e);
  t += fmt::format("\ndominant: {} (in {}, predicted {:.3g} %; alone it changes that error most)\n", b.dominant,
                   to_string(b.worst_signal), 100 * b.worst());
  for (const std::string& a : b.advice) t += "  - " + a + "\n";
  for (const std::string& f : b.failed) t += "  could not run: " + f + "\n";
  return t;
}

nlohmann::json to_json(const ErrorBudget& b) {
  const auto by_signal = [](const std::map<Signal, double>& m) {
    nlohmann::json j = nlohmann::json::object();
    for (const auto& [signal, e] : m) j[to_string(signal)] = e;
    return j;
  };
  nlohmann::json shares = nlohmann::json::array();
  for (const ComponentShare& s : b.shares) shares.push_back({{"component", s.component}, {"error", by_signal(s.error)}, {"moved", by_signal(s.moved)}});
  return {{"scene", b.scene},
          {"machine", b.machine},
          {"method", "nominal (perfect components) + root-sum-square of one-at-a-time shares at RMS size, both signs; a share is how far the component alone moves the signal against the perfect deck's (verify's tube, best time shift)"},
          {"offset_rms_volts", b.offset_rms_volts},
          {"nominal", by_signal(b.nominal)},
          {"shares", shares},
          {"predicted", by_signal(b.predicted)},
          {"worst_signal", to_string(b.worst_signal)},
          {"worst", b.worst()},
          {"dominant", b.dominant},
          {"advice", b.advice},
          {"failed", b.failed}};
}

}  // namespace gearpatch::tolerance
