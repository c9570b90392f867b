#include "scaling/time_scale.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "scaling/maxima.h"
#include "machine/machine_profile.h"

namespace gearpatch {

double comfortable_low(const MachineProfile& m) {
  return m.smallest_setting * *std::min_element(m.weights.begin(), m.weights.end());
}

double comfortable_high(const MachineProfile& m) {
  return *std::max_element(m.weights.begin(), m.weights.end());
}

double max_amplifier_frequency(const MachineProfile& m) {
  const double largest = *std::max_element(m.weights.begin(), m.weights.end());
  const double by_bandwidth = amplifier_phase_lag * 2 * M_PI * m.amplifier.bandwidth_hz / (1 + largest);
  const double by_slew = m.amplifier.slew_volts_per_second / m.unit_volts;
  return std::min(by_bandwidth, by_slew);
}

namespace {

std::vector<std::string> checks(const std::vector<IntegratorRate>& rates, double omega,
                                const MachineProfile& m, double beta) {
  std::vector<std::string> w;
  const double k0 = m.integrator_constant, low = comfortable_low(m);
  for (const auto& r : rates) {
    const double value = r.rate / (beta * k0);
    if (value < low)
      w.push_back(fmt::format("{} = {:.4g} at β = {:g} is below {:g}: a potentiometer set that low "
                              "is hard to set precisely", to_string(r.name), value, beta, low));
  }
  const double limit = max_machine_frequency_per_k0 * k0;
  if (omega / beta > limit)
    w.push_back(fmt::format("the contact oscillation runs at {:.4g} rad/s of machine time at β = {:g}, "
                            "above the {:g} rad/s the machine follows (100·k0); raise β to {:.3g} "
                            "or more", omega / beta, beta, limit, omega / limit));
  const double amplifiers = max_amplifier_frequency(m);
  if (omega / beta > amplifiers)
    w.push_back(fmt::format("the contact oscillation runs at {:.4g} rad/s of machine time at β = {:g}, "
                            "above the {:.4g} rad/s the machine's amplifiers follow (bandwidth {:g} Hz, "
                            "slew {:g} V/s); raise β to {:.3g} or more", omega / beta, beta, amplifiers,
                            m.amplifier.bandwidth_hz, m.amplifier.slew_volts_per_second, omega / amplifiers));
  return w;
}

}  // namespace

TimeScale choose_time_scale(const std::vector<IntegratorRate>& rates, double omega,
                            const MachineProfile& m, std::optional<double> explicit_beta) {
  TimeScale ts;
  if (explicit_beta) {
    ts.beta = *explicit_beta;
    ts.reason = fmt::format("β = {:g} as given (machine.time_scale or --beta)", ts.beta);
    ts.warnings = checks(rates, omega, m, ts.beta);
    return ts;
  }
  const double k0 = m.integrator_constant, high = comfortable_high(m), low = comfortable_low(m);
  auto largest = std::max_element(rates.begin(), rates.end(),
                                  [](const auto& a, const auto& b) { return a.rate < b.rate; });
  auto smallest = std::min_element(rates.begin(), rates.end(),
                                   [](const auto& a, const auto& b) { return a.rate < b.rate; });
  const double by_coefficient = largest->rate / (high * k0);
  const double by_oscillation = omega / (max_machine_frequency_per_k0 * k0);
  ts.beta = round_up_125(std::max(by_coefficient, by_oscillation));
  const double upper = smallest->rate / (low * k0);
  std::string bound =
      by_coefficient >= by_oscillation
          ? fmt::format("{} = {:.4g}/(β·k0) must stay <= {:g} (the largest weight), so β >= {:.4g}",
                        to_string(largest->name), largest->rate, high, by_coefficient)
          : fmt::format("the contact oscillation sqrt(c/Θ) = {:.4g} rad/s must stay <= {:g}·k0 rad/s "
                        "of machine time, so β >= {:.4g}",
                        omega, max_machine_frequency_per_k0, by_oscillation);
  ts.reason = fmt::format("β = {:g}, the smallest 1-2-5 value that fits: {}", ts.beta, bound);
  if (ts.beta <= upper * (1 + 1e-9)) {
    ts.reason += fmt::format("; every integrator coefficient is then in [{:g}, {:g}] "
                             "(smallest {} = {:.4g})", low, high, to_string(smallest->name),
                             smallest->rate / (ts.beta * k0));
  } else {
    ts.reason += fmt::format("; the integrator coefficients spread {:.3g}:1, wider than {:g}:1, "
                             "so some fall below {:g}", largest->rate / smallest->rate, high / low, low);
  }
  ts.warnings = checks(rates, omega, m, ts.beta);
  return ts;
}

}  // namespace gearpatch
