#pragma once
#include <map>
#include <set>
#include <string>
#include <vector>

#include "scaling/scaled_program.h"
#include "scaling/table1.h"

namespace gearpatch {

// The pieces scale_program's two scalings share (scaled_program.cc), and the solved one
// (solved_program.cc). Not part of the module's interface.

/// Table 1's coefficient as α·n at β on the machine; Error (about the scene
/// key to change) when no weight reaches it.
Potentiometer split(const Coefficient& c, double beta, const MachineProfile& machine, const Maxima& m,
                    double half_backlash);

/// The maxima from the simulated peaks: each becomes its peak·(1 + headroom);
/// a signal that stayed at zero keeps its a-priori maximum. `simulated`, if
/// given, receives the keys set from a peak.
Maxima autoscaled(const Maxima& a, const PhysicalPeaks& x, double headroom, std::vector<std::string>& notes,
                  std::set<Maximum>* simulated = nullptr);

/// A warning for each simulated peak beyond its scale, with the fix.
void overload_warnings(const std::map<std::string, double>& peaks, Maxima m, ScaledProgram& program);

/// The self-locking reaction dialled as strong as the machine allows.
void dial_strongest_lock(const MachineProfile& machine, double beta, Table1& t);

/// The solved scaling (scaling_problem.h) into `program`: scales, β, k0, every
/// potentiometer with its extra stages, the peak check; `run` may be null
/// when the peaks are not checked.
void solve_program(const ScalingInput& s, const ScalingOptions& o, const PeakRun* run, ScaledProgram& program);

}  // namespace gearpatch
