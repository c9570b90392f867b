#pragma once
#include <vector>

#include "model/gear_model.h"
#include "solver/trajectory.h"
#include "verify/circuit_trace.h"

namespace gearpatch::verify {

/// One impact (flanks meeting): in the reference, in the circuit, or both
/// when matched. A time of -1 means "not there".
struct Impact {
  double reference = -1, circuit = -1;  ///< s, real time of the outward crossing |Δφ| = ε
  double depth = 0;      ///< rad of penetration beyond ε, the deeper side's
  bool grazing = false;  ///< unmatched, and too shallow for the machine to resolve or changing no signal beyond the tolerance
  double speed_change_p = 0, speed_change_s = 0;  ///< rad/s, φ̇p and φ̇s after the contact less before, the deeper side's
  bool near_end = false; ///< unmatched, within the time tolerance of the run's end: its partner may lie beyond it
  double peak_reference = 0, peak_circuit = 0;  ///< N·m, largest |M0| within the contact
  double restitution_reference = -1, restitution_circuit = -1;  ///< -1: not measured
  bool released = false;  ///< matched and parted in both runs: its peak is complete
  double peak_error = 0;  ///< |peak_circuit − peak_reference| / M0's full scale, matched impacts
  bool matched() const { return reference >= 0 && circuit >= 0; }
  bool counts() const { return !grazing && !near_end; }  ///< unmatched, a mismatch the judge counts
};

/// The impacts of both runs, matched one to one by nearest time.
struct ImpactMatch {
  std::vector<Impact> impacts;  ///< in reference order, then the circuit's unmatched
  int circuit_count = 0;
  int missing() const;  ///< reference impacts the circuit lacks, grazing ones not counted
  int extra() const;    ///< circuit impacts the reference lacks, grazing ones not counted
};

/// What the matching may excuse: the machine's resolution in Δφ, the time
/// tolerance, and a contact that does nothing beyond the value tolerance.
struct MatchLimits {
  double grazing_depth = 0;   ///< rad beyond ε: an unmatched contact this shallow is grazing
  double time_tolerance = 0;  ///< s: the largest shift of a pair the judge accepts
  double run_end = 0;         ///< s: an unmatched contact within time_tolerance of it is not counted
  /// An unmatched contact whose peak |M0| and whose change of φ̇p and of φ̇s
  /// each stay within these (the tolerance times each full scale; 0: none
  /// excused this way) changes no signal a verdict judges: it is grazing.
  double torque_effect = 0, speed_effect_p = 0, speed_effect_s = 0;
  double hysteresis = 0;      ///< rad: a circuit contact ends once |Δφ| < ε − this (a recording's noise)
};

/// Finds every contact of the reference (its events) and of the circuit
/// (crossings of |Δφ| = ε) with its depth, peak torque and restitution, and
/// matches them in order. A contact that finds no partner is grazing when its
/// depth is at most the grazing depth (the machine's resolution in Δφ, from
/// the comparator offset) or when it does nothing beyond the tolerance (peak
/// torque and change of each speed within MatchLimits' effects), one within the time tolerance of the run's end is
/// near_end: reported, not a mismatch.
ImpactMatch match_impacts(const Trajectory& reference, const CircuitTrace& circuit, const GearModel& model,
                          const MatchLimits& limits);

}  // namespace gearpatch::verify
