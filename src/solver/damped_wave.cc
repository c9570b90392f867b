#include "solver/damped_wave.h"

#include <cmath>
#include <numbers>

namespace gearpatch {

DampedWaveForm::DampedWaveForm(double origin, double line0, double line1, double decay,
                               double frequency, double c, double s)
    : origin_(origin), line0_(line0), line1_(line1), decay_(decay), frequency_(frequency) {
  // d/dτ of e^{aτ}(x cos ωτ + y sin ωτ) is e^{aτ}((a x + ω y) cos + (a y − ω x) sin).
  wave_ = {c, s};
  slope1_ = {decay * c + frequency * s, decay * s - frequency * c};
  slope2_ = {decay * slope1_.x + frequency * slope1_.y, decay * slope1_.y - frequency * slope1_.x};
}

DampedWaveForm::Angle DampedWaveForm::at(double tau) const {
  Angle x;
  ::sincos(frequency_ * tau, &x.sine, &x.cosine);
  x.decay = std::exp(decay_ * tau);
  return x;
}

double DampedWaveForm::value(double tau) const {
  return line0_ + line1_ * tau + at(tau).of(wave_);
}

std::pair<double, double> DampedWaveForm::value_and_slope(double tau) const {
  const Angle x = at(tau);
  return {line0_ + line1_ * tau + x.of(wave_), line1_ + x.of(slope1_)};
}

std::pair<double, double> DampedWaveForm::slope(double tau) const {
  const Angle x = at(tau);
  return {line1_ + x.of(slope1_), x.of(slope2_)};
}

DampedWaveForm::Point DampedWaveForm::next_turn(double tau, double until) const {
  Point p = next_zero(slope1_, tau, wave_, until);
  p.value += line0_ + line1_ * p.tau;
  return p;
}

DampedWaveForm::Point DampedWaveForm::next_inflection(double tau, double until) const {
  Point p = next_zero(slope2_, tau, slope1_, until);
  p.value += line1_;
  return p;
}

DampedWaveForm::Point DampedWaveForm::next_zero(const Wave& zero, double tau, const Wave& other,
                                                double until) const {
  if (zero.radius < 0) {
    zero.radius = std::hypot(zero.x, zero.y);
    zero.phase = std::atan2(zero.y, zero.x) + 0.5 * std::numbers::pi;
  }
  if (!(zero.radius > 0)) return {INFINITY, 0};
  // At ωτ = phase + kπ: cos = −(−1)^k·y/r, sin = (−1)^k·x/r.
  double k = std::ceil((frequency_ * tau - zero.phase) / std::numbers::pi);
  double at = (zero.phase + k * std::numbers::pi) / frequency_;
  if (!(at > tau)) {
    k += 1;
    at = (zero.phase + k * std::numbers::pi) / frequency_;
  }
  if (!(at <= until)) return {at, NAN};
  const double parity = std::fmod(k, 2.0) == 0 ? 1.0 : -1.0;
  return {at, parity * std::exp(decay_ * at) * (other.y * zero.x - other.x * zero.y) / zero.radius};
}

}  // namespace gearpatch
