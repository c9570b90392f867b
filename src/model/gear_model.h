#pragma once
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "model/drive_profile.h"
#include "model/gear_state.h"

namespace gearpatch {

/// The physical constants of the equivalent gear (paper sections 3–5), SI.
struct GearParameters {
  double inertia_primary = 1;    ///< Θp
  double inertia_secondary = 1;  ///< Θs
  double stiffness = 1;          ///< c
  double damping = 0;            ///< d (from k by the corrected (4.8) if k was given)
  double half_backlash = 0;      ///< ε
  double bearing_primary = 0;    ///< k_Rp
  double bearing_secondary = 0;  ///< k_Rs
  double tooth_friction = 0;     ///< k_z = 1 − η_z, (5.6)
  bool self_locking = false;
  /// The capped contact law (Modelica's ElastoBacklash) instead of the paper's:
  /// M0 = M_c + min(M_c, M_d) on the positive side, 0 where that would pull.
  bool capped_contact = false;
  double drive_torque = 0;       ///< M_a
  double load_torque = 0;        ///< on the secondary, opposing positive rotation

  // What a drive engineer brings; each 0 or empty when unused.
  DriveProfile drive_profile;    ///< M_a(t) in place of drive_torque when not empty
  double motor_slope = 0;        ///< M_stall/φ̇_noload: the motor line M_a − motor_slope·φ̇p
  double viscous_primary = 0;    ///< b_p, N·m·s/rad
  double viscous_secondary = 0;  ///< b_s, N·m·s/rad, referred to the primary
  double reactive_load = 0;      ///< the share of bearing_secondary that is a reactive load
  /// Stribeck bearings: bearing_primary/secondary are then the break-away
  /// levels k_S, and a sliding shaft meets k_C + (k_S − k_C)·exp(−|φ̇|/φ̇_S).
  double sliding_primary = 0, sliding_secondary = 0;  ///< k_C, N·m
  double stribeck_speed = 0;     ///< φ̇_S, rad/s; 0: Coulomb bearings
  bool stribeck() const { return stribeck_speed > 0; }
  /// The friction level of a sliding shaft below its break-away level k_S.
  double stribeck_relief(double breakaway, double sliding, double omega) const {
    return stribeck() ? (breakaway - sliding) * -std::expm1(-std::abs(omega) / stribeck_speed) : 0.0;
  }

