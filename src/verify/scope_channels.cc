#include "verify/scope_channels.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace gearpatch::verify {

double volts_per_division(double volts) {
  const double wanted = std::max(std::abs(volts), 1e-3) / 4;
  const double decade = std::pow(10.0, std::floor(std::log10(wanted)));
  for (double step : {1.0, 2.0, 5.0, 10.0})
    if (step * decade >= wanted * (1 - 1e-12)) return step * decade;
  return 10 * decade;
}

double watch_scale(double peak_mu, double unit_volts) {
  return volts_per_division(std::clamp(std::abs(peak_mu), 0.05, 1.0) * unit_volts);
}

std::vector<WatchedSignal> provisional_watch_list(const circuit::Circuit& circuit,
                                                  const std::vector<std::pair<Signal, double>>& peak_mu) {
  std::vector<WatchedSignal> list;
  int channel = 1;
  for (Signal s : all_signals) {
    if (!circuit.probes.count(s)) continue;
    double peak = 1;
    for (const auto& [signal, mu] : peak_mu)
      if (signal == s) peak = mu;
    list.push_back({s, fmt::format("CH{}", channel++), 1.0, watch_scale(peak, circuit.machine.unit_volts)});
  }
  return list;
}

}  // namespace gearpatch::verify
