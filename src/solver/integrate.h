#pragma once
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "model/gear_model.h"
#include "solver/segment.h"
#include "solver/trajectory.h"

namespace gearpatch {

/// What the run is asked for: length, output grid, and the bounds on events
/// and on solver steps that stop a run whose cost would grow without bound.
struct RunSpec {
  double duration = 1;
  double output_step = 1e-3;
  std::size_t max_events = 5'000'000;
  std::size_t max_steps = 100'000'000;  ///< intervals the segments are walked in
  /// simulate() integrates the energy and momentum balances (Trajectory::balance)
  /// on the same run; off to time the solver alone.
  bool balance = true;

  /// The most output rows a run may have: a row costs about 130 bytes on its
  /// way to a CSV (the sample and its text), so 1e7 rows take 1.3 GB.
  static constexpr double max_rows = 1e7;
  /// A default grid takes at most this many rows (130 MB of CSV): a stiff
  /// contact settled for millions of periods is not sampled by default.
  static constexpr double max_default_rows = 1e6;
  /// A grid samples the contact oscillation at least this often a period.
  static constexpr double samples_per_period = 20;
  /// Rows of the output grid t_k = min(k·output_step, duration), as a double
  /// so that a tiny step cannot overflow the count.
  double rows() const { return std::ceil(duration / output_step - 1e-9) + 1; }
};

/// Throws Error (input) unless the output step is finite and positive and the
/// grid within RunSpec::max_rows: checked before anything is allocated for it.
void check_output_grid(const RunSpec& spec);

/// The period of the undamped contact oscillation, 2π/sqrt(c·(1/Θp + 1/Θs)).
double contact_period(const GearParameters& p);

/// The default output step: duration/2000, finer where that samples the
/// contact fewer than RunSpec::samples_per_period times a period, but no
/// finer than duration/RunSpec::max_default_rows.
double default_output_step(const GearParameters& p, double duration);

/// A warning when the output step samples a contact of `trajectory` fewer
/// than RunSpec::samples_per_period times a period (its peaks lie between
/// the samples); empty if it does not, or if the flanks never touched.
std::string undersampling_warning(const GearParameters& p, const RunSpec& spec,
                                  const Trajectory& trajectory);

/// A further output grid of one run and the observer that sees it (verify
/// checks the peaks on a fine grid and compares on the deck's).
struct Output {
  double step;
  Observer& observer;
};

/// Integrates the hybrid model from `initial`: mode by mode, each segment
/// from `stepper`, each mode ended by the first guard crossing; the observer
/// sees the output grid and the events, and each of `more` its own grid and
/// the same events. Throws Error if the run makes no progress (events without
/// time passing) or exceeds max_events.
void integrate(const GearModel& model, Stepper& stepper, GearState initial, const RunSpec& spec,
               Observer& observer, const std::vector<Output>& more = {});

/// Which reference solver to use.
enum class SolverKind { exact, adaptive };
SolverKind parse_solver(const std::string& name);

/// Why a scene needs the adaptive solver (empty when the exact one can run).
std::string adaptive_reason(const GearParameters& p);

/// The reference solver for these parameters: the exact one when every mode
/// is linear with constant forcing, else the adaptive one at `tolerance`.
std::unique_ptr<Stepper> make_reference_stepper(const GearParameters& p, double tolerance = 1e-10);

/// The one-call entry point: integrate with the named solver and record; the
/// exact solver falls back to the adaptive one (saying why in solver_note)
/// for a scene whose modes are not linear with constant forcing.
Trajectory simulate(const GearModel& model, const GearState& initial, const RunSpec& spec,
                    SolverKind solver = SolverKind::exact, double tolerance = 1e-10);

}  // namespace gearpatch
