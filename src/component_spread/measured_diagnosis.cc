#include "component_spread/measured_diagnosis.h"

#include <algorithm>
#include <chrono>
#include <fmt/format.h>

#include "component_spread/component_draw.h"

namespace gearpatch::component_spread {
namespace {

double worst_error(const verify::VerifyResult& r) {
  double worst = 0;
  for (const verify::SignalError& e : r.comparison.signals) worst = std::max(worst, e.max_error);
  return worst;
}

Variant circuit_change(std::string name, std::function<void(circuit::Circuit&)> change) {
  return {std::move(name), [change](verify::VerifyOptions& o) { also_alter(o, change); }};
}

/// The changed copies worth running for this circuit.
std::vector<Variant> variants(const circuit::Circuit& c) {
  std::vector<Variant> v;
  if (c.level == circuit::Level::hardware) {
    v.push_back(circuit_change("every amplifier offset zeroed", [](circuit::Circuit& k) {
      for (const circuit::Amplifier& a : k.amplifiers) k.machine.amplifier.offsets_by_name[amplifier_subckt(a)] = 0;
    }));
    for (const circuit::Amplifier& a : c.amplifiers) {
      const std::string subckt = amplifier_subckt(a);
      v.push_back(circuit_change(fmt::format("the offset of {} ({}) alone removed", subckt, a.out),
                                 [subckt](circuit::Circuit& k) { k.machine.amplifier.offsets_by_name[subckt] = 0; }));
    }
    const auto band = [](const circuit::FunctionBlock& b) {
      return b.name == "sign_p" || b.name == "sign_s" || b.name == "lock_char";
    };
    if (std::any_of(c.blocks.begin(), c.blocks.end(), band))
      v.push_back(circuit_change(fmt::format("the ideal friction characteristic (band {:g} MU)",
                                             circuit::friction_band(circuit::Level::ideal)),
                                 [band](circuit::Circuit& k) {
                                   for (circuit::FunctionBlock& b : k.blocks)
                                     if (band(b)) b.parameter = fmt::format("{}", circuit::friction_band(circuit::Level::ideal));
                                 }));
    if (c.uses(circuit::BlockKind::analog_switch))
      v.push_back(circuit_change("ideal switches (1 mΩ closed)",
                                 [](circuit::Circuit& k) { k.machine.switch_resistance = 1e-3; }));
    if (c.uses(circuit::BlockKind::comparator))
      v.push_back(circuit_change("a tenth of the comparator hysteresis",
                                 [](circuit::Circuit& k) { k.machine.comparator_hysteresis /= 10; }));
  }
  const bool has_delta = std::any_of(c.parameters.begin(), c.parameters.end(), [](const auto& p) {
    return p.first == Setting::delta1 || p.first == Setting::delta2;
  });
  if (has_delta)
    v.push_back(circuit_change("comparator offsets δ1, δ2 halved (their margin beyond a)", [](circuit::Circuit& k) {
      // With backlash the contact comparators watch X against a + margin.
      double a = 0;
      for (const auto& [setting, value] : k.parameters)
        if (setting == Setting::a) a = value;
      for (auto& [setting, value] : k.parameters)
        if (setting == Setting::delta1 || setting == Setting::delta2) value = a + (value - a) / 2;
    }));
  v.push_back({"a four times finer ngspice step (tmax/4, reltol/10)", [](verify::VerifyOptions& o) {
                 o.transient.max_step_points *= 4;
                 o.transient.reltol /= 10;
               }});
  return v;
}

/// The variants' ngspice limit: 10 times the judged run's time, at least 5 s.
/// A change that makes a hardware deck chatter (the ideal band on the lock's
/// loop, a tenth of the Schmitt triggers' hysteresis) can force ngspice into
/// tiny steps for minutes (measured on classic, random-2772-010: over 300 s
/// and 146 s against the judged run's 1.3 s); such a run is left out.
verify::VerifyOptions bounded(const verify::VerifyOptions& options, const verify::VerifyResult& failed) {
  verify::VerifyOptions out = options;
  const double seconds = std::max(5.0, 10 * failed.ngspice_seconds);
  const auto limit = std::chrono::milliseconds(static_cast<long long>(1000 * seconds));
  out.limits.timeout = std::min(options.limits.timeout, limit);
  return out;
}

}  // namespace

std::string MeasuredCause::sentence() const {
  return fmt::format("{}: the worst error falls from {:.3g} % to {:.3g} % of full scale{} (measured on a "
                     "changed copy of the deck)",
                     change, 100 * before, 100 * after, passes ? ", and the circuit passes" : "");
}

std::vector<MeasuredCause> diagnose_by_measurement(const Scene& scene, const verify::VerifyOptions& options,
                                                   const verify::VerifyResult& failed, const circuit::Circuit& built,
                                                   unsigned workers) {
  const std::vector<Variant> changes = variants(built);
  const std::vector<VariantRun> runs =
      run_variants(scene, bounded(options, failed), changes, workers, "gearpatch verify: diagnosis");
  const double before = worst_error(failed);
  // A failure by impacts alone has no excess of amplitude: then a tenth of the error itself.
  const double excess = before > failed.tolerance ? before - failed.tolerance : before;
  std::vector<MeasuredCause> causes;
  for (std::size_t i = 0; i < changes.size(); ++i) {
    if (!runs[i].result) continue;
    const MeasuredCause cause{changes[i].name, before, worst_error(*runs[i].result), runs[i].result->passed};
    if (cause.passes || (before - cause.after >= 0.1 * excess && before > cause.after)) causes.push_back(cause);
  }
  std::sort(causes.begin(), causes.end(), [](const MeasuredCause& a, const MeasuredCause& b) {
    return a.after != b.after ? a.after < b.after : a.change < b.change;
  });
  return causes;
}

}  // namespace gearpatch::component_spread
