#include "model/capped_restitution.h"

#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include "common/error.h"

namespace gearpatch {
namespace {

/// u and u̇ of u'' + δu' + κu = 0 at t from (u0, v0), any damping.
void damped(double kappa, double delta, double u0, double v0, double t, double& u, double& v) {
  const double a = -0.5 * delta, disc = kappa - a * a;
  double ec, es;  // e^{at}·cos(√D t), e^{at}·sin(√D t)/√D, continued to D <= 0
  if (disc > 0) {
    const double b = std::sqrt(disc);
    ec = std::exp(a * t) * std::cos(b * t);
    es = std::exp(a * t) * std::sin(b * t) / b;
  } else if (disc < 0) {
    const double g = std::sqrt(-disc);
    ec = std::exp(a * t) * std::cosh(g * t);
    es = std::exp(a * t) * std::sinh(g * t) / g;
  } else {
    ec = std::exp(a * t);
    es = t * std::exp(a * t);
  }
  u = ec * u0 + es * (v0 - a * u0);
  v = ec * v0 + es * (a * v0 - kappa * u0);
}

template <class F>
double bracketed_root(F f, double lo, double hi) {
  std::uintmax_t iterations = 300;
  boost::math::tools::eps_tolerance<double> tolerance(std::numeric_limits<double>::digits - 1);
  const auto [a, b] = boost::math::tools::toms748_solve(f, lo, hi, tolerance, iterations);
  return 0.5 * (a + b);
}

}  // namespace

double capped_restitution_for_damping(double d, double c, double theta) {
  if (d <= 0) return 1.0;
  // Impact speed 1: capped phase u = sin(ωt)/ω until d·u̇ = c·u, tan(ωt) = dω/c.
  const double omega = std::sqrt(2 * c / theta);
  const double t1 = std::atan(d * omega / c) / omega;
  const double u1 = std::sin(omega * t1) / omega, v1 = std::cos(omega * t1);
  // Spring and damper until c·u + d·u̇ = 0 (it starts at 2·d·v1 > 0).
  const double kappa = c / theta, delta = d / theta;
  auto push = [&](double t) {
    double u, v;
    damped(kappa, delta, u1, v1, t, u, v);
    return c * u + d * v;
  };
  const double disc = kappa - 0.25 * delta * delta;
  const double scale = disc > 0 ? std::numbers::pi / std::sqrt(disc) : 2.0 / delta;
  const double step = std::min(scale, 1 / std::sqrt(kappa)) / 64;
  double lo = 0, hi = step;
  for (int i = 0; push(hi) > 0; ++i) {
    if (i > 100000) throw Error("capped restitution: the contact never parts", Error::Kind::internal);
    lo = hi;
    hi += step;
  }
  const double t2 = bracketed_root(push, lo, hi);
  double u2, v2;
  damped(kappa, delta, u1, v1, t2, u2, v2);
  return -v2;  // parted: the relative speed stays until the edge
}

double damping_for_capped_restitution(double k, double c, double theta) {
  if (k >= 1) return 0.0;
  if (!(k > 0)) throw Error("the capped contact law reaches k = 0 only with infinite damping");
  auto excess = [&](double d) { return capped_restitution_for_damping(d, c, theta) - k; };
  // The law releases earlier than the paper's, so its restitution is higher
  // for the same d: start from the paper's damping and double until below k.
  double lo = 0, hi = 2 * std::sqrt(c * theta);
  for (int i = 0; excess(hi) > 0; ++i) {
    if (i > 200) throw Error("capped restitution: no damping reaches k", Error::Kind::internal);
    lo = hi;
    hi *= 2;
  }
  return bracketed_root(excess, lo, hi);
}

}  // namespace gearpatch
