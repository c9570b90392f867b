#include "verify/trace_likeness.h"

#include <cmath>
#include <fmt/format.h>
#include <map>

#include "verify/compare.h"
#include "verify/tube.h"

namespace gearpatch::verify {
namespace {

/// A recording's signals against the reference's, in machine units.
class Likeness {
 public:
  Likeness(const MeasuredTrace& m, const Trajectory& ref, const GearModel& model, const circuit::Circuit& c,
           double duration)
      : m_(m), beta_(c.beta), duration_(duration) {
    for (Signal s : all_signals) {
      auto [t, y] = reference_curve(ref, model, s);
      for (double& v : y) v /= c.probes.at(s).full_scale;
      tubes_.emplace(s, Tube(std::move(t), std::move(y), {0, 0}));
    }
  }

  /// rms of the recorded `s` against `factor` × the reference of `as`, with
  /// machine time `time_factor` × the sheet's (real time = machine time / (time_factor·β)).
  double rms(Signal s, Signal as, double factor, double time_factor) const {
    const auto& mu = m_.machine_units.at(s);
    const Tube& ref = tubes_.at(as);
    double sum = 0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < m_.machine_t.size(); ++i) {
      const double real = m_.machine_t[i] / (time_factor * beta_);
      if (real > duration_) break;
      const double d = mu[i] - factor * ref.reference(real);
      sum += d * d, ++n;
    }
    return n < 2 ? INFINITY : std::sqrt(sum / static_cast<double>(n));
  }

  /// rms over every recorded signal at a time scale.
  double rms_all(double time_factor) const {
    double sum = 0;
    for (const auto& r : m_.readings) sum += std::pow(rms(r.signal, r.signal, 1, time_factor), 2);
    return std::sqrt(sum / static_cast<double>(m_.readings.size()));
  }

 private:
  const MeasuredTrace& m_;
  double beta_, duration_;
  std::map<Signal, Tube> tubes_;
};

std::string pct(double x) { return fmt::format("{:.3g} %", 100 * x); }

/// The time factor that fits best: a coarse log grid over 1/20 .. 20, then a fine one around its best.
std::pair<double, double> best_time_factor(const Likeness& like) {
  double best = 1, best_rms = like.rms_all(1);
  for (int i = -130; i <= 130; ++i)
    if (const double k = std::pow(10.0, i / 100.0), e = like.rms_all(k); e < best_rms) best = k, best_rms = e;
  const double around = best;
  for (int i = -50; i <= 50; ++i)
    if (const double k = around * (1 + i / 1000.0), e = like.rms_all(k); e < best_rms) best = k, best_rms = e;
  return {best, best_rms};
}

}  // namespace

std::vector<std::string> what_the_trace_looks_like(const MeasuredTrace& m, const Trajectory& reference,
                                                   const GearModel& model, const circuit::Circuit& circuit,
                                                   double duration, double tolerance) {
  const Likeness like(m, reference, model, circuit, duration);
  const auto matches = [&](double hypothesis, double as_read) {
    return hypothesis <= tolerance && hypothesis < 0.5 * as_read;
  };
  std::vector<std::string> out;
  std::map<Signal, std::pair<Signal, double>> holds;  // recorded signal → the reference it matches, its sign
  std::map<Signal, double> as_read;
  for (const auto& r : m.readings) as_read[r.signal] = like.rms(r.signal, r.signal, 1, 1);
  for (const auto& r : m.readings) {
    const Signal s = r.signal;
    if (as_read[s] <= tolerance) continue;
    if (const double inverted = like.rms(s, s, -1, 1); matches(inverted, as_read[s])) {
      out.push_back(fmt::format("{} matches -1 × the reference (rms {} of full scale, as read {}): the channel {} "
                                "is inverted; watch the other output of its amplifier or give --channel {}={}{}",
                                to_string(s), pct(inverted), pct(as_read[s]), r.channel, to_string(s),
                                r.sign > 0 ? "-" : "", r.channel));
      continue;
    }
    for (Signal other : all_signals)
      for (double sign : {1.0, -1.0})
        if (other != s && !holds.count(s))
          if (const double e = like.rms(s, other, sign, 1); matches(e, as_read[s])) holds[s] = {other, sign};
  }
  const auto channel_of = [&](Signal s) {
    for (const auto& r : m.readings)
      if (r.signal == s) return r.channel;
    return std::string("?");
  };
  for (const auto& [s, held] : holds) {
    const auto back = holds.find(held.first);
    if (back != holds.end() && back->second.first == s) {
      if (s < held.first)
        out.push_back(fmt::format("{} and {} are swapped: {} (read as {}) holds {} and {} (read as {}) holds {}; "
                                  "give --channel {}={} --channel {}={}",
                                  channel_of(s), channel_of(held.first), channel_of(s), to_string(s),
                                  to_string(held.first), channel_of(held.first), to_string(held.first), to_string(s),
                                  to_string(s), channel_of(held.first), to_string(held.first), channel_of(s)));
    } else {
      out.push_back(fmt::format("{} (read as {}) matches {}{}'s reference: the probe is on the wrong output",
                                channel_of(s), to_string(s), held.second < 0 ? "-1 × " : "", to_string(held.first)));
    }
  }
  if (out.empty()) {
    // Two digits: the start found from the trace and its noise move the best factor by up to a percent.
    const double read = like.rms_all(1);
    const auto [k, e] = best_time_factor(like);
    if (matches(e, read) && std::abs(std::log(k)) > std::log(1 + std::max(tolerance, 0.01)))
      out.push_back(fmt::format("the recording matches the reference with the machine's time running {:.2g} × {} "
                                "than the sheet's (beta {:.6g} instead of {:.6g}; rms {}, as read {}): another time "
                                "scale; check the integrators' time constant and the mode (IC/OP) timing",
                                k >= 1 ? k : 1 / k, k >= 1 ? "slower" : "faster", k * circuit.beta, circuit.beta,
                                pct(e), pct(read)));
  }
  return out;
}

}  // namespace gearpatch::verify
