#pragma once
#include <cmath>
#include <utility>

namespace gearpatch {

/// A linear form of the state along one oscillating closed-form mode, in
/// τ = t − origin: g(τ) = line0 + line1·τ + h(τ), h = e^{aτ}·(c·cos ωτ + s·sin ωτ).
/// h and its derivatives are damped cosines whose zeros lie at a known phase
/// π/ω apart, so g's turning points (where line1 = 0) and the zeros of g''
/// come in closed form: the recorder's peak search needs no iteration there,
/// and elsewhere a scalar one on g alone instead of on the whole state.
class DampedWaveForm {
 public:
  DampedWaveForm(double origin, double line0, double line1, double decay, double frequency, double c,
                 double s);

  double origin() const { return origin_; }
  double line_slope() const { return line1_; }
  double value(double tau) const;
  /// g(τ) and g'(τ).
  std::pair<double, double> value_and_slope(double tau) const;
  /// g'(τ) and g''(τ).
  std::pair<double, double> slope(double tau) const;

  /// A time τ and the value there.
  struct Point {
    double tau, value;
  };
  /// The first zero of h' after τ (INFINITY if h is 0), with g there if it
  /// lies at or before `until` (else NaN: no exponential spent on it).
  Point next_turn(double tau, double until = INFINITY) const;
  /// The first zero of g'' after τ (INFINITY if h is 0), with g' there if
  /// it lies at or before `until` (else NaN).
  Point next_inflection(double tau, double until = INFINITY) const;

 private:
  /// An oscillation e^{aτ}·(x·cos ωτ + y·sin ωτ) and where it is zero:
  /// ωτ = phase + kπ, phase = atan2(y, x) + π/2 (worked out when first
  /// asked for: most forms are never searched for a zero).
  struct Wave {
    double x = 0, y = 0;
    mutable double radius = -1, phase = 0;
  };
  /// e^{aτ}, cos ωτ and sin ωτ at one τ, for any of the oscillations.
  struct Angle {
    double decay, cosine, sine;
    double of(const Wave& w) const { return decay * (w.x * cosine + w.y * sine); }
  };
  Angle at(double tau) const;
  /// The first zero of `zero` after τ, with the oscillation `other` there:
  /// one exponential, since cos and sin at the zero follow from its phase.
  Point next_zero(const Wave& zero, double tau, const Wave& other, double until) const;

  double origin_, line0_, line1_, decay_, frequency_;
  Wave wave_, slope1_, slope2_;  ///< h, h', h''
};

}  // namespace gearpatch
