#pragma once
#include <cmath>
#include <limits>
#include <utility>

namespace gearpatch {

/// The root of f in [lo, hi], where f(lo) and f(hi) have opposite signs, by
/// Newton's method kept inside the shrinking bracket (a bisection wherever a
/// step would leave it or shrink it too slowly): `f(t)` returns {f, f'}.
/// Within a mode the solution's derivatives are known in closed form, so a
/// turning point takes 3–4 evaluations where TOMS 748 on f alone took 8–10.
/// (Boost's newton_raphson_iterate needs no bracket and throws when it doubts
/// one; here the bracket is given, so this one cannot fail.)
template <class F>
double bracketed_newton(const F& f, double lo, double hi, double flo, double fhi) {
  if (flo == 0) return lo;
  if (fhi == 0) return hi;
  double below = flo < 0 ? lo : hi, above = flo < 0 ? hi : lo;  // f < 0 at below, > 0 at above
  // Start where the chord crosses zero: the root itself when f is linear.
  double t = lo - flo * (hi - lo) / (fhi - flo);
  if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);
  double last_step = hi - lo;
  constexpr double tolerance = 8 * std::numeric_limits<double>::epsilon();
  for (int i = 0; i < 100; ++i) {
    const auto [value, slope] = f(t);
    if (value == 0) return t;
    (value < 0 ? below : above) = t;
    const double a = std::min(below, above), b = std::max(below, above);
    double next = t - value / slope;
    // Converged: a step within rounding of t (it may round onto t itself).
    if (std::abs(next - t) <= tolerance * std::abs(t) && next >= a && next <= b) return next;
    if (!(next > a && next < b) || std::abs(next - t) > 0.5 * last_step) next = 0.5 * (a + b);
    last_step = std::abs(next - t);
    t = next;
    if (!(b - a > tolerance * std::abs(t))) return t;
  }
  return t;
}

}  // namespace gearpatch
