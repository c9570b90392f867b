#include "component_spread/composed_machines.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "common/error.h"
#include "model/gear_model.h"
#include "component_spread/monte_carlo_summary.h"
#include "verify/tube.h"
#include "verify/verify.h"

namespace gearpatch::component_spread {
namespace {

/// `y` over `t` linearly interpolated at the ascending times `at`, held past its ends.
std::vector<double> resample(const std::vector<double>& t, const std::vector<double>& y, const std::vector<double>& at) {
  std::vector<double> out(at.size());
  std::size_t j = 0;
  for (std::size_t i = 0; i < at.size(); ++i) {
    while (j + 1 < t.size() && t[j + 1] <= at[i]) ++j;
    if (at[i] <= t.front() || j + 1 >= t.size()) {
      out[i] = at[i] <= t.front() ? y.front() : y.back();
      continue;
    }
    const double span = t[j + 1] - t[j];
    out[i] = span > 0 ? y[j] + (at[i] - t[j]) / span * (y[j + 1] - y[j]) : y[j + 1];
  }
  return out;
}

/// The perfect trace of one signal as a polyline, looked up near a known index.
struct Polyline {
  const std::vector<double>& t;
  const std::vector<double>& y;

  /// The value at `at`, searching from index `i` (the segment nearest), held past the ends.
  double at(double x, std::size_t i) const {
    if (x <= t.front()) return y.front();
    if (x >= t.back()) return y.back();
    while (i + 1 < t.size() && t[i + 1] <= x) ++i;
    while (i > 0 && t[i] > x) --i;
    const double span = t[i + 1] - t[i];
    return span > 0 ? y[i] + (x - t[i]) / span * (y[i + 1] - y[i]) : y[i + 1];
  }
};

/// The point of the polyline nearest to (x, value) in verify's tube
/// geometry (time in units of `window`, value in units of `width`), within
/// ±window of x: the shift τ = x − its time and the excess = value − its
/// value. A steep trace a little late is a shift; a flat one moved, an excess.
std::pair<double, double> shift_and_excess(const Polyline& p, double x, double value, double window, double width) {
  const std::size_t n = p.t.size();
  std::size_t i = std::upper_bound(p.t.begin(), p.t.end(), x) - p.t.begin();
  i = i == 0 ? 0 : std::min(i - 1, n - 1);
  double best_shift = 0, best_excess = value - p.at(x, i);
  double best = std::pow(best_excess / width, 2);
  const auto consider = [&](std::size_t k) {  // the segment [k, k + 1], within ±window of x
    const double u0 = std::max(p.t[k], x - window), u1 = std::min(p.t[k + 1], x + window);
    if (u1 < u0) return;
    const double U0 = (u0 - x) / window, V0 = (p.at(u0, k) - value) / width;
    const double dU = (u1 - u0) / window, dV = (p.at(u1, k) - p.at(u0, k)) / width;
    const double length = dU * dU + dV * dV;
    const double s = length > 0 ? std::clamp(-(U0 * dU + V0 * dV) / length, 0.0, 1.0) : 0.0;
    const double U = U0 + s * dU, V = V0 + s * dV;
    if (U * U + V * V < best) best = U * U + V * V, best_shift = -U * window, best_excess = -V * width;
  };
  for (std::size_t k = i; k + 1 < n && (p.t[k] - x) / window < std::min(1.0, std::sqrt(best)); ++k) consider(k);
  for (std::size_t k = i; k > 0 && (x - p.t[k]) / window < std::min(1.0, std::sqrt(best)); --k) consider(k - 1);
  return {best_shift, best_excess};
}

/// Where a component's value lies among its measured values: the segment's
/// two departures and their weights (beyond the ends, the last segment
/// continued), and whether the component's departure is an event.
struct Blend {
  const Departure* below = nullptr;
  const Departure* above = nullptr;
  double weight_below = 0, weight_above = 0;
  bool event = false;