  double effective_inertia() const;  ///< Θ = ΘpΘs/(Θp+Θs)
  /// M_a at t at standstill of the primary (the motor line's stall torque).
  double drive_at(double t) const {
    return drive_profile.empty() ? drive_torque : drive_profile.torque(t);
  }
  /// dM_a/dt on the piece of the profile that starts at t.
  double drive_slope(double t) const { return drive_profile.slope(t); }
  /// The first drive breakpoint after t, +inf if none: an event.
  double next_breakpoint(double t) const { return drive_profile.next_breakpoint(t); }
  /// The feedback of φ̇p on the primary's torque: the motor line's fall plus viscous friction.
  double primary_speed_feedback() const { return motor_slope + viscous_primary; }
  /// The motor line or viscous friction: torques proportional to a shaft's speed.
  bool speed_feedback() const { return primary_speed_feedback() != 0 || viscous_secondary != 0; }
  /// True when every mode is linear with forcing polynomial in time, which the
  /// exact solver integrates in closed form: drive steps, ramps and tables, the
  /// motor line and viscous friction; not Stribeck bearings (the adaptive solver's).
  bool modes_linear() const { return !stribeck(); }
  bool primary_has_friction() const { return bearing_primary > 0; }
  bool secondary_has_friction() const {
    return bearing_secondary > 0 || tooth_friction > 0 || self_locking;
  }
};

/// A function of the state that is linear within a mode: a·φ̇p + b·φ̇s + c·Δφ + k.
/// Every guard of the model is one, which lets both solvers share them.
/// A guard may also grow with time (`time`·t) while the drive ramps.
struct LinearForm {
  double omega_p = 0, omega_s = 0, dphi = 0, constant = 0, time = 0;
  double operator()(const GearState& s) const {
    return omega_p * s.omega_p + omega_s * s.omega_s + dphi * s.dphi + constant;
  }
  double at(const GearState& s, double t) const { return (*this)(s) + time * t; }
  /// The form's time derivative along a solution whose state changes at `rate`.
  double rate(const GearState& rate) const {
    return omega_p * rate.omega_p + omega_s * rate.omega_s + dphi * rate.dphi + time;
  }
};

/// What ends a mode: the mode is valid while the guard's form is >= 0.
enum class GuardKind {
  contact_positive, contact_negative, release,
  primary_stops, secondary_stops,
  primary_breaks_forward, primary_breaks_backward,
  secondary_breaks_forward, secondary_breaks_backward,
  torque_reverses,
  drive_breakpoint,  ///< a corner or step of the drive profile: not a guard, a time event
  damping_capped, damping_uncapped, flanks_part, flanks_press,  ///< the capped law's phases
  // flanks_press stays last: the event budget counts kinds in an array up to it.
};
std::string to_string(GuardKind);

struct Guard {
  GuardKind kind;
  LinearForm form;
};

/// Constants of the linear equations of one mode:
///   φ̇p' = inv_p·(force_p + drive_rate·τ − M0),  φ̇s' = inv_s·(gain_s·M0 + force_s),
///   M0 = c·u + d·u̇ with u = Δφ − offset while `coupled`, else 0; τ from the
///   time the constants were taken at, on one piece of the drive profile.
struct ModeDynamics {
  double inv_p = 0, inv_s = 0, gain_s = 1, force_p = 0, force_s = 0, drive_rate = 0;
  bool coupled = false;
  double offset = 0, stiffness = 0, damping = 0;
};

/// The equation system (6.1)–(6.10) as a hybrid model, with the paper's
/// misprints corrected: dead-zone contact that transmits torque only outside
/// the backlash and is released at its edge, Coulomb bearing friction with a
/// held state at zero speed, tooth friction (5.5), self-locking (5.10) as a
/// held state (k_Re → ∞). Terms a scene does not need are never evaluated.
class GearModel {
 public:
  explicit GearModel(const GearParameters& parameters);
  const GearParameters& parameters() const { return p_; }

  /// The mode's constants at time t (the drive torque of the profile piece at t).
  ModeDynamics dynamics(const Mode& mode, double t = 0) const;
  LinearForm torque_form(const Mode& mode) const;  ///< M0 as a function of the state
  double torque(const Mode& mode, const GearState& s) const { return torque_form(mode)(s); }
  GearState derivative(const Mode& mode, const GearState& s, double t = 0) const;
  /// The guards of the mode on the drive profile's piece that starts at t.
  std::vector<Guard> guards(const Mode& mode, double t = 0) const;
  /// The same into `out` (cleared first), which keeps its capacity from mode to mode.
  void guards(const Mode& mode, double t, std::vector<Guard>& out) const;

  /// The mode the initial state starts in; may apply the self-locking reset.
  Mode initial_mode(GearState& state) const;
  /// Crosses the guard at time t: snaps the state onto the boundary, applies velocity
  /// resets (self-locking), and returns the new mode.
  Mode cross(const Mode& mode, GuardKind kind, GearState& state, double t = 0) const;

  double kinetic_energy(const GearState& s) const;
  double spring_energy(const GearState& s) const;
  double momentum(const GearState& s) const;  ///< Θp·φ̇p + Θs·φ̇s
  /// Δφ' of (6.9): the twist beyond the backlash.
  double contact_twist(double dphi) const;

  /// The terms of (6.1)–(6.10) this scene needs, for reports.
  std::vector<std::string> active_terms() const;

 private:
  /// The contact's offset, stiffness and damping in mode m (part of dynamics()).
  void contact_law(const Mode& m, ModeDynamics& d) const;
  Shaft resolve_primary(const Mode& mode, const GearState& s, double t) const;
  Shaft resolve_secondary(const Mode& mode, const GearState& s) const;
  int torque_sign_at(const Mode& mode, const GearState& s) const;
  int engagement(const Mode& mode) const;
  Phase entry_phase(const Mode& mode, const GearState& s) const;
  void capped_guards(const Mode& mode, std::vector<Guard>& g) const;
  void settle(Mode& mode, GearState& s, double t) const;

  GearParameters p_;
};

}  // namespace gearpatch
