#pragma once
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "circuit/netlist.h"
#include "model/gear_model.h"
#include "solver/signal.h"
#include "solver/trajectory.h"

namespace gearpatch {
struct Scene;
}

namespace gearpatch::sweep {

/// PointMetrics: the figures of merit of one sweep point (its JSON key is
/// "figures").
/// The figures of one run that a study compares across points, all from the
/// exact reference: the contacts' closed-form records (solver/trajectory.h)
/// and the exact final state, never an output grid.
struct PointMetrics {
  int impacts = 0;                  ///< contacts that began with an impact
  /// Achieved, per impact: ContactRecord::restitution of a released contact;
  /// for one held to the run's end (k = 0) −Δφ̇ there / Δφ̇ at the impact, once below 1e-9 of it.
  std::vector<double> restitution;
  double peak_torque = 0;           ///< N·m, largest |M0| of any contact
  double peak_twist = 0;            ///< rad, largest |Δφ| of any contact
  /// s: from then on |φ̇p − φ̇s| stays within 1 % of its largest value (on
  /// the run's output rows, events included); NaN if it is outside at the end.
  double settling_time = 0;
  double momentum_mean = 0;         ///< rad/s, (Θp·φ̇p + Θs·φ̇s)/(Θp+Θs) at the end
  // The run's energy balance (solver/energy_balance.h), J:
  // drive_work = energy_change + load_work + dissipated + energy_residual.
  double drive_work = 0;            ///< ∫M_a·φ̇p dt (the motor line included)
  double load_work = 0;             ///< on the load, active and reactive
  double dissipated = 0;            ///< friction, contact damping and self-locking catches, >= 0
  double energy_change = 0;         ///< kinetic + spring energy, end − start
  double energy_residual = 0;
  // Its momentum balance, N·m·s, Θp·φ̇p + Θs·φ̇s with the secondary referred to the primary:
  // drive_impulse = momentum_change + load_impulse + friction_impulse + momentum_residual.
  double drive_impulse = 0;
  double load_impulse = 0;
  double friction_impulse = 0;      ///< bearings (sliding and holding), viscous, tooth friction, lock
  double momentum_change = 0;
  double momentum_residual = 0;
  /// The larger of the two residuals, each as a fraction of its balance's
  /// scale (the largest term, or the amount stored if larger).
  double residual_fraction = 0;
};

/// The figures of a reference run of `model` from `initial` (its balance
/// starts there: Trajectory::balance).
PointMetrics point_metrics(const GearModel& model, const GearState& initial, const Trajectory& trajectory);

/// What a point runs besides the reference.
struct PointOptions {
  std::vector<Signal> signals = {Signal::omega_p, Signal::omega_s};  ///< traces kept for the overlay plot
  bool verify = false;
  circuit::Level level = circuit::Level::ideal;
};

/// Runs one point: the reference always, the circuit with ngspice when
/// asked; returns its result JSON: "figures", "trace" (t and the chosen
/// signals on the run's output), and "verify" (passed, worst error, failures).
nlohmann::json run_point(const Scene& scene, const PointOptions& options);

/// Figures as JSON and back (NaN as null).
nlohmann::json to_json(const PointMetrics& f);
PointMetrics metrics_from_json(const nlohmann::json& j);

}  // namespace gearpatch::sweep