  double shift(std::size_t i) const { return weight_below * below->shift[i] + weight_above * above->shift[i]; }
  double excess(std::size_t i) const { return weight_below * below->excess[i] + weight_above * above->excess[i]; }
};

Blend blend(const ComponentResponse& c, Signal signal, double x) {
  const std::vector<double>& v = c.values;
  if (v.size() < 2) return {};
  std::size_t j = std::upper_bound(v.begin(), v.end(), x) - v.begin();
  j = std::clamp<std::size_t>(j, 1, v.size() - 1);
  const double w = (x - v[j - 1]) / (v[j] - v[j - 1]);
  return {&c.departure[j - 1].at(signal), &c.departure[j].at(signal), 1 - w, w, c.event};
}

/// The largest distance of a departure from the perfect trace in the tube's
/// geometry: its shift in units of the time window, its excess in units of the value width.
double reach(const Departure& d, double window, double width) {
  double most = 0;
  for (std::size_t i = 0; i < d.shift.size(); ++i) most = std::max(most, std::hypot(d.shift[i] / window, d.excess[i] / width));
  return most;
}

/// How a component's departure of `signal` grows from the smaller to the
/// larger measured size of each sign (their reaches summed over the signs),
/// and the ratio of the sizes; {0, 0} when no sign was measured at two sizes.
std::pair<double, double> growth(const ComponentResponse& c, Signal signal, double window, double width) {
  double small = 0, large = 0, ratio = 0;
  for (const int sign : {-1, 1}) {
    std::size_t a = c.values.size(), b = a;  // the smallest and the largest measured size of this sign
    for (std::size_t k = 0; k < c.values.size(); ++k) {
      if (c.values[k] * sign <= 0) continue;
      if (a == c.values.size() || std::abs(c.values[k]) < std::abs(c.values[a])) a = k;
      if (b == c.values.size() || std::abs(c.values[k]) > std::abs(c.values[b])) b = k;
    }
    if (a == c.values.size() || std::abs(c.values[b]) < 1.05 * std::abs(c.values[a])) continue;
    small += reach(c.departure[a].at(signal), window, width);
    large += reach(c.departure[b].at(signal), window, width);
    ratio = std::abs(c.values[b] / c.values[a]);
  }
  if (ratio == 0 || small == 0) return {0, 0};
  return {large / small, ratio};
}

/// Whether a component's departure is an event rather than a change in
/// proportion to its value: in some signal, from its smaller to its larger
/// measured size, the departure grows by less than √ratio (the same event
/// at both sizes: it saturates) or by more than ratio^1.5 (an event appears
/// past a threshold between them); a proportional change grows by the ratio.
bool is_event(const ComponentResponse& c, const TraceModel& m) {
  for (const auto& [signal, trace] : m.perfect) {
    const auto width = m.width.find(signal);
    const auto [grows, ratio] = growth(c, signal, m.shift, width == m.width.end() ? m.full_scale.at(signal) : width->second);
    if (ratio > 0 && (grows < std::sqrt(ratio) || grows > std::pow(ratio, 1.5))) return true;
  }
  return false;
}

/// One signal's departure at one point of a composed machine: the
/// proportional components' departures add; the events count once (several
/// offsets that each alone change the motion's course change it once, not
/// several times over): per direction the farthest of their shifts and of
/// their excesses.
struct PointDeparture {
  double shift = 0, excess = 0;
  double shift_up = 0, shift_down = 0, excess_up = 0, excess_down = 0;

