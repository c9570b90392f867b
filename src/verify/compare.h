#pragma once
#include <utility>
#include <vector>

#include "model/gear_model.h"
#include "solver/signal.h"
#include "solver/trajectory.h"
#include "verify/circuit_trace.h"
#include "verify/impacts.h"

namespace gearpatch::verify {

/// Disagreement of one signal, as fractions of its full scale (1 MU).
struct SignalError {
  Signal signal{};
  double full_scale = 1;
  /// Amplitude error: the largest distance of a circuit point from the
  /// reference after the best time shift within the time tolerance — the
  /// tube's measure; it passes while this is at most the value tolerance.
  double max_error = 0;
  double pointwise_error = 0;  ///< largest |circuit − reference| at equal times, timing included
  double rms_error = 0;        ///< RMS of the amplitude error over the circuit's points
  double time_of_max = 0;      ///< s, real time of the largest amplitude error
  double reference_at_max = 0, circuit_at_max = 0;  ///< physical units
  std::size_t outside = 0;     ///< circuit points outside the tube
  std::vector<std::pair<double, double>> failed_spans;  ///< s, where the circuit leaves the tube
};

/// The documented default tolerances of the two levels: fractions of each
/// signal's full scale in value and of the run in time.
inline constexpr double ideal_level_tolerance = 0.005;
inline constexpr double hardware_level_tolerance = 0.02;

/// What the comparison needs besides the two runs.
struct CompareSettings {
  std::vector<std::pair<Signal, double>> full_scales;
  double duration = 1;     ///< s, the run
  double tolerance = ideal_level_tolerance;  ///< value tolerance as a fraction of full scale, time tolerance as one of the run
  double grazing_depth = 0;  ///< rad beyond ε that the machine cannot resolve
  double contact_hysteresis = 0;  ///< rad, a recording's resolution in Δφ (impacts.h)
};

/// Everything `verify` measures about a circuit run against the reference.
struct Comparison {
  std::vector<SignalError> signals;
  ImpactMatch impacts;
  double time_tolerance = 0;       ///< s, the tube's half-width in time
  double worst_impact_shift = 0;   ///< max |Δt| of matched impacts / run duration; 1 for a missing one
  std::vector<double> restitution; ///< measured per impact in the circuit (frictionless scenes)
  double momentum_drift = -1;      ///< max |Δ(Θp·φ̇p + Θs·φ̇s)| / initial scale, frictionless only
};

/// The reference signal as a polyline: its samples with each event's state
/// before and after inserted at the event's instant, so a jump is vertical,
/// and each contact's closed-form peak torque (M0) or twist (Δφ).
std::pair<std::vector<double>, std::vector<double>> reference_curve(const Trajectory& reference,
                                                                    const GearModel& model, Signal signal);

/// Compares the circuit trace with the reference trajectory: each signal in a
/// tube (verify/tube.h) of ±tolerance·duration in time and ±tolerance·full
/// scale in value, every circuit point counted; the impacts matched one to
/// one (verify/impacts.h); momentum for frictionless scenes.
Comparison compare(const Trajectory& reference, const CircuitTrace& circuit, const GearModel& model,
                   const CompareSettings& settings);

}  // namespace gearpatch::verify
