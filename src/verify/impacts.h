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
  bool grazing = false;  ///< unmatched, and too shallow for the machine to resolve
  double peak_reference = 0, peak_circuit = 0;  ///< N·m, largest |M0| within the contact
  double restitution_reference = -1, restitution_circuit = -1;  ///< -1: not measured
  bool released = false;  ///< matched and parted in both runs: its peak is complete
  double peak_error = 0;  ///< |peak_circuit − peak_reference| / M0's full scale, matched impacts
  bool matched() const { return reference >= 0 && circuit >= 0; }
};

/// The impacts of both runs, matched one to one by nearest time.
struct ImpactMatch {
  std::vector<Impact> impacts;  ///< in reference order, then the circuit's unmatched
  int circuit_count = 0;
  int missing() const;  ///< reference impacts the circuit lacks, grazing ones not counted
  int extra() const;    ///< circuit impacts the reference lacks, grazing ones not counted
};

/// Finds every contact of the reference (its events) and of the circuit
/// (crossings of |Δφ| = ε) with its depth, peak torque and restitution, and
/// matches them. A contact whose depth is at most `grazing_depth` (the
/// machine's resolution in Δφ, from the comparator offset) that finds no
/// partner is grazing: reported, not a mismatch.
ImpactMatch match_impacts(const Trajectory& reference, const CircuitTrace& circuit, const GearModel& model,
                          double grazing_depth);

}  // namespace gearpatch::verify
