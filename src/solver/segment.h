#pragma once
#include <memory>
#include <optional>
#include <vector>

#include "model/gear_model.h"
#include "solver/damped_wave.h"

namespace gearpatch {

/// The solution inside one mode, revealed interval by interval: the event
/// locator looks for guard sign changes on each interval and refines them on
/// `state_at`, which is valid at least on the last interval handed out.
class Segment {
 public:
  virtual ~Segment() = default;
  /// Extends the known solution; returns the new end time (at most the horizon).
  virtual double advance() = 0;
  virtual GearState state_at(double t) const = 0;
  /// The state's time derivative at t where the segment has it in closed
  /// form (the event locator then refines a crossing by Newton's method
  /// instead of TOMS 748 on the values alone); false where it does not.
  virtual bool rate_at(double /*t*/, GearState& /*rate*/) const { return false; }
  /// The form `f` of the state along this segment as a line plus a damped
  /// cosine, where the mode oscillates with constant forcing (the peak
  /// search then finds turning points from their phase); empty elsewhere.
  virtual std::optional<DampedWaveForm> damped_wave(const LinearForm& /*f*/) const { return std::nullopt; }
  /// True where the state on each interval handed out is a polynomial of
  /// degree at most IntervalPolynomial::degree in time (a Runge–Kutta step's
  /// dense output): a guard may then leave and re-enter within one interval,
  /// and the locator looks at its turning points.
  virtual bool polynomial_intervals() const { return false; }
};

/// Makes the segment of one mode; the exact solver and the adaptive one are
/// two steppers behind this interface.
class Stepper {
 public:
  virtual ~Stepper() = default;
  /// `guards` are model.guards(mode, t0), computed once by the caller.
  virtual std::unique_ptr<Segment> start(const GearModel& model, const Mode& mode,
                                         const GearState& state, double t0, double horizon,
                                         const std::vector<Guard>& guards) = 0;
};

/// Closed-form solution of each mode: exact to rounding.
std::unique_ptr<Stepper> make_exact_stepper();
/// Boost.Odeint's dense-output Dormand–Prince 5(4) with the given relative
/// and absolute tolerance: for inputs that are not piecewise constant, and the
/// other end of the speed/accuracy trade.
std::unique_ptr<Stepper> make_adaptive_stepper(double tolerance);

}  // namespace gearpatch
