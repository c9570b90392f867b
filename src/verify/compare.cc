#include "verify/compare.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "common/error.h"

namespace gearpatch::verify {
namespace {

/// y(t) linearly interpolated at the times `at` (held constant outside). A
/// trace without points has nothing to interpolate: verify refuses such
/// simulator output first, so reaching here with one is a bug.
std::vector<double> interpolate(const std::vector<double>& t, const std::vector<double>& y,
                                const std::vector<double>& at) {
  if (t.empty() || t.size() != y.size())
    throw Error(fmt::format("interpolating a trace of {} times and {} values", t.size(), y.size()),
                Error::Kind::internal);
  std::vector<double> out;
  out.reserve(at.size());
  for (double x : at) {
    auto hi = std::upper_bound(t.begin(), t.end(), x);
    if (hi == t.begin()) { out.push_back(y.front()); continue; }
    if (hi == t.end()) { out.push_back(y.back()); continue; }
    const std::size_t j = hi - t.begin(), i = j - 1;
    const double w = t[j] > t[i] ? (x - t[i]) / (t[j] - t[i]) : 1.0;
    out.push_back(y[i] + w * (y[j] - y[i]));
  }
  return out;
}

/// Times where |x| crosses `level` outward (outward = true) or inward.
std::vector<double> crossings(const std::vector<double>& t, const std::vector<double>& x, double level,
                              bool outward) {
  std::vector<double> found;
  for (std::size_t i = 1; i < x.size(); ++i) {
    const double a = std::abs(x[i - 1]) - level, b = std::abs(x[i]) - level;
    const bool hit = outward ? (a <= 0 && b > 0) : (a > 0 && b <= 0);
    if (hit) found.push_back(t[i - 1] + (t[i] - t[i - 1]) * (a / (a - b)));
  }
  return found;
}

double value_at(const std::vector<double>& t, const std::vector<double>& y, double x) {
  return interpolate(t, y, {x}).front();
}

bool frictionless_and_free(const GearParameters& p) {
  return !p.primary_has_friction() && !p.secondary_has_friction() && p.drive_torque == 0 &&
         p.load_torque == 0;
}

void compare_impacts(const Trajectory& ref, const CircuitTrace& c, const GearModel& model,
                     double duration, Comparison& out) {
  const double eps = model.parameters().half_backlash;
  if (eps == 0) return;
  const std::vector<double> found = crossings(c.t, c.signals.at(Signal::dphi), eps, true);
  out.circuit_impacts = static_cast<int>(found.size());
  for (const auto& e : ref.events) {
    if (e.kind != GuardKind::contact_positive && e.kind != GuardKind::contact_negative) continue;
    ImpactTime impact{e.t, -1};
    for (double t : found)
      if (impact.circuit < 0 || std::abs(t - e.t) < std::abs(impact.circuit - e.t)) impact.circuit = t;
    out.worst_impact_shift = std::max(
        out.worst_impact_shift, impact.circuit < 0 ? 1.0 : std::abs(impact.circuit - e.t) / duration);
    out.impacts.push_back(impact);
  }
  if (!frictionless_and_free(model.parameters())) return;
  const auto& wp = c.signals.at(Signal::omega_p);
  const auto& ws = c.signals.at(Signal::omega_s);
  const std::vector<double> releases = crossings(c.t, c.signals.at(Signal::dphi), eps, false);
  for (double begin : found) {
    auto end = std::upper_bound(releases.begin(), releases.end(), begin);
    if (end == releases.end()) break;
    const double in = value_at(c.t, wp, begin) - value_at(c.t, ws, begin);
    const double away = value_at(c.t, wp, *end) - value_at(c.t, ws, *end);
    if (in != 0) out.restitution.push_back(-away / in);
  }
}

double signal_of(Signal signal, const GearModel& model, const Mode& mode, const GearState& s) {
  return value({0, s.omega_p, s.omega_s, s.dphi, model.torque(mode, s)}, signal);
}

/// Times at which the reference signal is discontinuous.
std::vector<double> jumps_of(Signal name, const Trajectory& ref, const GearModel& model,
                             double scale) {
  std::vector<double> times;
  for (const auto& e : ref.events) {
    const double before = signal_of(name, model, e.mode_before, e.before);
    const double after = signal_of(name, model, e.mode_after, e.after);
    if (std::abs(after - before) > 1e-9 * scale) times.push_back(e.t);
  }
  return times;
}

}  // namespace

Comparison compare(const Trajectory& ref, const CircuitTrace& c, const GearModel& model,
                   const std::vector<std::pair<Signal, double>>& full_scales, double duration,
                   double jump_window) {
  Comparison out;
  std::vector<double> times;
  for (const Sample& s : ref.samples) times.push_back(s.t);
  for (const auto& [name, scale] : full_scales) {
    std::vector<double> reference;
    for (const Sample& s : ref.samples)
      reference.push_back(value(s, name));
    const std::vector<double> circuit = interpolate(c.t, c.signals.at(name), times);
    SignalError e{name, scale};
    const std::vector<double> jumps = jumps_of(name, ref, model, scale);
    e.jumps = static_cast<int>(jumps.size());
    double sum = 0;
    std::size_t counted = 0;
    for (std::size_t i = 0; i < times.size(); ++i) {
      const bool near_jump = std::any_of(jumps.begin(), jumps.end(), [&](double j) {
        return std::abs(times[i] - j) <= jump_window;
      });
      if (near_jump) {
        ++e.excluded;
        continue;
      }
      ++counted;
      const double error = std::abs(circuit[i] - reference[i]) / scale;
      sum += error * error;
      if (error > e.max_error) {
        e.max_error = error;
        e.time_of_max = times[i];
        e.reference_at_max = reference[i];
        e.circuit_at_max = circuit[i];
      }
    }
    e.rms_error = std::sqrt(sum / std::max<std::size_t>(counted, 1));
    out.signals.push_back(e);
  }
  compare_impacts(ref, c, model, duration, out);
  if (frictionless_and_free(model.parameters())) {
    const auto& p = model.parameters();
    const auto& wp = c.signals.at(Signal::omega_p);
    const auto& ws = c.signals.at(Signal::omega_s);
    const double p0 = p.inertia_primary * ref.samples.front().omega_p +
                      p.inertia_secondary * ref.samples.front().omega_s;
    const double scale = std::max(std::abs(p0), 1e-300);
    out.momentum_drift = 0;
    for (std::size_t i = 0; i < wp.size(); ++i)
      out.momentum_drift = std::max(out.momentum_drift,
                                    std::abs(p.inertia_primary * wp[i] + p.inertia_secondary * ws[i] - p0) / scale);
  }
  return out;
}

}  // namespace gearpatch::verify
