#include "verify/compare.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "common/error.h"

#include "verify/tube.h"

namespace gearpatch::verify {
namespace {

bool frictionless_and_free(const GearParameters& p) {
  return !p.primary_has_friction() && !p.secondary_has_friction() && p.drive_torque == 0 &&
         p.load_torque == 0;
}

double signal_of(Signal signal, const GearModel& model, const Mode& mode, const GearState& s) {
  return value({0, s.omega_p, s.omega_s, s.dphi, model.torque(mode, s)}, signal);
}

/// Largest error at equal times, the reference interpolated at the circuit's points.
void pointwise(const std::vector<double>& rt, const std::vector<double>& ry, const std::vector<double>& ct,
               const std::vector<double>& cy, SignalError& e) {
  const Tube exact(rt, ry, {0, 0});
  for (std::size_t i = 0; i < ct.size(); ++i)
    e.pointwise_error = std::max(e.pointwise_error, std::abs(cy[i] - exact.reference(ct[i])) / e.full_scale);
}

/// RMS of the amplitude error over the circuit's points.
double rms_distance(const Tube& tube, const std::vector<double>& ct, const std::vector<double>& cy) {
  double sum = 0;
  for (std::size_t i = 0; i < ct.size(); ++i) {
    const auto [lo, hi] = tube.range(ct[i]);
    const double d = std::max({0.0, lo - cy[i], cy[i] - hi});
    sum += d * d;
  }
  return std::sqrt(sum / std::max<std::size_t>(ct.size(), 1));
}

double momentum_drift(const Trajectory& ref, const CircuitTrace& c, const GearParameters& p) {
  const auto& wp = c.signals.at(Signal::omega_p);
  const auto& ws = c.signals.at(Signal::omega_s);
  const double p0 = p.inertia_primary * ref.samples.front().omega_p +
                    p.inertia_secondary * ref.samples.front().omega_s;
  const double scale = std::max(std::abs(p0), 1e-300);
  double drift = 0;
  for (std::size_t i = 0; i < wp.size(); ++i)
    drift = std::max(drift, std::abs(p.inertia_primary * wp[i] + p.inertia_secondary * ws[i] - p0) / scale);
  return drift;
}

}  // namespace

std::pair<std::vector<double>, std::vector<double>> reference_curve(const Trajectory& ref, const GearModel& model,
                                                                    Signal signal) {
  std::vector<double> t, y;
  auto event = ref.events.begin();
  for (const Sample& s : ref.samples) {
    for (; event != ref.events.end() && event->t <= s.t; ++event) {
      t.push_back(event->t), y.push_back(signal_of(signal, model, event->mode_before, event->before));
      // Flanks meeting: the contact's first instant at the speeds before, which
      // differ from those after when a self-locking gear catches the secondary.
      if (event->mode_after.contact != event->mode_before.contact && event->mode_after.contact != Contact::free)
        t.push_back(event->t), y.push_back(signal_of(signal, model, event->mode_after, event->before));
      t.push_back(event->t), y.push_back(signal_of(signal, model, event->mode_after, event->after));
    }
    t.push_back(s.t), y.push_back(value(s, signal));
  }
  // A contact shorter than the grid step peaks between samples: its closed-form
  // peak torque and twist become vertices, so the tube holds the true peak.
  for (const ContactRecord& c : ref.contacts) {
    const Extremum* peak = signal == Signal::m0 ? &c.torque : signal == Signal::dphi ? &c.twist : nullptr;
    if (!peak || t.empty() || peak->t < t.front() || peak->t > t.back()) continue;
    const auto at = std::upper_bound(t.begin(), t.end(), peak->t) - t.begin();
    t.insert(t.begin() + at, peak->t), y.insert(y.begin() + at, peak->value);
  }
  return {t, y};
}

Comparison compare(const Trajectory& ref, const CircuitTrace& c, const GearModel& model,
                   const CompareSettings& settings) {
  // verify refuses such simulator output first, so reaching here with one is a bug.
  for (const auto& [signal, values] : c.signals)
    if (c.t.empty() || values.size() != c.t.size())
      throw Error(fmt::format("comparing a trace of {} times and {} values of {}", c.t.size(), values.size(),
                              to_string(signal)), Error::Kind::internal);
  Comparison out;
  out.time_tolerance = settings.tolerance * settings.duration;
  for (const auto& [signal, scale] : settings.full_scales) {
    const auto [rt, ry] = reference_curve(ref, model, signal);
    const Tube tube(rt, ry, {out.time_tolerance, settings.tolerance * scale});
    const TubeFit fit = tube.fit(c.t, c.signals.at(signal));
    SignalError e;
    e.signal = signal, e.full_scale = scale;
    e.max_error = fit.worst_distance / scale;
    e.time_of_max = fit.time_of_worst;
    e.reference_at_max = fit.reference_at_worst;
    e.circuit_at_max = fit.compared_at_worst;
    e.outside = fit.outside;
    e.failed_spans = fit.failed_spans;
    pointwise(rt, ry, c.t, c.signals.at(signal), e);
    e.rms_error = rms_distance(tube, c.t, c.signals.at(signal)) / scale;
    out.signals.push_back(e);
  }
  // A recording may lack a channel: its impacts need all four signals, the momentum both speeds.
  const bool all_four = std::all_of(all_signals.begin(), all_signals.end(), [&](Signal s) { return c.signals.count(s); });
  MatchLimits limits{settings.grazing_depth, out.time_tolerance, settings.duration};
  limits.hysteresis = settings.contact_hysteresis;
  const auto scale_of = [&](Signal signal) {
    for (const auto& [s, scale] : settings.full_scales)
      if (s == signal) return scale;
    return 0.0;
  };
  // An unmatched contact that changes no judged signal beyond the tolerance is grazing.
  limits.torque_effect = settings.tolerance * scale_of(Signal::m0);
  limits.speed_effect_p = settings.tolerance * scale_of(Signal::omega_p);
  limits.speed_effect_s = settings.tolerance * scale_of(Signal::omega_s);
  if (all_four) out.impacts = match_impacts(ref, c, model, limits);
  const auto m0 = std::find_if(settings.full_scales.begin(), settings.full_scales.end(),
                               [](const auto& s) { return s.first == Signal::m0; });
  for (Impact& i : out.impacts.impacts) {
    if (i.matched() && m0 != settings.full_scales.end())
      i.peak_error = std::abs(i.peak_circuit - i.peak_reference) / m0->second;
    if (i.matched())
      out.worst_impact_shift = std::max(out.worst_impact_shift, std::abs(i.circuit - i.reference) / settings.duration);
    else if (i.reference >= 0 && i.counts())
      out.worst_impact_shift = 1;
    if (i.restitution_circuit >= 0) out.restitution.push_back(i.restitution_circuit);
  }
  if (all_four && frictionless_and_free(model.parameters())) out.momentum_drift = momentum_drift(ref, c, model.parameters());
  return out;
}

}  // namespace gearpatch::verify
