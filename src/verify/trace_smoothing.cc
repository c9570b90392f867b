#include "verify/trace_smoothing.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gearpatch::verify {

std::vector<double> smooth_moving_average(const std::vector<double>& y, std::size_t half) {
  if (half < 1 || y.size() < 3) return y;
  std::vector<double> sum(y.size() + 1, 0.0);  // prefix sums
  for (std::size_t i = 0; i < y.size(); ++i) sum[i + 1] = sum[i] + y[i];
  std::vector<double> out(y.size());
  for (std::size_t i = 0; i < y.size(); ++i) {
    // Symmetric about the sample, narrowed at the record's ends so a slope is not bent.
    const std::size_t k = std::min({half, i, y.size() - 1 - i});
    out[i] = (sum[i + k + 1] - sum[i - k]) / static_cast<double>(2 * k + 1);
  }
  return out;
}

double smoothed_noise_gain(std::size_t half) { return 1 / static_cast<double>(2 * half + 1); }

double smoothing_half_width(const Trajectory& reference, double tolerance, double duration) {
  double shortest = tolerance * duration;
  for (const ContactRecord& c : reference.contacts)
    if (c.impact && c.released) shortest = std::min(shortest, c.end - c.start);
  return shortest / 8;
}

double residual_noise(const std::vector<double>& raw, const std::vector<double>& smoothed, std::size_t half) {
  if (raw.size() < 3 || half < 1) return 0;
  double sum = 0;
  for (std::size_t i = 0; i < raw.size(); ++i) sum += (raw[i] - smoothed[i]) * (raw[i] - smoothed[i]);
  // The residual keeps 1 − gain of the noise's variance; what the window bends of the signal counts as noise.
  return std::sqrt(sum / static_cast<double>(raw.size()) / (1 - smoothed_noise_gain(half)));
}

double dithered_quantisation_bias(double step, double noise) {
  if (step <= 0) return 0;
  double sum = 0;
  for (int k = 1; k <= 50; ++k) {
    const double r = static_cast<double>(k) * noise / step;
    sum += std::exp(-2 * std::numbers::pi * std::numbers::pi * r * r) / k;
  }
  return std::min(step / 2, step / std::numbers::pi * sum);
}

}  // namespace gearpatch::verify
