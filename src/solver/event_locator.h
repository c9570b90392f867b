#pragma once
#include <functional>
#include <optional>
#include <vector>

#include "model/gear_model.h"
#include "solver/segment.h"

namespace gearpatch {

/// The first guard crossing in a segment, or none before the horizon.
struct Crossing {
  double time;
  std::optional<GuardKind> kind;  ///< empty: the horizon was reached
};

/// Walks the segment interval by interval, brackets the first sign change of
/// any guard and refines it on the segment's dense output (TOMS 748) to a
/// few ulps. `on_interval(a, b)` is called for every interval [a, b] that is
/// passed without a crossing, and for [a, t_crossing], so the caller can
/// sample the solution while it is valid.
Crossing locate_first_crossing(Segment& segment, const std::vector<Guard>& guards, double t0,
                               const std::function<void(double, double)>& on_interval);

}  // namespace gearpatch
