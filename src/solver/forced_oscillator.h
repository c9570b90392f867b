#pragma once

namespace gearpatch {

/// The exact solution of u'' + δ·u' + κ·u = f from u(0), u'(0), for any
/// damping (under-, critically, over-damped) and for κ = δ = 0 (free flight:
/// a parabola). Within a mode of the gear model the relative twist obeys
/// exactly this, so the exact solver is exact to rounding.
class ForcedOscillator {
 public:
  ForcedOscillator(double kappa, double delta, double force, double u0, double v0);

  /// u(t) and u'(t).
  void at(double t, double& u, double& v) const;
  /// Everything at t at once: the free (homogeneous) part w = u − f/κ and
  /// its rate w' = u', each without the cancellation of subtracting the
  /// equilibrium from u; and the changes u(t) − u(0), u'(t) − u'(0), each
  /// without the cancellation of subtracting the initial value (exact to
  /// relative precision as t → 0).
  struct Values {
    double w = 0, v = 0, du = 0, dv = 0;
  };
  void evaluate(double t, Values& x) const;
  double equilibrium() const { return rest_; }  ///< f/κ (0 in free flight)
  double kappa() const { return kappa_; }
  double delta() const { return delta_; }

  /// A time step that samples every root of a + b·t + u-like terms: 1/8 of a
  /// period when oscillating (any step under half a period would do: the
  /// exact segment cuts each interval at the first minimum of a guard; 1/8
  /// took the fewest instructions over the example scenes, against 1/4, 1/6,
  /// 1/12, 1/16 and 0.45), a quarter of the fastest decay time otherwise; 0
  /// in free flight (where `vertex` gives the only turning point).
  double sampling_step() const;
  /// The time of u's extremum in free flight (negative if none ahead).
  double vertex() const;
  bool underdamped() const { return kappa_ > 0 && disc_ > 0; }

 private:
  double kappa_, delta_, force_, u0_, v0_;
  double rest_ = 0;    ///< f/κ, the equilibrium
  double decay_ = 0;   ///< a = −δ/2
  double disc_ = 0;    ///< κ − a²
};

}  // namespace gearpatch
