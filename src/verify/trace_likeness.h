#pragma once
#include <string>
#include <vector>

#include "model/gear_model.h"
#include "solver/trajectory.h"
#include "verify/measured_trace.h"

namespace gearpatch::verify {

/// What a recording that fails may be instead: each recorded signal tried
/// against −1 × its reference and against every other signal's reference,
/// and the whole recording against the reference at other time scales. Each
/// hypothesis that brings the rms error (fraction of full scale) within the
/// tolerance and below half of the error as read is a sentence naming the
/// fix; empty when none does.
std::vector<std::string> what_the_trace_looks_like(const MeasuredTrace& measured, const Trajectory& reference,
                                                   const GearModel& model, const circuit::Circuit& circuit,
                                                   double duration, double tolerance);

}  // namespace gearpatch::verify
