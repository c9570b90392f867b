#pragma once
#include <memory>
#include <vector>

#include "solver/segment.h"

namespace gearpatch {

/// The segment of a mode with speed feedback (the motor line, viscous
/// friction), exact to rounding: x(τ) = x0 + (e^{Bτ} − I)·z0 for the
/// augmented system (see LinearModeSegment in the .cc). ExactSegment's
/// reduction to one scalar oscillator needs momentum balance, which
/// feedback breaks.
std::unique_ptr<Segment> make_linear_mode_segment(const GearModel& model, const Mode& mode,
                                                  const GearState& state, double t0,
                                                  double horizon, const std::vector<Guard>& guards);

}  // namespace gearpatch
