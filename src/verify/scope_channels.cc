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

}  // namespace gearpatch::verify
