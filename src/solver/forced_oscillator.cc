#include "solver/forced_oscillator.h"

#include <cmath>
#include <algorithm>
#include <numbers>

namespace gearpatch {

ForcedOscillator::ForcedOscillator(double kappa, double delta, double force, double u0, double v0)
    : kappa_(kappa), delta_(delta), force_(force), u0_(u0), v0_(v0) {
  if (kappa_ > 0) {
    rest_ = force_ / kappa_;
    decay_ = -0.5 * delta_;
    disc_ = kappa_ - decay_ * decay_;
  }
}

namespace {

/// e^{at}·cos(√D·t) and e^{at}·sin(√D·t)/√D, continued to D <= 0 (cosh, sinh,
/// and the critical limit 1, t) without loss of precision near D = 0.
void modes(double a, double disc, double t, double& ec, double& es) {
  const double z = -disc * t * t;
  if (std::abs(z) < 1e-3) {  // Taylor series of cos(√D t) and sin(√D t)/√D in z
    double c = 1, s = 1, term_c = 1, term_s = 1;
    for (int n = 1; n <= 6; ++n) {
      term_c *= z / ((2 * n - 1) * (2 * n));
      term_s *= z / ((2 * n) * (2 * n + 1));
      c += term_c;
      s += term_s;
    }
    const double e = std::exp(a * t);
    ec = e * c;
    es = e * s * t;
  } else if (disc > 0) {
    const double b = std::sqrt(disc);
    const double e = std::exp(a * t);
    ec = e * std::cos(b * t);
    es = e * std::sin(b * t) / b;
  } else {  // written so that nothing overflows: a + g < 0 when κ > 0
    const double g = std::sqrt(-disc);
    const double slow = std::exp((a + g) * t);
    const double fast_ratio = std::expm1(-2 * g * t);  // e^{−2gt} − 1
    ec = slow * (1 + 0.5 * fast_ratio);
    es = slow * (-fast_ratio) / (2 * g);
  }
}

}  // namespace

void ForcedOscillator::at(double t, double& u, double& v) const {
  if (kappa_ == 0) {  // free flight (δ is 0 too: no coupling)
    u = u0_ + t * (v0_ + 0.5 * force_ * t);
    v = v0_ + force_ * t;
    return;
  }
  double ec, es;
  modes(decay_, disc_, t, ec, es);
  const double w0 = u0_ - rest_;
  u = rest_ + ec * w0 + es * (v0_ - decay_ * w0);
  v = ec * v0_ + es * (decay_ * v0_ - kappa_ * w0);
}

double ForcedOscillator::sampling_step() const {
  if (kappa_ == 0) return 0;
  if (disc_ > 0) return 2 * std::numbers::pi / std::sqrt(disc_) / 16;
  const double g = std::sqrt(-disc_);
  return 0.25 / (g - decay_);  // the faster of the two decays
}

double ForcedOscillator::slowest_sampling_step() const {
  if (kappa_ == 0 || disc_ > 0) return sampling_step();
  const double g = std::sqrt(-disc_);
  return std::max(sampling_step(), 0.25 / std::max(-(decay_ + g), 1e-300));
}

double ForcedOscillator::vertex() const {
  if (kappa_ != 0 || force_ == 0) return -1;
  return -v0_ / force_;
}

}  // namespace gearpatch
