#include "model/restitution.h"

#include <cmath>
#include <numbers>

namespace gearpatch {

double damping_for_restitution(double k, double c, double theta) {
  const double critical = 2.0 * std::sqrt(c * theta);
  if (k <= 0) return critical;
  if (k >= 1) return 0.0;
  const double ln_k = std::log(k);
  return critical * (-ln_k) / std::sqrt(std::numbers::pi * std::numbers::pi + ln_k * ln_k);
}

double restitution_for_damping(double d, double c, double theta) {
  const double zeta = d / (2.0 * std::sqrt(c * theta));
  if (zeta >= 1) return 0.0;
  return std::exp(-std::numbers::pi * zeta / std::sqrt(1.0 - zeta * zeta));
}

}  // namespace gearpatch
