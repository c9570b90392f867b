#pragma once
#include <cmath>

namespace gearpatch {

/// The exact solution of u'' + δ·u' + κ·u = f + f1·t from u(0), u'(0), for
/// any damping (under-, critically, over-damped) and for κ = δ = 0 (free
/// flight: a cubic). Within a mode of the gear model, on one piece of a
/// piecewise-linear drive, the relative twist obeys exactly this, so the
/// exact solver is exact to rounding.
class ForcedOscillator {
 public:
  ForcedOscillator(double kappa, double delta, double force, double u0, double v0,
                   double force_rate = 0);

  /// u(t) and u'(t).
  void at(double t, double& u, double& v) const;
  /// Everything at t at once: the free (homogeneous) part w = u − u_p of the
  /// twist, u_p(t) = (f + f1·t)/κ − δ·f1/κ², and its rate w', each without the cancellation of subtracting the
  /// equilibrium from u; and the changes u(t) − u(0), u'(t) − u'(0), each
  /// without the cancellation of subtracting the initial value (exact to
  /// relative precision as t → 0).
  struct Values {
    double w = 0, v = 0, du = 0, dv = 0;
  };
  void evaluate(double t, Values& x) const;
  /// u_p(0) = f/κ − δ·f1/κ² (0 in free flight); u_p grows at f1/κ.
  double equilibrium() const { return rest_; }
  double equilibrium_rate() const { return rest_rate_; }
  double kappa() const { return kappa_; }
  double delta() const { return delta_; }

  /// A time step that samples every root of a + b·t + u-like terms: 1/4 of a
  /// period when oscillating (any step under half a period would do: the
  /// exact segment cuts each interval at the first minimum of a guard; with
  /// turning points found by Newton's method 1/4 took the fewest instructions
  /// over the example scenes, against 1/2.5, 1/3, 1/5, 1/6 and 1/8), a quarter
  /// of the fastest decay time otherwise; 0 in free flight (where `vertex`
  /// gives the only turning point).
  double sampling_step() const;
  /// The time of u's extremum in free flight with constant forcing (negative if none ahead).
  double vertex() const;
  bool underdamped() const { return kappa_ > 0 && disc_ > 0; }
  /// The free part w = e^{at}·(w(0)·cos bt + …): its decay a = −δ/2, its
  /// angular frequency b (when underdamped) and its start w(0), w'(0).
  double decay() const { return decay_; }
  double frequency() const { return std::sqrt(disc_); }
  double free_start() const { return u0_ - rest_; }
  double free_rate_start() const { return w_rate0_; }

 private:
  double kappa_, delta_, force_, u0_, v0_, force_rate_;
  double rest_ = 0;       ///< u_p(0)
  double rest_rate_ = 0;  ///< u_p' = f1/κ
  double w_rate0_ = 0;    ///< w'(0) = v0 − f1/κ
  double decay_ = 0;   ///< a = −δ/2
  double disc_ = 0;    ///< κ − a²
};

}  // namespace gearpatch
