#pragma once
#include "model/gear_model.h"
#include "solver/energy_balance.h"
#include "solver/trajectory.h"

namespace gearpatch {

/// The observer that accumulates a run's energy and momentum flows on the
/// solver's own solution: each interval's power and torque terms are
/// integrated on the segment (the closed form, or the adaptive solver's dense
/// output) by adaptive Gauss–Kronrod quadrature to about 1e-13 of their
/// magnitude, never on output samples; each self-locking catch adds its jump.
class BalanceRecorder : public Observer {
 public:
  /// `initial`: the state the run was asked to start from (a self-locking
  /// reset at t = 0 counts as a catch).
  BalanceRecorder(const GearModel& model, const GearState& initial);
  void sample(double, const Mode&, const GearState&) override {}
  void event(const EventRecord& record) override;
  void interval(double a, double b, const Mode& mode, const Segment& segment) override;
  /// The balances of the run so far.
  RunBalance balance() const { return make_balance(model_, energy_, momentum_, initial_, end_); }

 private:
  /// Adds the jump from `before` to `after` to the self-locking catches.
  void catch_jump(const GearState& before, const GearState& after);

  const GearModel& model_;
  GearState initial_, end_;
  bool started_ = false;
  Flows energy_{}, momentum_{};
};

}  // namespace gearpatch