  void add(const Blend& b, std::size_t i) {
    const double s = b.shift(i), e = b.excess(i);
    if (!b.event) {
      shift += s, excess += e;
      return;
    }
    shift_up = std::max(shift_up, s), shift_down = std::min(shift_down, s);
    excess_up = std::max(excess_up, e), excess_down = std::min(excess_down, e);
  }
  double total_shift() const { return shift + shift_up + shift_down; }
  double total_excess() const { return excess + excess_up + excess_down; }
};

}  // namespace

TraceModel trace_model(const verify::VerifyResult& perfect) {
  TraceModel m;
  m.t = perfect.circuit.t;
  m.shift = perfect.comparison.time_tolerance;
  const GearModel model(perfect.gear);
  for (const verify::SignalError& e : perfect.comparison.signals) {
    const auto trace = perfect.circuit.signals.find(e.signal);
    if (trace == perfect.circuit.signals.end()) continue;
    const auto [rt, ry] = verify::reference_curve(perfect.reference, model, e.signal);
    const verify::Tube tube(rt, ry, {perfect.comparison.time_tolerance, 0});
    std::vector<double>&low = m.low[e.signal], &high = m.high[e.signal];
    for (double at : m.t) {
      const auto [lo, hi] = tube.range(at);
      low.push_back(lo), high.push_back(hi);
    }
    m.perfect[e.signal] = trace->second;
    m.full_scale[e.signal] = e.full_scale;
    m.width[e.signal] = perfect.tolerance * e.full_scale;
  }
  return m;
}

Departures departures(const TraceModel& m, const verify::VerifyResult& variant) {
  Departures out;
  for (const auto& [signal, perfect] : m.perfect) {
    const auto trace = variant.circuit.signals.find(signal);
    Departure& d = out[signal];
    if (trace == variant.circuit.signals.end() || variant.circuit.t.empty()) {
      d.shift.assign(m.t.size(), 0.0), d.excess.assign(m.t.size(), 0.0);
      continue;
    }
    const Polyline p{m.t, perfect};
    std::vector<double> shift, excess;
    for (std::size_t j = 0; j < trace->second.size(); ++j) {
      const auto [tau, beyond] = shift_and_excess(p, variant.circuit.t[j], trace->second[j], m.shift, m.width.at(signal));
      shift.push_back(tau), excess.push_back(beyond);
    }
    d.shift = resample(variant.circuit.t, shift, m.t);
    d.excess = resample(variant.circuit.t, excess, m.t);
  }
  return out;
}

void add_component(TraceModel& m, const std::string& component, std::vector<double> values,
                   std::vector<Departures> measured) {
  if (values.size() != measured.size() || values.empty())
    throw Error("a component's response needs one departure per measured value", Error::Kind::internal);
  values.push_back(0);
  Departures none;
  for (const auto& [signal, trace] : m.perfect) none[signal] = {std::vector<double>(m.t.size()), std::vector<double>(m.t.size())};
  measured.push_back(std::move(none));
  std::vector<std::size_t> order(values.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  ComponentResponse c{component, {}, {}, false};
  for (std::size_t k : order) {
    if (!c.values.empty() && values[k] == c.values.back()) continue;
    c.values.push_back(values[k]);
    c.departure.push_back(std::move(measured[k]));
  }
  c.event = is_event(c, m);
  m.components.push_back(std::move(c));
}

std::map<Signal, double> composed_errors(const TraceModel& m, const std::vector<double>& values) {
  if (values.size() != m.components.size())
    throw Error("a composed machine needs one value per component", Error::Kind::internal);
  std::map<Signal, double> out;
  std::vector<Blend> blends;
  for (const auto& [signal, perfect] : m.perfect) {
    blends.clear();
    for (std::size_t k = 0; k < values.size(); ++k)
      if (values[k] != 0) blends.push_back(blend(m.components[k], signal, values[k]));
    const std::vector<double>&low = m.low.at(signal), &high = m.high.at(signal);
    const Polyline p{m.t, perfect};
    double worst = 0;
    for (std::size_t i = 0; i < m.t.size(); ++i) {
      PointDeparture d;
      for (const Blend& b : blends)
        if (b.below) d.add(b, i);
      const double shift = d.total_shift(), excess = d.total_excess();
      const double y = (shift == 0 ? perfect[i] : p.at(m.t[i] - shift, i)) + excess;
      worst = std::max({worst, low[i] - y, y - high[i]});
    }
    out[signal] = worst / m.full_scale.at(signal);
  }
  return out;
}

ComposedP90 composed_p90(const TraceModel& m, const std::vector<std::vector<double>>& machines) {
  std::map<Signal, std::vector<double>> errors;
  std::vector<double> worst;
  for (const std::vector<double>& values : machines) {
    double most = 0;
    for (const auto& [signal, e] : composed_errors(m, values)) {
      errors[signal].push_back(e);
      most = std::max(most, e);
    }
    worst.push_back(most);
  }
  ComposedP90 out;
  out.machines = machines.size();
  for (const auto& [signal, e] : errors) out.signals[signal] = quantile(e, 0.9);
  out.worst = quantile(worst, 0.9);
  return out;
}

}  // namespace gearpatch::component_spread
