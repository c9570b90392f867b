#pragma once
#include <string>
#include <vector>

#include "model/gear_model.h"
#include "solver/signal.h"
#include "solver/trajectory.h"
#include "verify/circuit_trace.h"

namespace gearpatch::verify {

/// Disagreement of one signal, as fractions of its full scale (1 MU).
struct SignalError {
  Signal signal{};
  double full_scale = 1;
  double max_error = 0;
  double rms_error = 0;
  double time_of_max = 0;  ///< s, real time
  double reference_at_max = 0, circuit_at_max = 0;  ///< physical units
  int jumps = 0;              ///< discontinuities of this signal in the reference
  std::size_t excluded = 0;   ///< samples left out around them
};

/// One impact (flanks meeting) in the reference and, if found, in the circuit.
struct ImpactTime {
  double reference = 0;
  double circuit = -1;  ///< -1: no matching impact in the circuit
};

/// Everything `verify` measures about a circuit run against the reference.
struct Comparison {
  std::vector<SignalError> signals;
  std::vector<ImpactTime> impacts;
  int circuit_impacts = 0;
  double worst_impact_shift = 0;   ///< max |Δt| / run duration
  std::vector<double> restitution; ///< measured per impact in the circuit (frictionless scenes)
  double momentum_drift = -1;      ///< max |Δ(Θp·φ̇p + Θs·φ̇s)| / initial scale, frictionless only
};

/// Compares the circuit trace with the reference trajectory. The circuit is
/// linearly interpolated onto the reference's output grid; impacts are the
/// outward crossings of |Δφ| = ε. Where a signal jumps in the reference (M0
/// when damped flanks meet or part, φ̇s when a self-locking gear catches the
/// load) a circuit can only match it in time, not in value: samples within
/// `jump_window` seconds of a jump are left out of that signal's errors, and
/// the impact times are checked instead.
Comparison compare(const Trajectory& reference, const CircuitTrace& circuit, const GearModel& model,
                   const std::vector<std::pair<Signal, double>>& full_scales, double duration,
                   double jump_window);

}  // namespace gearpatch::verify
