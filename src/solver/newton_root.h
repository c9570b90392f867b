#pragma once
#include <algorithm>
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
  // f < 0 at `below`, > 0 at `above`, with the values there.
  double below = lo, above = hi, f_below = flo, f_above = fhi;
  if (flo > 0) {
    std::swap(below, above);
    std::swap(f_below, f_above);
  }
  auto chord = [&] { return below - f_below * (above - below) / (f_above - f_below); };
  double t = chord();  // the root itself when f is linear
  if (!(t > std::min(lo, hi) && t < std::max(lo, hi))) t = 0.5 * (lo + hi);
  double last_step = std::abs(hi - lo);
  bool chord_last = false;
  constexpr double tolerance = 8 * std::numeric_limits<double>::epsilon();
  for (int i = 0; i < 100; ++i) {
    const auto [value, slope] = f(t);
    if (value == 0) return t;
    if (value < 0) {
      below = t;
      f_below = value;
    } else {
      above = t;
      f_above = value;
    }
    const double a = std::min(below, above), b = std::max(below, above);
    double next = t - value / slope;
    // Converged: a step within rounding of t (it may round onto t itself,
    // or onto a bracket end when the root is there).
    if (std::abs(next - t) <= tolerance * std::abs(t)) return std::clamp(next, a, b);
    if (!(next > a && next < b) || std::abs(next - t) > 0.5 * last_step) {
      // Newton leaves the bracket (a root at its end, often: a turning point
      // where the interval was cut) or stalls: the chord of the bracket,
      // or its midpoint if the chord was the last resort too.
      if (chord_last) {
        next = 0.5 * (a + b);
      } else {
        next = chord();
        // The chord rounds onto an end: f there is rounding against f at t.
        if (!(next > a && next < b)) return std::clamp(next, a, b);
      }
      chord_last = !chord_last;
    } else {
      chord_last = false;
    }
    last_step = std::abs(next - t);
    t = next;
    if (!(b - a > tolerance * std::abs(t))) return t;
  }
  return t;
}

}  // namespace gearpatch
