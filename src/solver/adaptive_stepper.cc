#include <algorithm>
#include <array>
#include <boost/numeric/odeint.hpp>
#include <cmath>

#include "solver/segment.h"

namespace gearpatch {
namespace {

namespace odeint = boost::numeric::odeint;
using Vector = std::array<double, 3>;

Vector to_vector(const GearState& s) { return {s.omega_p, s.omega_s, s.dphi}; }
GearState to_state(const Vector& v) { return {v[0], v[1], v[2]}; }

/// One mode integrated by Dormand–Prince 5(4) with dense output; the guards
/// are checked on each accepted step and refined on the interpolant.
class AdaptiveSegment : public Segment {
 public:
  AdaptiveSegment(const GearModel& model, const Mode& mode, const GearState& s, double t0,
                  double horizon, double tolerance)
      : model_(model), mode_(mode), horizon_(horizon),
        // The local error per step is set 1000 times below the tolerance so that the
        // global error over a run of a few thousand steps stays within it.
        stepper_(odeint::make_dense_output(tolerance / 1000, tolerance / 1000,
                                           odeint::runge_kutta_dopri5<Vector>())) {
    stepper_.initialize(to_vector(s), t0, initial_step(model, mode, horizon - t0));
  }

  double advance() override {
    auto rhs = [this](const Vector& y, Vector& dy, double t) {
      dy = to_vector(model_.derivative(mode_, to_state(y), t));
    };
    if (stepper_.current_time() < horizon_) stepper_.do_step(rhs);
    return std::min(stepper_.current_time(), horizon_);
  }

  GearState state_at(double t) const override {
    Vector y;
    stepper_.calc_state(t, y);
    return to_state(y);
  }

  bool polynomial_intervals() const override { return true; }  // Dormand–Prince's quintic dense output

 private:
  static double initial_step(const GearModel& model, const Mode& mode, double span) {
    const ModeDynamics d = model.dynamics(mode);
    const double weight = d.inv_p + d.inv_s * d.gain_s;
    const double rate = d.coupled ? std::sqrt(weight * d.stiffness) + weight * d.damping : 0.0;
    return rate > 0 ? std::min(span, 1e-3 / rate) : std::max(span * 1e-3, 1e-12);
  }

  const GearModel& model_;
  Mode mode_;
  double horizon_;
  mutable odeint::dense_output_runge_kutta<
      odeint::controlled_runge_kutta<odeint::runge_kutta_dopri5<Vector>>>
      stepper_;
};

class AdaptiveStepper : public Stepper {
 public:
  explicit AdaptiveStepper(double tolerance) : tolerance_(tolerance) {}
  std::unique_ptr<Segment> start(const GearModel& model, const Mode& mode, const GearState& state,
                                 double t0, double horizon, const std::vector<Guard>&) override {
    return std::make_unique<AdaptiveSegment>(model, mode, state, t0, horizon, tolerance_);
  }

 private:
  double tolerance_;
};

}  // namespace

std::unique_ptr<Stepper> make_adaptive_stepper(double tolerance) {
  return std::make_unique<AdaptiveStepper>(tolerance);
}

}  // namespace gearpatch
