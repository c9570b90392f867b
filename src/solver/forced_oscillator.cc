#include "solver/forced_oscillator.h"

#include <cmath>
#include <algorithm>
#include <numbers>

namespace gearpatch {

ForcedOscillator::ForcedOscillator(double kappa, double delta, double force, double u0, double v0,
                                   double force_rate)
    : kappa_(kappa), delta_(delta), force_(force), u0_(u0), v0_(v0), force_rate_(force_rate) {
  w_rate0_ = v0_;
  if (kappa_ > 0) {
    rest_ = force_ / kappa_;
    if (force_rate_ != 0) {  // the particular part of a ramp: (f + f1·t)/κ − δ·f1/κ²
      rest_rate_ = force_rate_ / kappa_;
      rest_ -= delta_ * force_rate_ / (kappa_ * kappa_);
      w_rate0_ = v0_ - rest_rate_;
    }
    decay_ = -0.5 * delta_;
    disc_ = kappa_ - decay_ * decay_;
  }
}

namespace {

/// e^x and e^x − 1 from one library call, each to relative precision: from
/// expm1 where |x| < 1/2 (e = 1 + (e − 1) then loses nothing), else from exp
/// (e − 1 has no cancellation there, and a tiny e keeps its precision).
void exponentials(double x, double& e, double& e_minus_1) {
  if (x == 0) {
    e = 1;
    e_minus_1 = 0;
  } else if (std::abs(x) < 0.5) {
    e_minus_1 = std::expm1(x);
    e = 1 + e_minus_1;
  } else {
    e = std::exp(x);
    e_minus_1 = e - 1;
  }
}

/// e^{at}·cos(√D·t) and e^{at}·sin(√D·t)/√D, continued to D <= 0 (cosh, sinh,
/// and the critical limit 1, t) without loss of precision near D = 0; with
/// `ec_minus_1`, also e^{at}·cos(√D·t) − 1 without the cancellation near t = 0.
void modes(double a, double disc, double t, double& ec, double& es, double* ec_minus_1 = nullptr) {
  const double z = -disc * t * t;
  if (std::abs(z) < 1e-3) {
    // Taylor series of cos(√D t) − 1 and sin(√D t)/(√D t) in z, by Horner:
    // the terms beyond z⁵ are below 1e-22 here.
    const double c_minus_1 =
        z * (1.0 / 2 + z * (1.0 / 24 + z * (1.0 / 720 + z * (1.0 / 40320 + z * (1.0 / 3628800)))));
    const double s =
        1 + z * (1.0 / 6 + z * (1.0 / 120 + z * (1.0 / 5040 + z * (1.0 / 362880 + z * (1.0 / 39916800)))));
    double e, e_minus_1;
    exponentials(a * t, e, e_minus_1);
    ec = e * (1 + c_minus_1);
    es = e * s * t;
    if (ec_minus_1) *ec_minus_1 = e * c_minus_1 + e_minus_1;
  } else if (disc > 0) {
    // Two library calls instead of four: e^{at} and e^{at} − 1 from one
    // exponential, cos(bt) and sin(bt) from the half angle's sine and cosine
    // (which also give cos(bt) − 1 = −2·sin²(bt/2) without cancellation).
    const double b = std::sqrt(disc);
    double e, e_minus_1;
    exponentials(a * t, e, e_minus_1);
    double half_sine, half_cosine;
    ::sincos(0.5 * b * t, &half_sine, &half_cosine);
    const double cosine = (half_cosine - half_sine) * (half_cosine + half_sine);
    ec = e * cosine;
    es = e * (2 * half_sine * half_cosine) / b;
    if (ec_minus_1) *ec_minus_1 = e_minus_1 * cosine - 2 * half_sine * half_sine;
  } else {  // written so that nothing overflows: a + g < 0 when κ > 0
    const double g = std::sqrt(-disc);
    double slow, slow_minus_1;
    exponentials((a + g) * t, slow, slow_minus_1);
    const double fast_ratio = std::expm1(-2 * g * t);  // e^{−2gt} − 1
    ec = slow * (1 + 0.5 * fast_ratio);
    es = slow * (-fast_ratio) / (2 * g);
    if (ec_minus_1) *ec_minus_1 = slow_minus_1 + 0.5 * slow * fast_ratio;
  }
}

}  // namespace

void ForcedOscillator::at(double t, double& u, double& v) const {
  if (kappa_ == 0) {  // free flight (δ is 0 too: no coupling)
    u = u0_ + t * (v0_ + t * (0.5 * force_ + force_rate_ * t / 6));
    v = v0_ + t * (force_ + 0.5 * force_rate_ * t);
    return;
  }
  double ec, es;
  modes(decay_, disc_, t, ec, es);
  const double w0 = u0_ - rest_, w1 = w_rate0_;
  u = rest_ + rest_rate_ * t + ec * w0 + es * (w1 - decay_ * w0);
  v = rest_rate_ + ec * w1 + es * (decay_ * w1 - kappa_ * w0);
}

void ForcedOscillator::evaluate(double t, Values& x) const {
  if (kappa_ == 0) {  // free flight: no free part to speak of
    x.du = t * (v0_ + t * (0.5 * force_ + force_rate_ * t / 6));
    x.dv = t * (force_ + 0.5 * force_rate_ * t);
    x.w = u0_ + x.du;
    x.v = v0_ + x.dv;
    return;
  }
  const double w0 = u0_ - rest_, w1 = w_rate0_;
  if (t == 0) {  // the start of every segment, asked for often
    x = {w0, w1, 0, 0};
    return;
  }
  double ec, es, ec_minus_1;
  modes(decay_, disc_, t, ec, es, &ec_minus_1);
  const double sine_u = es * (w1 - decay_ * w0), sine_v = es * (decay_ * w1 - kappa_ * w0);
  x.w = ec * w0 + sine_u;
  x.v = ec * w1 + sine_v;
  x.du = ec_minus_1 * w0 + sine_u + rest_rate_ * t;
  x.dv = ec_minus_1 * w1 + sine_v;
}

double ForcedOscillator::sampling_step() const {
  if (kappa_ == 0) return 0;
  // Shorter than half a period, so g'' changes sign on a step at most once.
  if (disc_ > 0) return 2 * std::numbers::pi / std::sqrt(disc_) / 4;
  const double g = std::sqrt(-disc_);
  return 0.25 / (g - decay_);  // the faster of the two decays
}

double ForcedOscillator::vertex() const {
  if (kappa_ != 0 || force_ == 0 || force_rate_ != 0) return -1;
  return -v0_ / force_;
}

}  // namespace gearpatch
