#include "component_spread/error_budget.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <fmt/format.h>

#include "common/error.h"
#include "scene/scene.h"
#include "component_spread/component_draw.h"
#include "component_spread/composed_machines.h"
#include "verify/tube.h"

namespace gearpatch::component_spread {

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

/// A component tolerance the budget measures: one amplifier's offset, or
/// every potentiometer's setting error together.
struct Component {
  std::string name;    ///< "offset gp_amp_xp", "potentiometer resolution"
  std::string subckt;  ///< the amplifier's; empty for the potentiometers
  double rms = 0;      ///< the size of its share's runs
  double largest = 0;  ///< the size of its second runs: the largest the profile draws
};

/// The components, and whether each is measured with both signs.
struct Plan {
  std::vector<Component> components;
  int signs = 1;
  std::size_t settings = 0;  ///< potentiometers the resolution applies to
};

Plan plan(const circuit::Circuit& c) {
  Plan p;
  const AmplifierModel& oa = c.machine.amplifier;
  p.signs = oa.random_sign ? 2 : 1;
  if (const double rms = offset_rms(oa); rms > 0)
    for (const circuit::Amplifier& a : c.amplifiers)
      p.components.push_back({"offset " + amplifier_subckt(a), amplifier_subckt(a), rms, oa.offset_volts + oa.offset_spread_volts});
  for (const auto& [setting, value] : c.parameters) p.settings += c.weights.count(setting);
  // A setting error is uniform in ± half a step: its RMS is step/√12, and so
  // is that of the sum of the settings' errors over √settings.
  const double step = c.machine.potentiometer_resolution / std::sqrt(12.0);
  if (step > 0 && p.settings > 0) p.components.push_back({"potentiometer resolution", "", step, 2 * step});
  return p;
}

/// The component at `size`, and at −size too when signs are random.
std::vector<double> sizes(const Plan& p, double size) {
  return p.signs == 2 ? std::vector<double>{size, -size} : std::vector<double>{size};
}

std::vector<Variant> variants(const Plan& p, const std::vector<std::size_t>& which, bool largest) {
  std::vector<Variant> out;
  for (std::size_t k : which) {
    const Component& c = p.components[k];
    for (double x : sizes(p, largest ? c.largest : c.rms)) {
      const std::string name = fmt::format("{} {:+.3g}", c.name, x);
      out.push_back({name, c.subckt.empty() ? perfect(all_settings(x)) : perfect(one_offset(c.subckt, x))});
    }
  }
  return out;
}

/// One machine as the Monte Carlo draws it, as the components' values: each
/// offset, and the potentiometers' errors summed over √settings (the
/// variable whose change by the RMS size is the share's run).
std::vector<double> machine_values(const Plan& p, const ComponentDraw& d) {
  std::vector<double> out;
  for (const Component& c : p.components) {
    if (!c.subckt.empty()) {
      const auto it = d.offsets.find(c.subckt);
      out.push_back(it == d.offsets.end() ? 0.0 : it->second);
      continue;
    }
    double sum = 0;
    for (const auto& [setting, error] : d.setting_errors) sum += error;
    out.push_back(sum / std::sqrt(static_cast<double>(std::max<std::size_t>(p.settings, 1))));
  }
  return out;
}

/// The machines the budget composes: the Monte Carlo's draws of seed 1, so
/// the first of them are the machines `monte-carlo --seed 1` runs.
constexpr std::size_t kMachines = 1000;
/// Components measured also at their largest size: the heaviest shares, each
/// moving some signal by at least a tenth of the tolerance.
constexpr std::size_t kTwice = 4;

/// What the prediction is composed from, and how it is recomposed for advice.
struct Composition {
  TraceModel model;
  std::vector<std::vector<double>> machines;
  std::vector<bool> offset;  ///< per component: an amplifier's offset (else the potentiometers)
  std::size_t index(const std::string& component) const;
};

std::size_t Composition::index(const std::string& component) const {
  for (std::size_t k = 0; k < model.components.size(); ++k)
    if (model.components[k].component == component) return k;
  return model.components.size();
}

/// The p90 over the machines with each component's value changed by
/// `change`: the worst signal's, and of each machine's worst.
ComposedP90 recomposed_all(const Composition& c, const std::function<double(std::size_t, double)>& change) {
  std::vector<std::vector<double>> machines = c.machines;
  for (std::vector<double>& values : machines)
    for (std::size_t k = 0; k < values.size(); ++k) values[k] = change(k, values[k]);
  return composed_p90(c.model, machines);
}

double recomposed(const ErrorBudget& b, const Composition& c, const std::function<double(std::size_t, double)>& change) {
  return recomposed_all(c, change).signals.at(b.worst_signal);
}

/// What would shrink a prediction beyond the tolerance: only a change that,
/// composed from the shares measured on copies, moves it by at least a tenth
/// of its excess.
void advise(ErrorBudget& b, const Composition& c, double tolerance) {
  const double nominal = b.nominal.at(b.worst_signal), worst = b.predicted.at(b.worst_signal);
  if (nominal > tolerance)
    b.advice.push_back(fmt::format("with perfect components the circuit errs {:.3g} % already: the blocks' own "
                                   "imperfections (bandwidth, diode corners, δ, hysteresis) or the scaling (β, k0) "
                                   "dominate, not the tolerances",
                                   100 * nominal));
  const double excess = worst - tolerance;
  if (excess <= 0) return;
  const auto worth = [&](double after) { return worst - after >= 0.1 * excess; };
  if (const std::size_t d = c.index(b.dominant); d < c.model.components.size()) {
    const double without = recomposed(b, c, [&](std::size_t k, double x) { return k == d ? 0.0 : x; });
    if (worth(without) && c.offset[d])
      b.advice.push_back(fmt::format("trim the offset of {}: the budget of {} falls from {:.3g} % to {:.3g} %",
                                     b.dominant.substr(7), to_string(b.worst_signal), 100 * worst, 100 * without));
    else if (worth(without))
      b.advice.push_back(fmt::format("set the potentiometers finer: the budget of {} falls from {:.3g} % to {:.3g} %",
                                     to_string(b.worst_signal), 100 * worst, 100 * without));
  }
  if (b.offset_rms_volts <= 0) return;
  const double trimmed = recomposed(b, c, [&](std::size_t k, double x) { return c.offset[k] ? x / 10 : x; });
  if (worth(trimmed))
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

namespace {

/// One component's share from its RMS-size runs (one per sign): how far
/// they move each signal (the larger of both signs) and change its error.
ComponentShare share_of(const std::string& component, const std::map<Signal, double>& nominal,
                        const verify::VerifyResult& perfect, const std::vector<const VariantRun*>& runs) {
  ComponentShare share{component, {}, {}};
  for (const auto& [signal, e0] : nominal) {
    double most = 0, farthest = 0;
    for (const VariantRun* run : runs) {
      if (!run->result) continue;
      const double change = std::abs(signal_errors(*run->result).at(signal) - e0);
      most = std::max(most, change);
      const std::map<Signal, double> moved = displacement(perfect, *run->result);
      const auto it = moved.find(signal);
      farthest = std::max({farthest, change, it == moved.end() ? 0.0 : it->second});
    }
    share.error[signal] = most;
    share.moved[signal] = farthest;
  }
  return share;
}

double farthest(const ComponentShare& s) {
  double most = 0;
  for (const auto& [signal, e] : s.moved) most = std::max(most, e);
  return most;
}

/// The components worth a second size (plan order): the kTwice heaviest
/// shares among those moving some signal by a tenth of the tolerance, whose
/// largest size lies beyond the RMS size.
std::vector<std::size_t> heaviest(const Plan& p, const std::vector<ComponentShare>& shares, double tolerance) {
  std::vector<std::size_t> k;
  for (std::size_t i = 0; i < shares.size(); ++i)
    if (farthest(shares[i]) >= 0.1 * tolerance && p.components[i].largest > 1.05 * p.components[i].rms) k.push_back(i);
  std::sort(k.begin(), k.end(), [&](std::size_t a, std::size_t b) { return farthest(shares[a]) > farthest(shares[b]); });
  if (k.size() > kTwice) k.resize(kTwice);
  std::sort(k.begin(), k.end());
  return k;
}

/// The runs of component k (both signs) within runs of `which` components at one size.
std::vector<const VariantRun*> runs_of(const Plan& p, const std::vector<VariantRun>& runs,
                                       const std::vector<std::size_t>& which, std::size_t k) {
  std::vector<const VariantRun*> out;
  const auto at = std::find(which.begin(), which.end(), k);
  if (at == which.end()) return out;
  for (int s = 0; s < p.signs; ++s) out.push_back(&runs[(at - which.begin()) * p.signs + s]);
  return out;
}

/// The perfect traces, every component's measured departures, and the
/// machines drawn as the Monte Carlo draws them.
Composition compose(const Plan& p, const verify::VerifyResult& perfect, const circuit::Circuit& shape,
                    const std::vector<std::vector<VariantRun>>& runs, const std::vector<std::vector<std::size_t>>& which) {
  Composition c{trace_model(perfect), {}, {}};
  std::vector<std::size_t> included;
  for (std::size_t k = 0; k < p.components.size(); ++k) {
    std::vector<double> values;
    std::vector<Departures> measured_departures;
    for (std::size_t size = 0; size < runs.size(); ++size) {
      const std::vector<double> xs = sizes(p, size == 0 ? p.components[k].rms : p.components[k].largest);
      const std::vector<const VariantRun*> measured = runs_of(p, runs[size], which[size], k);
      for (std::size_t s = 0; s < measured.size(); ++s)
        if (measured[s]->result) values.push_back(xs[s]), measured_departures.push_back(departures(c.model, *measured[s]->result));
    }
    if (values.empty()) continue;
    add_component(c.model, p.components[k].name, std::move(values), std::move(measured_departures));
    c.offset.push_back(!p.components[k].subckt.empty());
    included.push_back(k);
  }
  for (std::size_t i = 0; i < kMachines; ++i) {
    const std::vector<double> all = machine_values(p, draw_components(shape, draw_seed(1, i)));
    std::vector<double>& values = c.machines.emplace_back();
    for (std::size_t k : included) values.push_back(all[k]);
  }
  return c;
}

/// The prediction: each signal's p90 over the composed machines, and the
/// p90 of each machine's worst; beside it the root-sum-square estimate.
void predict(ErrorBudget& b, const Composition& c) {
  const ComposedP90 p90 = composed_p90(c.model, c.machines);
  b.machines = p90.machines;
  b.worst_machine = p90.worst;
  double worst = -1;
  for (const auto& [signal, e0] : b.nominal) {
    double sum = 0;
    for (const ComponentShare& s : b.shares) sum += s.moved.at(signal) * s.moved.at(signal);
    b.rss[signal] = e0 + std::sqrt(sum);
    const auto it = p90.signals.find(signal);
    b.predicted[signal] = it == p90.signals.end() ? e0 : it->second;
    if (b.predicted[signal] > worst) worst = b.predicted[signal], b.worst_signal = signal;
  }
}

/// The component whose removal from every composed machine lowers the p90
/// of each machine's worst signal most, among the kTwice whose shares in the
/// worst signal weigh most: what ablation (removing it) confirms.
std::string dominant(const ErrorBudget& b, const Composition& c) {
  std::vector<const ComponentShare*> heaviest;
  for (const ComponentShare& s : b.shares) heaviest.push_back(&s);
  std::sort(heaviest.begin(), heaviest.end(), [&](const ComponentShare* x, const ComponentShare* y) {
    return x->moved.at(b.worst_signal) > y->moved.at(b.worst_signal);
  });
  if (heaviest.size() > kTwice) heaviest.resize(kTwice);
  std::string best = heaviest.empty() ? std::string() : heaviest.front()->component;
  double lowest = b.worst();
  for (const ComponentShare* s : heaviest) {
    const std::size_t k = c.index(s->component);
    if (k >= c.model.components.size()) continue;
    const double without = recomposed_all(c, [&](std::size_t j, double x) { return j == k ? 0.0 : x; }).worst;
    if (without < lowest) lowest = without, best = s->component;
  }
  return best;
}

}  // namespace

ErrorBudget error_budget(const Scene& scene, verify::VerifyOptions base, unsigned workers) {
  base.level = circuit::Level::hardware;
  ErrorBudget b;
  b.scene = scene.name;
  b.machine = scene.machine.name;
  b.offset_rms_volts = offset_rms(scene.machine.amplifier);
  circuit::Circuit shape;  // the circuit verify builds: its amplifiers and settings
  // Build once through a variant that records the circuit; it is the perfect run itself.
  std::vector<Variant> first{{"perfect components", [&](verify::VerifyOptions& o) {
                                perfect()(o);
                                also_alter(o, [&](circuit::Circuit& c) { shape = c; });
                              }}};
  std::vector<VariantRun> start = run_variants(scene, base, first, 1, "gearpatch budget (perfect deck)");
  if (!start[0].result) throw Error(fmt::format("error budget: the deck with perfect components failed: {}", start[0].failure));
  const verify::VerifyResult& perfect_run = *start[0].result;
  b.nominal = signal_errors(perfect_run);
  const Plan p = plan(shape);
  std::vector<std::vector<std::size_t>> which(1, std::vector<std::size_t>(p.components.size()));
  std::iota(which[0].begin(), which[0].end(), 0);
  std::vector<std::vector<VariantRun>> runs{run_variants(scene, base, variants(p, which[0], false), workers, "gearpatch budget")};
  for (std::size_t k = 0; k < p.components.size(); ++k)
    b.shares.push_back(share_of(p.components[k].name, b.nominal, perfect_run, runs_of(p, runs[0], which[0], k)));
  const double tolerance = base.tolerance.value_or(verify::default_tolerance(circuit::Level::hardware));
  which.push_back(heaviest(p, b.shares, tolerance));
  runs.push_back(run_variants(scene, base, variants(p, which[1], true), workers, "gearpatch budget (largest sizes)"));
  for (std::size_t k : which[1]) b.twice.push_back(p.components[k].name);
  b.runs = 1;
  for (const std::vector<VariantRun>& size : runs)
    for (const VariantRun& run : size) {
      ++b.runs;
      if (!run.result) b.failed.push_back(run.failure);
    }
  const Composition c = compose(p, perfect_run, shape, runs, which);
  predict(b, c);
  std::sort(b.shares.begin(), b.shares.end(),
            [](const ComponentShare& x, const ComponentShare& y) { return x.largest() > y.largest(); });
  b.dominant = dominant(b, c);
  advise(b, c, tolerance);
  return b;
}

std::string to_table(const ErrorBudget& b) {
  std::string t = fmt::format("error budget of {} on {} (offsets of {:.3g} mV RMS, random sign): the p90 over {} "
                              "machines drawn as the Monte Carlo draws them, each composed from the perfect deck's "
                              "traces and how far each tolerance alone moves them\n",
                              b.scene, b.machine, 1e3 * b.offset_rms_volts, b.machines);
  t += fmt::format("{:<32}", "% of full scale");
  for (const auto& [signal, e] : b.nominal) t += fmt::format(" {:>9}", to_string(signal));
  t += fmt::format("\n{:<32}", "perfect components");
  for (const auto& [signal, e] : b.nominal) t += fmt::format(" {:>9.3f}", 100 * e);
  for (const ComponentShare& s : b.shares) {
    if (s.largest() < 1e-3 * b.worst() && &s != &b.shares.front()) continue;
    t += fmt::format("\n{:<32}", s.component);
    for (const auto& [signal, e] : s.moved) t += fmt::format(" {:>9.3f}", 100 * e);
  }
  t += fmt::format("\n{:<32}", "nominal + RSS of the shares");
  for (const auto& [signal, e] : b.rss) t += fmt::format(" {:>9.3f}", 100 * e);
  t += fmt::format("\n{:<32}", "predicted (p90 of the machines)");
  for (const auto& [signal, e] : b.predicted) t += fmt::format(" {:>9.3f}", 100 * e);
  t += fmt::format("\nworst signal of each machine: p90 {:.3g} %", 100 * b.worst());
  t += fmt::format("\n{} ngspice runs: the perfect deck, each tolerance at its RMS size", b.runs);
  if (!b.twice.empty()) {
    t += ", and at its largest size";
    for (const std::string& c : b.twice) t += (&c == &b.twice.front() ? " " : ", ") + c;
  }
  t += fmt::format("\ndominant: {} (in {}, predicted {:.3g} %; removed from every machine it lowers the worst p90 most)\n", b.dominant,
                   to_string(b.worst_signal), 100 * b.predicted.at(b.worst_signal));
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
          {"method", "p90 over machines drawn as the Monte Carlo draws them (seed 1), each composed as the perfect deck's traces shifted by every tolerance's time shift of them plus what each moves beyond that shift, measured one at a time at its RMS size (both signs; the heaviest also at the largest size) and interpolated at the drawn value, proportional tolerances added and those whose departure is an event (out of proportion between the two sizes) counted once (per point and direction the farthest), judged in verify's tube; a share is how far the component alone at its RMS size moves the signal against the perfect deck's (verify's tube, best time shift)"},
          {"offset_rms_volts", b.offset_rms_volts},
          {"nominal", by_signal(b.nominal)},
          {"shares", shares},
          {"predicted", by_signal(b.predicted)},
          {"rss", by_signal(b.rss)},
          {"machines", b.machines},
          {"runs", b.runs},
          {"twice", b.twice},
          {"worst_signal", to_string(b.worst_signal)},
          {"worst", b.worst()},
          {"dominant", b.dominant},
          {"advice", b.advice},
          {"failed", b.failed}};
}

}  // namespace gearpatch::component_spread
