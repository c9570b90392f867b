#include "scaling/peaks.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "model/gear_model.h"
#include "scaling/maxima.h"
#include "scaling/table1.h"
#include "scaling/scaling_input.h"
#include "solver/integrate.h"

namespace gearpatch {
namespace {

/// Keeps the running maximum of every quantity, at grid samples and at both
/// sides of every event (where contact begins and speeds jump).
class PeakObserver : public Observer {
 public:
  PeakObserver(const GearModel& model, const Mode& first, PhysicalPeaks& out)
      : model_(model), p_(model.parameters()), mode_(first), out_(out) {}

  void sample(double, const Mode& mode, const GearState& s) override {
    mode_ = mode;
    update(mode, s);
  }
  void event(const EventRecord& e) override {
    // The self-locking reset stops the secondary at once (k_Re → ∞): the
    // reaction of blocks 16/17 is at its limit while the machine does that.
    if (p_.self_locking && e.kind != GuardKind::secondary_stops && e.before.omega_s != 0 &&
        e.after.omega_s == 0) {
      out_.lock_stops = true;
      raise(out_.catch_speed, e.before.omega_s);
    }
    update(mode_, e.before);
    update(e.mode_after, e.after);
    mode_ = e.mode_after;
  }

 private:
  static void raise(double& peak, double value) { peak = std::max(peak, std::abs(value)); }

  void update(const Mode& mode, const GearState& s) {
    raise(out_.omega_p, s.omega_p);
    raise(out_.omega_s, s.omega_s);
    raise(out_.rate, s.omega_p - s.omega_s);
    raise(out_.dphi, s.dphi);
    const double twist = model_.contact_twist(s.dphi);
    raise(out_.contact_twist, twist);
    const double m0 = model_.torque(mode, s);
    raise(out_.torque, m0);
    const bool contact = mode.contact != Contact::free;
    if (contact) {
      raise(out_.spring, p_.stiffness * twist);
      raise(out_.damping, p_.damping * (s.omega_p - s.omega_s));
    }
    const bool sliding = mode.secondary == Shaft::forward || mode.secondary == Shaft::backward;
    if (contact && sliding && p_.tooth_friction > 0) raise(out_.tooth, m0);
    if (p_.self_locking && mode.secondary == Shaft::held) {
      const double impressed = std::abs(m0 - p_.load_torque) - p_.bearing_secondary -
                               p_.tooth_friction * std::abs(m0);
      raise(out_.lock, std::max(0.0, impressed));
    }
    out_.primary_moved = out_.primary_moved || s.omega_p != 0;
    out_.secondary_moved = out_.secondary_moved || s.omega_s != 0;
  }

  const GearModel& model_;
  const GearParameters& p_;
  Mode mode_;
  PhysicalPeaks& out_;
};

}  // namespace

PhysicalPeaks simulate_peaks(const ScalingInput& in, const std::vector<Output>& more) {
  const GearParameters& p = in.gear;
  const GearModel model(p);
  RunSpec spec;
  spec.duration = in.duration;
  // At least 2000 samples per contact oscillation (a peak between two is
  // missed by at most 1 − cos(π/2000) ≈ 1.2e-6 of it), and no more than 2e6 in all.
  const double period = 2 * std::numbers::pi / contact_frequency(p);
  spec.output_step = std::max(std::min(in.duration / 20000, period / 2000), in.duration / 2e6);
  GearState start = in.initial;
  const Mode first = model.initial_mode(start);
  PhysicalPeaks peaks;
  peaks.drive = std::abs(p.drive_torque);
  PeakObserver observer(model, first, peaks);
  auto stepper = make_reference_stepper(p);
  integrate(model, *stepper, in.initial, spec, observer, more);
  return peaks;
}

PeakRun run_reference(const ScalingInput& input, const std::vector<Output>& more) {
  PeakRun run;
  try {
    run.peaks = simulate_peaks(input, more);
  } catch (const Error& e) {
    run.failure = e;
  }
  return run;
}

PeakFractions peak_fractions(const PhysicalPeaks& x, const Maxima& m, const GearParameters& p) {
  PeakFractions f;
  f.scaled["Wp"] = x.omega_p / m.speed_primary;
  f.scaled["Ws"] = x.omega_s / m.speed_secondary;
  f.scaled["DW"] = x.rate / m.relative_speed;
  f.scaled["X"] = x.dphi / m.twist;
  f.scaled["X'"] = x.contact_twist / m.contact_twist;
  f.scaled["m"] = x.torque / m.torque;
  if (m.drive_torque > 0 && x.drive > 0) f.scaled["drive"] = x.drive / m.drive_torque;
  if (p.half_backlash > 0) f.bounded["dead_zone"] = x.contact_twist / m.twist;
  f.bounded["spring"] = x.spring / m.torque;
  if (p.damping > 0) f.bounded["damping"] = x.damping / m.torque;
  if (p.bearing_primary > 0) f.bounded["friction_primary"] = x.primary_moved ? 1.0 : 0.0;
  if (p.bearing_secondary > 0) f.bounded["friction_secondary"] = x.secondary_moved ? 1.0 : 0.0;
  if (p.tooth_friction > 0) f.bounded["tooth_friction"] = x.tooth / m.torque;
  if (p.self_locking) f.bounded["lock_reaction"] = x.lock_stops ? 1.0 : x.lock / lock_torque(m, p);
  return f;
}

}  // namespace gearpatch
